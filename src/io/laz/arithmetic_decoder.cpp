// LASzip's arithmetic decoder and models (arithmetic_decoder.h). The constants
// are those of Said's coder as LASzip configures it: 13-bit bit
// probabilities, 15-bit symbol distributions, 32-bit interval.
#include "io/laz/arithmetic_decoder.h"

#include <limits>
#include <stdexcept>

namespace sharpmesh::io::laz {
namespace {

constexpr std::uint32_t kBitLengthShift = 13;
constexpr std::uint32_t kBitMaxCount = 1u << 13;
constexpr std::uint32_t kSymbolLengthShift = 15;
constexpr std::uint32_t kSymbolMaxCount = 1u << 15;
constexpr std::uint32_t kMinLength = 0x01000000u;

}  // namespace

void BitModel::reset() {
  bit_0_count_ = 1;
  bit_count_ = 2;
  bit_0_prob_ = 1u << (kBitLengthShift - 1);
  update_cycle_ = bits_until_update_ = 4;
}

void BitModel::update() {
  if ((bit_count_ += update_cycle_) > kBitMaxCount) {
    bit_count_ = (bit_count_ + 1) >> 1;
    bit_0_count_ = (bit_0_count_ + 1) >> 1;
    if (bit_0_count_ == bit_count_) ++bit_count_;
  }
  const std::uint32_t scale = 0x80000000u / bit_count_;
  bit_0_prob_ = (bit_0_count_ * scale) >> (31 - kBitLengthShift);
  update_cycle_ = (5 * update_cycle_) >> 2;
  if (update_cycle_ > 64) update_cycle_ = 64;
  bits_until_update_ = update_cycle_;
}

SymbolModel::SymbolModel(std::uint32_t symbols) : symbols_(symbols), last_symbol_(symbols - 1) {
  if (symbols < 2 || symbols > (1u << 11)) throw std::logic_error("LAZ symbol model: 2 to 2048 symbols");
  if (symbols > 16) {
    std::uint32_t table_bits = 3;
    while (symbols > (1u << (table_bits + 2))) ++table_bits;
    table_size_ = 1u << table_bits;
    table_shift_ = kSymbolLengthShift - table_bits;
    decoder_table_.assign(table_size_ + 2, 0);
  }
  distribution_.assign(symbols, 0);
  symbol_count_.assign(symbols, 0);
  reset();
}

void SymbolModel::reset() {
  total_count_ = 0;
  update_cycle_ = symbols_;
  std::fill(symbol_count_.begin(), symbol_count_.end(), 1u);
  update();
  symbols_until_update_ = update_cycle_ = (symbols_ + 6) >> 1;
}

void SymbolModel::update() {
  if ((total_count_ += update_cycle_) > kSymbolMaxCount) {
    total_count_ = 0;
    for (std::uint32_t& count : symbol_count_) total_count_ += (count = (count + 1) >> 1);
  }
  const std::uint32_t scale = 0x80000000u / total_count_;
  std::uint32_t sum = 0;
  if (table_size_ == 0) {
    for (std::uint32_t k = 0; k < symbols_; ++k) {
      distribution_[k] = (scale * sum) >> (31 - kSymbolLengthShift);
      sum += symbol_count_[k];
    }
  } else {
    std::uint32_t s = 0;
    for (std::uint32_t k = 0; k < symbols_; ++k) {
      distribution_[k] = (scale * sum) >> (31 - kSymbolLengthShift);
      sum += symbol_count_[k];
      const std::uint32_t w = distribution_[k] >> table_shift_;
      while (s < w) decoder_table_[++s] = k - 1;
    }
    decoder_table_[0] = 0;
    while (s <= table_size_) decoder_table_[++s] = symbols_ - 1;
  }
  update_cycle_ = (5 * update_cycle_) >> 2;
  const std::uint32_t max_cycle = (symbols_ + 6) << 3;
  if (update_cycle_ > max_cycle) update_cycle_ = max_cycle;
  symbols_until_update_ = update_cycle_;
}

ArithmeticDecoder::ArithmeticDecoder(const std::uint8_t* begin, const std::uint8_t* end) : at_(begin), end_(end) {
  for (int i = 0; i < 4; ++i) value_ = (value_ << 8) | next_byte();
}

std::uint8_t ArithmeticDecoder::next_byte() {
  if (at_ == end_) {
    overrun_ = true;
    return 0;
  }
  return *at_++;
}

void ArithmeticDecoder::renormalize() {
  do {
    value_ = (value_ << 8) | next_byte();
  } while ((length_ <<= 8) < kMinLength);
}

std::uint32_t ArithmeticDecoder::decode_bit(BitModel& m) {
  const std::uint32_t x = m.bit_0_prob_ * (length_ >> kBitLengthShift);
  const std::uint32_t bit = value_ >= x;
  if (bit == 0) {
    length_ = x;
    ++m.bit_0_count_;
  } else {
    value_ -= x;
    length_ -= x;
  }
  if (length_ < kMinLength) renormalize();
  if (--m.bits_until_update_ == 0) m.update();
  return bit;
}

std::uint32_t ArithmeticDecoder::decode_symbol(SymbolModel& m) {
  std::uint32_t n, symbol, x, y = length_;
  if (m.table_size_ != 0) {
    const std::uint32_t dv = value_ / (length_ >>= kSymbolLengthShift);
    const std::uint32_t t = dv >> m.table_shift_;
    symbol = m.decoder_table_[t];
    n = m.decoder_table_[t + 1] + 1;
    while (n > symbol + 1) {
      const std::uint32_t k = (symbol + n) >> 1;
      if (m.distribution_[k] > dv) n = k; else symbol = k;
    }
    x = m.distribution_[symbol] * length_;
    if (symbol != m.last_symbol_) y = m.distribution_[symbol + 1] * length_;
  } else {
    x = symbol = 0;
    length_ >>= kSymbolLengthShift;
    n = m.symbols_;
    std::uint32_t k = n >> 1;
    do {
      const std::uint32_t z = length_ * m.distribution_[k];
      if (z > value_) {
        n = k;
        y = z;
      } else {
        symbol = k;
        x = z;
      }
    } while ((k = (symbol + n) >> 1) != symbol);
  }
  value_ -= x;
  length_ = y - x;
  if (length_ < kMinLength) renormalize();
  ++m.symbol_count_[symbol];
  if (--m.symbols_until_update_ == 0) m.update();
  return symbol;
}

std::uint32_t ArithmeticDecoder::read_short() {
  const std::uint32_t symbol = value_ / (length_ >>= 16);
  value_ -= length_ * symbol;
  if (length_ < kMinLength) renormalize();
  return symbol;
}

std::uint32_t ArithmeticDecoder::read_bits(std::uint32_t bits) {
  if (bits > 19) {
    const std::uint32_t low = read_short();
    return (read_bits(bits - 16) << 16) | low;
  }
  const std::uint32_t symbol = value_ / (length_ >>= bits);
  value_ -= length_ * symbol;
  if (length_ < kMinLength) renormalize();
  return symbol;
}

IntegerDecompressor::IntegerDecompressor(std::uint32_t bits, std::uint32_t contexts, std::uint32_t bits_high, std::uint32_t range)
    : bits_high_(bits_high) {
  if (range != 0) {
    corr_range_ = range;
    while (range != 0) {
      range >>= 1;
      ++corr_bits_;
    }
    if (corr_range_ == (1u << (corr_bits_ - 1))) --corr_bits_;
    corr_min_ = -static_cast<std::int32_t>(corr_range_ / 2);
  } else if (bits != 0 && bits < 32) {
    corr_bits_ = bits;
    corr_range_ = 1u << bits;
    corr_min_ = -static_cast<std::int32_t>(corr_range_ / 2);
  } else {
    corr_bits_ = 32;
    corr_range_ = 0;
    corr_min_ = std::numeric_limits<std::int32_t>::min();
  }
  bits_.assign(contexts, SymbolModel(corr_bits_ + 1));
  for (std::uint32_t i = 1; i <= corr_bits_; ++i) correctors_.emplace_back(i <= bits_high_ ? 1u << i : 1u << bits_high_);
}

void IntegerDecompressor::reset() {
  for (SymbolModel& m : bits_) m.reset();
  corrector0_.reset();
  for (SymbolModel& m : correctors_) m.reset();
}

std::int32_t IntegerDecompressor::read_corrector(ArithmeticDecoder& decoder, SymbolModel& bits_model) {
  k_ = decoder.decode_symbol(bits_model);
  if (k_ == 0) return static_cast<std::int32_t>(decoder.decode_bit(corrector0_));
  if (k_ >= 32) return corr_min_;
  std::uint32_t c;
  if (k_ <= bits_high_) {
    c = decoder.decode_symbol(correctors_[k_ - 1]);
  } else {
    const std::uint32_t low_bits = k_ - bits_high_;
    c = decoder.decode_symbol(correctors_[k_ - 1]);
    c = (c << low_bits) | decoder.read_bits(low_bits);
  }
  // c in [0, 2^k) stands for [-(2^k - 1), -2^(k-1)] and [2^(k-1) + 1, 2^k]; unsigned arithmetic wraps as LASzip's does.
  if (c >= (1u << (k_ - 1))) c += 1u;
  else c -= static_cast<std::uint32_t>((std::uint64_t{1} << k_) - 1);
  return static_cast<std::int32_t>(c);
}

std::int32_t IntegerDecompressor::decompress(ArithmeticDecoder& decoder, std::int32_t prediction, std::uint32_t context) {
  std::int32_t real = static_cast<std::int32_t>(static_cast<std::uint32_t>(prediction) +
                                                static_cast<std::uint32_t>(read_corrector(decoder, bits_[context])));
  if (real < 0) real = static_cast<std::int32_t>(static_cast<std::uint32_t>(real) + corr_range_);
  else if (static_cast<std::uint32_t>(real) >= corr_range_) real = static_cast<std::int32_t>(static_cast<std::uint32_t>(real) - corr_range_);
  return real;
}

}  // namespace sharpmesh::io::laz
