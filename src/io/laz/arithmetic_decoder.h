// The entropy decoder of LASzip (Isenburg, "LASzip: lossless compression of
// LiDAR data", 2013): Said's adaptive arithmetic coder ("Introduction to
// arithmetic coding: theory and practice", 2004) with its adaptive bit and
// symbol models, and the integer corrector coding built on them. Everything
// here is bit-exact with LASzip's compressor: models adapt after the same
// counts and renormalise the same way, or the stream would not decode.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace sharpmesh::io::laz {

/// An adaptive model of one binary decision.
class BitModel {
 public:
  BitModel() { reset(); }
  void reset();

 private:
  friend class ArithmeticDecoder;
  void update();
  std::uint32_t update_cycle_ = 0, bits_until_update_ = 0;
  std::uint32_t bit_0_prob_ = 0, bit_0_count_ = 0, bit_count_ = 0;
};

/// An adaptive model of a symbol in [0, symbols), with the decoder's lookup
/// table for alphabets larger than 16 symbols.
class SymbolModel {
 public:
  explicit SymbolModel(std::uint32_t symbols);
  void reset();

 private:
  friend class ArithmeticDecoder;
  void update();
  std::uint32_t symbols_, last_symbol_;
  std::uint32_t table_size_ = 0, table_shift_ = 0;
  std::uint32_t total_count_ = 0, update_cycle_ = 0, symbols_until_update_ = 0;
  std::vector<std::uint32_t> distribution_, symbol_count_, decoder_table_;
};

/// Decodes from a byte range. Reading past its end yields zero bytes and
/// sets overrun(), which the caller turns into an error naming the file.
class ArithmeticDecoder {
 public:
  ArithmeticDecoder(const std::uint8_t* begin, const std::uint8_t* end);
  std::uint32_t decode_bit(BitModel& model);
  std::uint32_t decode_symbol(SymbolModel& model);
  /// Raw bits, not modelled (1 to 32).
  std::uint32_t read_bits(std::uint32_t bits);
  std::uint32_t read_int() { const std::uint32_t low = read_short(); return (read_short() << 16) | low; }
  bool overrun() const { return overrun_; }

 private:
  std::uint32_t read_short();
  std::uint8_t next_byte();
  void renormalize();
  const std::uint8_t* at_;
  const std::uint8_t* end_;
  std::uint32_t value_ = 0, length_ = 0xFFFFFFFFu;
  bool overrun_ = false;
};

/// LASzip's integer decompressor: a value is its prediction plus a corrector
/// coded as its bit length k (one symbol model per context) and then its
/// k bits (modelled up to `bits_high`, raw above), wrapped into the range.
class IntegerDecompressor {
 public:
  IntegerDecompressor(std::uint32_t bits = 16, std::uint32_t contexts = 1, std::uint32_t bits_high = 8, std::uint32_t range = 0);
  /// Resets the models (at the start of each chunk).
  void reset();
  std::int32_t decompress(ArithmeticDecoder& decoder, std::int32_t prediction, std::uint32_t context = 0);
  /// The bit length k of the last corrector, a context for the next coordinate.
  std::uint32_t k() const { return k_; }

 private:
  std::int32_t read_corrector(ArithmeticDecoder& decoder, SymbolModel& bits_model);
  std::uint32_t corr_bits_ = 0, corr_range_ = 0, bits_high_;
  std::int32_t corr_min_ = 0;
  std::uint32_t k_ = 0;
  std::vector<SymbolModel> bits_;
  BitModel corrector0_;
  std::vector<SymbolModel> correctors_;  ///< index k - 1 for k = 1 .. corr_bits
};

}  // namespace sharpmesh::io::laz
