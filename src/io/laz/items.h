// Decoders of LASzip's version-2 items (Isenburg 2013, section 3): each
// predicts a field of the point record from the previous point and decodes
// the difference. A chunk starts with a raw record, which seeds them.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <vector>

#include "io/laz/arithmetic_decoder.h"

namespace sharpmesh::io::laz {

/// Median of the last five values, updated in LASzip's order.
class StreamingMedian5 {
 public:
  void reset() { values_ = {0, 0, 0, 0, 0}; high_ = true; }
  void add(std::int32_t v);
  std::int32_t get() const { return values_[2]; }

 private:
  std::array<std::int32_t, 5> values_{0, 0, 0, 0, 0};
  bool high_ = true;
};

/// The 20 bytes of LAS point formats 0-5: coordinates, intensity, returns,
/// flags, class, scan angle, user data, point source.
class Point10Decoder {
 public:
  Point10Decoder();
  void reset(const std::uint8_t* first);
  void decode(ArithmeticDecoder& decoder, std::uint8_t* out);

 private:
  SymbolModel& lazy(std::array<std::unique_ptr<SymbolModel>, 256>& models, std::uint8_t context);
  std::array<std::uint8_t, 20> last_{};
  std::array<std::uint16_t, 16> last_intensity_{};
  std::array<StreamingMedian5, 16> x_diff_median_, y_diff_median_;
  std::array<std::int32_t, 8> last_height_{};
  SymbolModel changed_values_{64};
  IntegerDecompressor intensity_{16, 4};
  std::array<SymbolModel, 2> scan_angle_rank_{SymbolModel(256), SymbolModel(256)};
  IntegerDecompressor point_source_{16};
  std::array<std::unique_ptr<SymbolModel>, 256> bit_byte_, classification_, user_data_;
  IntegerDecompressor dx_{32, 2}, dy_{32, 22}, z_{32, 20};
};

/// The 8-byte GPS time: up to four interleaved sequences of regular steps.
class GpsTimeDecoder {
 public:
  void reset(const std::uint8_t* first);
  void decode(ArithmeticDecoder& decoder, std::uint8_t* out);

 private:
  void decode_time(ArithmeticDecoder& decoder);
  SymbolModel multi_{516};
  SymbolModel zero_diff_{6};
  IntegerDecompressor diff_{32, 9};
  std::uint32_t last_ = 0, next_ = 0;
  std::array<std::int64_t, 4> last_time_{};
  std::array<std::int32_t, 4> last_diff_{};
  std::array<std::int32_t, 4> extreme_counter_{};
};

/// The 6-byte RGB of formats 2, 3 and 5: byte differences, green and blue
/// predicted from red's change.
class RgbDecoder {
 public:
  void reset(const std::uint8_t* first);
  void decode(ArithmeticDecoder& decoder, std::uint8_t* out);

 private:
  std::array<std::uint16_t, 3> last_{};
  SymbolModel byte_used_{128};
  std::array<SymbolModel, 6> diff_{SymbolModel(256), SymbolModel(256), SymbolModel(256), SymbolModel(256), SymbolModel(256),
                                   SymbolModel(256)};
};

/// Extra bytes after the standard record: each byte's difference.
class ExtraBytesDecoder {
 public:
  explicit ExtraBytesDecoder(std::size_t count);
  void reset(const std::uint8_t* first);
  void decode(ArithmeticDecoder& decoder, std::uint8_t* out);

 private:
  std::vector<std::uint8_t> last_;
  std::vector<SymbolModel> models_;
};

}  // namespace sharpmesh::io::laz
