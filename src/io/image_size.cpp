#include "io/image_size.h"

#include <opencv2/imgcodecs.hpp>

#include "io/formats.h"
#include "sharpmesh/errors.h"

namespace sharpmesh::io {

std::pair<int, int> image_size(const std::string& path) {
  (void)read_file(path);  // a clear message for missing or unreadable files
  const cv::Mat image = cv::imread(path, cv::IMREAD_UNCHANGED);
  if (image.empty()) throw InvalidInput(path + ": not an image OpenCV can decode");
  return {image.cols, image.rows};
}

}  // namespace sharpmesh::io
