#include "curve_plot.h"

#include <algorithm>
#include <cmath>

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "sharpmesh/errors.h"
#include "sharpmesh/io.h"

namespace sharpmesh::cli {
namespace {

const cv::Scalar kColors[] = {{200, 80, 30}, {40, 40, 220}, {40, 160, 40}, {160, 40, 160}, {20, 150, 220}, {100, 100, 100}};

void text(cv::Mat& image, const std::string& s, cv::Point at, double scale = 0.45, cv::Scalar color = {0, 0, 0}) {
  cv::putText(image, s, at, cv::FONT_HERSHEY_SIMPLEX, scale, color, 1, cv::LINE_AA);
}

}  // namespace

void write_curve_plot(const std::string& path, const std::vector<double>& x, const std::vector<std::string>& x_labels,
                      const std::string& x_title, const std::vector<CurvePanel>& panels) {
  const int panel_w = 480, panel_h = 380, left = 60, right = 20, top = 40, bottom = 60;
  cv::Mat image(panel_h, panel_w * static_cast<int>(panels.size()), CV_8UC3, cv::Scalar(255, 255, 255));
  const double lx0 = std::log10(x.front()), lx1 = std::log10(x.back());
  for (std::size_t p = 0; p < panels.size(); ++p) {
    const int ox = static_cast<int>(p) * panel_w;
    const int x0 = ox + left, x1 = ox + panel_w - right, y0 = panel_h - bottom, y1 = top;
    auto px = [&](double v) { return x0 + static_cast<int>(std::lround((std::log10(v) - lx0) / std::max(1e-12, lx1 - lx0) * (x1 - x0))); };
    auto py = [&](double f) { return y0 - static_cast<int>(std::lround(f * (y0 - y1))); };
    for (int k = 0; k <= 10; k += 2) {
      cv::line(image, {x0, py(k / 10.0)}, {x1, py(k / 10.0)}, {225, 225, 225});
      text(image, std::to_string(k * 10) + "%", {ox + 12, py(k / 10.0) + 5}, 0.4);
    }
    for (std::size_t i = 0; i < x.size(); ++i) {
      cv::line(image, {px(x[i]), y0}, {px(x[i]), y1}, {235, 235, 235});
      text(image, x_labels[i], {px(x[i]) - 16, y0 + 18}, 0.35);
    }
    cv::rectangle(image, {x0, y1}, {x1, y0}, {0, 0, 0});
    text(image, panels[p].title, {x0, y1 - 14}, 0.55);
    text(image, x_title, {x0 + 40, panel_h - 14}, 0.4);
    int legend_width = 0;
    for (const Curve& curve : panels[p].curves) {
      int baseline = 0;
      legend_width = std::max(legend_width, cv::getTextSize(curve.label, cv::FONT_HERSHEY_SIMPLEX, 0.4, 1, &baseline).width);
    }
    const int lx = std::max(x0 + 5, x1 - legend_width - 35);
    for (std::size_t c = 0; c < panels[p].curves.size(); ++c) {
      const Curve& curve = panels[p].curves[c];
      const cv::Scalar color = kColors[c % (sizeof kColors / sizeof kColors[0])];
      for (std::size_t i = 0; i + 1 < std::min(x.size(), curve.y.size()); ++i)
        cv::line(image, {px(x[i]), py(curve.y[i])}, {px(x[i + 1]), py(curve.y[i + 1])}, color, 2, cv::LINE_AA);
      for (std::size_t i = 0; i < std::min(x.size(), curve.y.size()); ++i) cv::circle(image, {px(x[i]), py(curve.y[i])}, 3, color, -1, cv::LINE_AA);
      const int ly = y0 - 12 - 18 * static_cast<int>(panels[p].curves.size() - 1 - c);
      cv::line(image, {lx, ly - 4}, {lx + 20, ly - 4}, color, 2);
      text(image, curve.label, {lx + 25, ly}, 0.4);
    }
  }
  std::vector<unsigned char> png;
  if (!cv::imencode(".png", image, png)) throw InvalidInput("cannot encode the plot " + path);
  write_text_file(path, std::string(png.begin(), png.end()));
}

}  // namespace sharpmesh::cli
