#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <fstream>

#include <sys/stat.h>

#include "io/formats.h"
#include "sharpmesh/errors.h"

namespace sharpmesh::io {

std::string extension(const std::string& path) {
  const std::size_t slash = path.find_last_of('/');
  const std::size_t dot = path.find_last_of('.');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return "";
  std::string ext = path.substr(dot + 1);
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return ext;
}

std::string read_file(const std::string& path) {
  struct stat info {};
  if (::stat(path.c_str(), &info) != 0) throw InvalidInput("cannot open '" + path + "': " + std::strerror(errno));
  if (S_ISDIR(info.st_mode)) throw InvalidInput("cannot open '" + path + "': is a directory");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InvalidInput("cannot open '" + path + "': " + std::strerror(errno));
  std::string data;
  in.seekg(0, std::ios::end);
  const std::streamoff size = in.tellg();
  if (size < 0) throw InvalidInput("cannot read '" + path + "'");
  data.resize(static_cast<std::size_t>(size));
  in.seekg(0);
  if (size > 0 && !in.read(data.data(), size)) throw InvalidInput("cannot read '" + path + "': " + std::strerror(errno));
  return data;
}

void check_finite(const Vec3& p, const std::string& path, const std::string& where) {
  if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2]))
    throw InvalidInput(path + ": " + where + ": non-finite coordinate (NaN or infinity)");
}

}  // namespace sharpmesh::io
