// Contours of the images (thesis 6.3.2): Canny edges (Gaussian blur of
// sigma, Sobel gradients, non-maxima suppression, hysteresis) by OpenCV, and
// the affine-gap score of a segment over them (Needleman & Wunsch 1970).
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <vector>

#include "sharpmesh/errors.h"
#include "sharpmesh/stereo_reconstruct.h"

namespace sharpmesh {

void DepthMapOptions::check() const {
  if (!(canny_sigma >= 0 && canny_sigma <= 50)) throw InvalidArgument("the Canny sigma must be in [0, 50] pixels");
  if (!(canny_low > 0 && canny_high >= canny_low))
    throw InvalidArgument("the Canny thresholds must satisfy 0 < low <= high");
  if (!(contour_distance >= 0 && contour_distance <= 50)) throw InvalidArgument("the contour distance must be in [0, 50] pixels");
  if (!(gap_open > 0 && gap_extend > 0)) throw InvalidArgument("the gap penalties must be positive");
  if (!(overlap_angle >= 0 && overlap_angle < 90)) throw InvalidArgument("the overlap angle must be in [0, 90) degrees");
}

std::vector<std::uint8_t> detect_contours(const std::vector<std::uint8_t>& grey, int width, int height,
                                          const DepthMapOptions& options) {
  if (width <= 0 || height <= 0 || grey.size() != static_cast<std::size_t>(width) * height)
    throw InvalidInput("contour detection: the image buffer does not match its size");
  const cv::Mat image(height, width, CV_8UC1, const_cast<std::uint8_t*>(grey.data()));
  cv::Mat blurred;
  if (options.canny_sigma > 0)
    cv::GaussianBlur(image, blurred, cv::Size(0, 0), options.canny_sigma);
  else
    blurred = image;
  // 3x3 Sobel derivatives and the L2 gradient magnitude M = sqrt(Sx^2 + Sy^2),
  // as in 6.3.2; computed once, for the contrast below and for Canny.
  cv::Mat dx, dy;
  cv::Sobel(blurred, dx, CV_16S, 1, 0, 3, 1, 0, cv::BORDER_REPLICATE);
  cv::Sobel(blurred, dy, CV_16S, 0, 1, 3, 1, 0, cv::BORDER_REPLICATE);
  double scale = 1.0;
  if (options.canny_adaptive) {
    // The thresholds hold for an image whose 99th-percentile gradient
    // magnitude (its strong edges) is kReferenceContrast, as in the generated
    // scenes (95-130); others get them scaled in proportion.
    constexpr double kReferenceContrast = 100.0;
    cv::Mat fx, fy, magnitude;
    dx.convertTo(fx, CV_32F);
    dy.convertTo(fy, CV_32F);
    cv::magnitude(fx, fy, magnitude);
    std::vector<float> values(magnitude.begin<float>(), magnitude.end<float>());
    auto percentile = values.begin() + static_cast<std::ptrdiff_t>(0.99 * static_cast<double>(values.size() - 1));
    std::nth_element(values.begin(), percentile, values.end());
    scale = std::clamp(static_cast<double>(*percentile) / kReferenceContrast, 0.05, 20.0);
  }
  cv::Mat edges;
  cv::Canny(dx, dy, edges, scale * options.canny_low, scale * options.canny_high, true);
  return std::vector<std::uint8_t>(edges.begin<std::uint8_t>(), edges.end<std::uint8_t>());
}

double contour_edge_score(const std::vector<std::uint8_t>& contours, int width, int height, const Vec2& a,
                          const Vec2& b, double gap_open, double gap_extend) {
  // A pixel "on the contour" is an edge pixel or one of its 8 neighbours: the
  // tracks' projections carry sub-pixel noise and Canny's lines are one pixel wide.
  const auto on_contour = [&](int col, int row) {
    for (int dr = -1; dr <= 1; ++dr)
      for (int dc = -1; dc <= 1; ++dc) {
        const int r = row + dr, c = col + dc;
        if (r >= 0 && r < height && c >= 0 && c < width && contours[static_cast<std::size_t>(r) * width + c]) return true;
      }
    return false;
  };
  const double length = std::hypot(b[0] - a[0], b[1] - a[1]);
  const int steps = std::max(1, static_cast<int>(std::ceil(length)));
  double score = 0;
  int gap = 0;
  const auto close_gap = [&] {
    if (gap > 0) score -= gap_open + (gap - 1) * gap_extend;
    gap = 0;
  };
  int last_col = INT32_MIN, last_row = INT32_MIN;
  for (int s = 0; s <= steps; ++s) {
    const double t = static_cast<double>(s) / steps;
    // COLMAP pixel convention: pixel (col, row) spans [col, col + 1) x [row, row + 1).
    const int col = static_cast<int>(std::floor(a[0] + t * (b[0] - a[0])));
    const int row = static_cast<int>(std::floor(a[1] + t * (b[1] - a[1])));
    if (col == last_col && row == last_row) continue;
    last_col = col;
    last_row = row;
    if (on_contour(col, row)) {
      close_gap();
      score += 1;
    } else {
      ++gap;
    }
  }
  close_gap();
  return score;
}

}  // namespace sharpmesh
