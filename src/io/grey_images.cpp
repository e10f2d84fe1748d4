// The images of a stereo model, read as 8-bit grey by OpenCV, in view order.
#include <opencv2/imgcodecs.hpp>

#include "io/formats.h"
#include "sharpmesh/errors.h"
#include "sharpmesh/stereo_reconstruct.h"

namespace sharpmesh {

std::vector<GreyImage> read_grey_images(const StereoModel& model, const std::string& folder, const Progress& progress) {
  std::vector<GreyImage> images;
  images.reserve(model.cameras.size());
  for (std::size_t v = 0; v < model.cameras.size(); ++v) {
    report_progress(progress, "reading images", static_cast<double>(v) / model.cameras.size());
    const Camera& camera = model.cameras[v];
    const std::string path = folder + "/" + camera.image_name;
    (void)io::read_file(path);  // a clear message for missing or unreadable files
    const cv::Mat image = cv::imread(path, cv::IMREAD_GRAYSCALE);
    if (image.empty()) throw InvalidInput(path + ": not an image OpenCV can decode");
    if (image.cols != camera.width || image.rows != camera.height)
      throw InvalidInput(path + ": the image is " + format_number(image.cols) + "x" + format_number(image.rows) +
                         " but its camera says " + format_number(camera.width) + "x" + format_number(camera.height));
    GreyImage grey;
    grey.width = image.cols;
    grey.height = image.rows;
    grey.pixels.assign(image.begin<std::uint8_t>(), image.end<std::uint8_t>());
    images.push_back(std::move(grey));
  }
  report_progress(progress, "reading images", 1.0);
  return images;
}

}  // namespace sharpmesh
