// Bilinear sampling of a grey image at a pixel position in COLMAP's
// convention (pixel centres at half-integers), shared by the photo-consistency
// tests of tracks and of soup triangles.
#pragma once

#include <algorithm>

#include "sharpmesh/stereo_reconstruct.h"

namespace sharpmesh::detail {

/// Intensity at `pixel`; false when the position is outside the pixel centres' hull.
inline bool sample_bilinear(const GreyImage& image, const Vec2& pixel, double& value) {
  const double x = pixel[0] - 0.5, y = pixel[1] - 0.5;
  if (!(x >= 0 && y >= 0 && x <= image.width - 1 && y <= image.height - 1)) return false;
  const int x0 = std::min(static_cast<int>(x), std::max(image.width - 2, 0));
  const int y0 = std::min(static_cast<int>(y), std::max(image.height - 2, 0));
  const int x1 = std::min(x0 + 1, image.width - 1), y1 = std::min(y0 + 1, image.height - 1);
  const double fx = x - x0, fy = y - y0;
  const auto at = [&](int c, int r) { return static_cast<double>(image.pixels[static_cast<std::size_t>(r) * image.width + c]); };
  value = (1 - fy) * ((1 - fx) * at(x0, y0) + fx * at(x1, y0)) + fy * ((1 - fx) * at(x0, y1) + fx * at(x1, y1));
  return true;
}

}  // namespace sharpmesh::detail
