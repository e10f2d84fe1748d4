// Calibrated cameras and tracks: the input of the multi-view stereo pipeline
// (thesis 3.2 and 6.3). A track is a 3D point with the list of views that
// observed it. Plain C++; the readers are in stereo_io.h.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "sharpmesh/types.h"

namespace sharpmesh {

using Vec2 = std::array<double, 2>;
/// Row-major 3x3 matrix.
using Mat3 = std::array<std::array<double, 3>, 3>;

Mat3 identity3();
Mat3 transpose(const Mat3& m);
Mat3 operator*(const Mat3& a, const Mat3& b);
Vec3 operator*(const Mat3& m, const Vec3& v);
/// Rotation of a unit quaternion given scalar first (qw, qx, qy, qz), as COLMAP and NVM write it.
/// The quaternion is normalised; a zero quaternion throws InvalidInput.
Mat3 rotation_from_quaternion(double qw, double qx, double qy, double qz);
/// Inverse of rotation_from_quaternion, with qw >= 0.
std::array<double, 4> quaternion_from_rotation(const Mat3& r);

/// A pinhole camera with undistorted images (thesis 3.2: P = A [R t]).
/// Pixel coordinates follow COLMAP: x right, y down, the image spans
/// [0, width] x [0, height], so the top-left pixel's centre is (0.5, 0.5).
struct Camera {
  std::string image_name;  ///< file name relative to the image folder
  int width = 0;
  int height = 0;
  double fx = 0, fy = 0;  ///< focal lengths in pixels
  double cx = 0, cy = 0;  ///< principal point in pixels
  Mat3 rotation = identity3();  ///< world to camera: x_cam = R x + t
  Vec3 translation{0, 0, 0};

  /// Camera centre in world coordinates, -R^T t.
  Vec3 center() const;
  Vec3 to_camera(const Vec3& world) const;
  /// Depth of a world point along the optical axis (camera z).
  double depth(const Vec3& world) const { return to_camera(world)[2]; }
  /// Projects a world point; false (pixel untouched) when it is not in front of the camera.
  bool project(const Vec3& world, Vec2& pixel) const;
  /// True when the pixel lies inside the image rectangle.
  bool in_image(const Vec2& pixel) const;
  /// Unit direction, in world coordinates, of the ray from the centre through a pixel.
  Vec3 viewing_ray(const Vec2& pixel) const;
  /// The world point on the ray through `pixel` at the given depth.
  Vec3 unproject(const Vec2& pixel, double depth) const;
  /// Throws InvalidInput naming `where` when the camera is unusable
  /// (non-positive size or focal length, non-finite values, R not a rotation).
  void validate(const std::string& where) const;
};

/// A 3D point with the views that observed it (thesis 6.3: "each input track
/// stores its 3D point location as well as the list of camera locations from
/// which it was observed").
struct Track {
  Vec3 position{0, 0, 0};
  std::vector<std::uint32_t> views;  ///< indices into StereoModel::cameras, distinct
  std::vector<Vec2> pixels;          ///< empty, or the observation in each view
  Rgb color{128, 128, 128};
};

/// Cameras and tracks, in the order of the files they came from.
struct StereoModel {
  std::vector<Camera> cameras;
  std::vector<Track> tracks;
  /// The tracks are fused depth-map points (COLMAP's fused.ply with its .vis):
  /// each one's views are the depth maps that agree on it, not the views
  /// it was triangulated from.
  bool dense_points = false;
  /// Throws InvalidInput naming `where` when a track refers to a missing view,
  /// has a non-finite position, or pixels that do not match its views.
  void validate(const std::string& where) const;
};

/// Reprojection residuals of the tracks' recorded pixels, in pixels.
struct ReprojectionStats {
  std::size_t observations = 0;
  double mean = 0;
  double rms = 0;
  double max = 0;
};
ReprojectionStats reprojection_error(const StereoModel& model);

}  // namespace sharpmesh
