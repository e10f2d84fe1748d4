// Image dimensions, for the camera formats that do not store them (Bundler, NVM).
#pragma once

#include <string>
#include <utility>

namespace sharpmesh::io {

/// (width, height) of an image file; InvalidInput naming the file when it cannot be decoded.
std::pair<int, int> image_size(const std::string& path);

}  // namespace sharpmesh::io
