// Bounded little-endian reading and writing of binary records, for the
// binary formats (COLMAP .bin, .vis). Reading past the end throws
// InvalidInput naming the file and what was being read.
#pragma once

#include <cstdint>
#include <cstring>
#include <string>
#include <string_view>
#include <type_traits>

#include "sharpmesh/errors.h"

namespace sharpmesh::io {

class BinaryReader {
 public:
  BinaryReader(std::string_view data, std::string path) : data_(data), path_(std::move(path)) {}

  template <class T>
  T read(const char* what) {
    static_assert(std::is_trivially_copyable_v<T>);
    if (data_.size() - pos_ < sizeof(T))
      throw InvalidInput(path_ + ": truncated at byte " + format_number(pos_) + " while reading " + what);
    T value;
    std::memcpy(&value, data_.data() + pos_, sizeof(T));
    pos_ += sizeof(T);
    return value;
  }
  /// A NUL-terminated string.
  std::string read_string(const char* what) {
    const std::size_t end = data_.find('\0', pos_);
    if (end == std::string_view::npos)
      throw InvalidInput(path_ + ": truncated at byte " + format_number(pos_) + " while reading " + what);
    std::string s(data_.substr(pos_, end - pos_));
    pos_ = end + 1;
    return s;
  }
  /// Throws unless `count` records of at least `record_size` bytes can still follow
  /// (guards allocations against absurd counts in corrupt headers).
  void expect(std::uint64_t count, std::size_t record_size, const char* what) const {
    if (record_size > 0 && count > (data_.size() - pos_) / record_size)
      throw InvalidInput(path_ + ": " + what + " count " + format_number(count) + " exceeds the file size (truncated or corrupt)");
  }
  bool at_end() const { return pos_ == data_.size(); }
  std::size_t position() const { return pos_; }
  const std::string& path() const { return path_; }

 private:
  std::string_view data_;
  std::string path_;
  std::size_t pos_ = 0;
};

class BinaryWriter {
 public:
  template <class T>
  void write(T value) {
    static_assert(std::is_trivially_copyable_v<T>);
    const char* p = reinterpret_cast<const char*>(&value);
    bytes_.append(p, sizeof(T));
  }
  void write_string(const std::string& s) { bytes_.append(s.c_str(), s.size() + 1); }
  const std::string& bytes() const { return bytes_; }

 private:
  std::string bytes_;
};

}  // namespace sharpmesh::io
