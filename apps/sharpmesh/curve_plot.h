// PNG plots of cumulative error curves (several methods on shared axes),
// drawn with OpenCV so the tool needs no plotting package.
#pragma once

#include <string>
#include <vector>

namespace sharpmesh::cli {

struct Curve {
  std::string label;
  std::vector<double> y;  ///< fractions in [0, 1], one per x
};

struct CurvePanel {
  std::string title;
  std::vector<Curve> curves;
};

/// Side-by-side panels sharing the x values (drawn on a log scale, labelled
/// with `x_labels`). Written atomically.
void write_curve_plot(const std::string& path, const std::vector<double>& x, const std::vector<std::string>& x_labels,
                      const std::string& x_title, const std::vector<CurvePanel>& panels);

}  // namespace sharpmesh::cli
