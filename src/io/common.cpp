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

std::ifstream open_file(const std::string& path) {
  struct stat info {};
  if (::stat(path.c_str(), &info) != 0) throw InvalidInput("cannot open '" + path + "': " + std::strerror(errno));
  if (S_ISDIR(info.st_mode)) throw InvalidInput("cannot open '" + path + "': is a directory");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InvalidInput("cannot open '" + path + "': " + std::strerror(errno));
  return in;
}

LineBlocks::LineBlocks(const std::string& path, std::uint64_t offset) : path_(path), in_(open_file(path)) {
  in_.seekg(static_cast<std::streamoff>(offset));
}

bool LineBlocks::next(std::string_view& text) {
  constexpr std::size_t kRead = std::size_t(4) << 20;
  buffer_.erase(0, used_);  // the partial line left over from the last block
  used_ = 0;
  for (;;) {
    // The carry holds no newline: any one found ends a run of new whole lines.
    const std::size_t newline = buffer_.find_last_of('\n');
    if (newline != std::string::npos) {
      used_ = newline + 1;
      break;
    }
    if (at_end_) {
      used_ = buffer_.size();
      break;
    }
    const std::size_t old_size = buffer_.size();
    buffer_.resize(old_size + kRead);
    in_.read(buffer_.data() + old_size, static_cast<std::streamsize>(kRead));
    const auto got = static_cast<std::size_t>(in_.gcount());
    buffer_.resize(old_size + got);
    if (got < kRead) {
      if (in_.bad()) throw InvalidInput("cannot read '" + path_ + "': " + std::strerror(errno));
      at_end_ = true;
    }
  }
  text = std::string_view(buffer_.data(), used_);
  return used_ > 0;
}

std::string read_file(const std::string& path) {
  std::ifstream in = open_file(path);
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
