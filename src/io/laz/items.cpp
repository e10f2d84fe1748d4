// LASzip's version-2 item decoders (items.h), field by field as the
// compressor predicts them (Isenburg 2013, 3.1-3.4).
#include "io/laz/items.h"

#include <algorithm>
#include <cstring>

namespace sharpmesh::io::laz {
namespace {

// Contexts by return number r and number of returns n (rows n, columns r):
// single returns, first of many, last of many and intermediate returns get
// their own predictions; the "impossible" pairs some writers produce still
// map to distinct contexts.
constexpr std::uint8_t kReturnMap[8][8] = {
    {15, 14, 13, 12, 11, 10, 9, 8}, {14, 0, 1, 3, 6, 10, 10, 9},   {13, 1, 2, 4, 7, 11, 11, 10},  {12, 3, 4, 5, 8, 12, 12, 11},
    {11, 6, 7, 8, 9, 13, 13, 12},   {10, 10, 11, 12, 13, 14, 14, 13}, {9, 10, 11, 12, 13, 14, 15, 14}, {8, 9, 10, 11, 12, 13, 14, 15}};
// Elevation contexts: how far the return lies from the first one.
constexpr std::uint8_t kReturnLevel[8][8] = {{0, 1, 2, 3, 4, 5, 6, 7}, {1, 0, 1, 2, 3, 4, 5, 6}, {2, 1, 0, 1, 2, 3, 4, 5},
                                            {3, 2, 1, 0, 1, 2, 3, 4}, {4, 3, 2, 1, 0, 1, 2, 3}, {5, 4, 3, 2, 1, 0, 1, 2},
                                            {6, 5, 4, 3, 2, 1, 0, 1}, {7, 6, 5, 4, 3, 2, 1, 0}};

// The GPS-time codes: multiples of the last step up to kMulti, down to kMultiMinus, unchanged, a full new time, a switch of sequence.
constexpr std::int32_t kMulti = 500;
constexpr std::int32_t kMultiMinus = -10;
constexpr std::uint32_t kMultiUnchanged = kMulti - kMultiMinus + 1;
constexpr std::uint32_t kMultiCodeFull = kMulti - kMultiMinus + 2;

template <class T>
T load(const std::uint8_t* p) {
  T v;
  std::memcpy(&v, p, sizeof v);
  return v;
}
template <class T>
void store(std::uint8_t* p, T v) {
  std::memcpy(p, &v, sizeof v);
}
std::int32_t wrapping_add(std::int32_t a, std::int32_t b) {
  return static_cast<std::int32_t>(static_cast<std::uint32_t>(a) + static_cast<std::uint32_t>(b));
}
std::int32_t wrapping_multiply(std::int32_t a, std::int32_t b) {
  return static_cast<std::int32_t>(static_cast<std::uint32_t>(static_cast<std::int64_t>(a) * b));
}
// GPS times are 64-bit patterns the coder adds to; a corrupt stream may overflow them, which wraps.
void advance_time(std::int64_t& time, std::int64_t diff) {
  time = static_cast<std::int64_t>(static_cast<std::uint64_t>(time) + static_cast<std::uint64_t>(diff));
}
std::uint8_t clamp_byte(int v) { return static_cast<std::uint8_t>(std::clamp(v, 0, 255)); }

}  // namespace

void StreamingMedian5::add(std::int32_t v) {
  auto& x = values_;
  if (high_) {
    if (v < x[2]) {
      x[4] = x[3];
      x[3] = x[2];
      if (v < x[0]) {
        x[2] = x[1];
        x[1] = x[0];
        x[0] = v;
      } else if (v < x[1]) {
        x[2] = x[1];
        x[1] = v;
      } else {
        x[2] = v;
      }
    } else {
      if (v < x[3]) {
        x[4] = x[3];
        x[3] = v;
      } else {
        x[4] = v;
      }
      high_ = false;
    }
  } else {
    if (x[2] < v) {
      x[0] = x[1];
      x[1] = x[2];
      if (x[4] < v) {
        x[2] = x[3];
        x[3] = x[4];
        x[4] = v;
      } else if (x[3] < v) {
        x[2] = x[3];
        x[3] = v;
      } else {
        x[2] = v;
      }
    } else {
      if (x[1] < v) {
        x[0] = x[1];
        x[1] = v;
      } else {
        x[0] = v;
      }
      high_ = true;
    }
  }
}

Point10Decoder::Point10Decoder() = default;

SymbolModel& Point10Decoder::lazy(std::array<std::unique_ptr<SymbolModel>, 256>& models, std::uint8_t context) {
  if (!models[context]) models[context] = std::make_unique<SymbolModel>(256);
  return *models[context];
}

void Point10Decoder::reset(const std::uint8_t* first) {
  for (int i = 0; i < 16; ++i) {
    x_diff_median_[i].reset();
    y_diff_median_[i].reset();
    last_intensity_[i] = 0;
  }
  last_height_.fill(0);
  changed_values_.reset();
  intensity_.reset();
  for (SymbolModel& m : scan_angle_rank_) m.reset();
  point_source_.reset();
  for (auto* models : {&bit_byte_, &classification_, &user_data_})
    for (auto& m : *models)
      if (m) m->reset();
  dx_.reset();
  dy_.reset();
  z_.reset();
  std::memcpy(last_.data(), first, 20);
}

void Point10Decoder::decode(ArithmeticDecoder& decoder, std::uint8_t* out) {
  std::uint8_t* p = last_.data();
  const std::uint32_t changed = decoder.decode_symbol(changed_values_);
  if (changed & 32) p[14] = static_cast<std::uint8_t>(decoder.decode_symbol(lazy(bit_byte_, p[14])));
  const unsigned r = p[14] & 7u, n = (p[14] >> 3) & 7u;
  const unsigned m = kReturnMap[n][r], l = kReturnLevel[n][r];
  if (changed != 0) {
    if (changed & 16) {
      const auto intensity = static_cast<std::uint16_t>(intensity_.decompress(decoder, last_intensity_[m], m < 3 ? m : 3));
      store(p + 12, intensity);
      last_intensity_[m] = intensity;
    } else {
      store(p + 12, last_intensity_[m]);
    }
    if (changed & 8) p[15] = static_cast<std::uint8_t>(decoder.decode_symbol(lazy(classification_, p[15])));
    if (changed & 4) p[16] = static_cast<std::uint8_t>(decoder.decode_symbol(scan_angle_rank_[(p[14] >> 6) & 1u]) + p[16]);
    if (changed & 2) p[17] = static_cast<std::uint8_t>(decoder.decode_symbol(lazy(user_data_, p[17])));
    if (changed & 1) store(p + 18, static_cast<std::uint16_t>(point_source_.decompress(decoder, load<std::uint16_t>(p + 18))));
  }
  const std::uint32_t single = n == 1 ? 1 : 0;
  std::int32_t diff = dx_.decompress(decoder, x_diff_median_[m].get(), single);
  store(p, wrapping_add(load<std::int32_t>(p), diff));
  x_diff_median_[m].add(diff);
  std::uint32_t k = dx_.k();
  diff = dy_.decompress(decoder, y_diff_median_[m].get(), single + (k < 20 ? (k & ~1u) : 20));
  store(p + 4, wrapping_add(load<std::int32_t>(p + 4), diff));
  y_diff_median_[m].add(diff);
  k = (dx_.k() + dy_.k()) / 2;
  const std::int32_t z = z_.decompress(decoder, last_height_[l], single + (k < 18 ? (k & ~1u) : 18));
  store(p + 8, z);
  last_height_[l] = z;
  std::memcpy(out, p, 20);
}

void GpsTimeDecoder::reset(const std::uint8_t* first) {
  last_ = next_ = 0;
  last_diff_.fill(0);
  extreme_counter_.fill(0);
  multi_.reset();
  zero_diff_.reset();
  diff_.reset();
  last_time_ = {load<std::int64_t>(first), 0, 0, 0};
}

void GpsTimeDecoder::decode(ArithmeticDecoder& decoder, std::uint8_t* out) {
  decode_time(decoder);
  store(out, last_time_[last_]);
}

void GpsTimeDecoder::decode_time(ArithmeticDecoder& decoder) {
  // A step too large for 32 bits starts a new sequence with the full time.
  const auto start_full = [&] {
    next_ = (next_ + 1) & 3;
    const auto high = static_cast<std::uint32_t>(diff_.decompress(decoder, static_cast<std::int32_t>(static_cast<std::uint64_t>(last_time_[last_]) >> 32), 8));
    const std::uint32_t low = decoder.read_int();
    last_time_[next_] = static_cast<std::int64_t>((static_cast<std::uint64_t>(high) << 32) | low);
    last_ = next_;
    last_diff_[last_] = 0;
    extreme_counter_[last_] = 0;
  };
  // An unusual step is adopted as the sequence's step after four in a row.
  const auto extreme = [&](std::int32_t diff) {
    if (++extreme_counter_[last_] > 3) {
      last_diff_[last_] = diff;
      extreme_counter_[last_] = 0;
    }
  };
  for (int switches = 0; switches < 8; ++switches) {
    if (last_diff_[last_] == 0) {
      const std::uint32_t multi = decoder.decode_symbol(zero_diff_);
      if (multi == 1) {
        last_diff_[last_] = diff_.decompress(decoder, 0, 0);
        advance_time(last_time_[last_], last_diff_[last_]);
        extreme_counter_[last_] = 0;
      } else if (multi == 2) {
        start_full();
      } else if (multi > 2) {
        last_ = (last_ + multi - 2) & 3;
        continue;
      }
      return;
    }
    const std::uint32_t multi = decoder.decode_symbol(multi_);
    if (multi == 1) {
      advance_time(last_time_[last_], diff_.decompress(decoder, last_diff_[last_], 1));
      extreme_counter_[last_] = 0;
    } else if (multi < kMultiUnchanged) {
      std::int32_t diff;
      if (multi == 0) {
        diff = diff_.decompress(decoder, 0, 7);
        extreme(diff);
      } else if (multi < static_cast<std::uint32_t>(kMulti)) {
        diff = diff_.decompress(decoder, wrapping_multiply(static_cast<std::int32_t>(multi), last_diff_[last_]), multi < 10 ? 2 : 3);
      } else if (multi == static_cast<std::uint32_t>(kMulti)) {
        diff = diff_.decompress(decoder, wrapping_multiply(kMulti, last_diff_[last_]), 4);
        extreme(diff);
      } else {
        const std::int32_t factor = kMulti - static_cast<std::int32_t>(multi);
        if (factor > kMultiMinus) {
          diff = diff_.decompress(decoder, wrapping_multiply(factor, last_diff_[last_]), 5);
        } else {
          diff = diff_.decompress(decoder, wrapping_multiply(kMultiMinus, last_diff_[last_]), 6);
          extreme(diff);
        }
      }
      advance_time(last_time_[last_], diff);
    } else if (multi == kMultiCodeFull) {
      start_full();
    } else if (multi > kMultiCodeFull) {
      last_ = (last_ + multi - kMultiCodeFull) & 3;
      continue;
    }
    return;
  }
  // Only a corrupt stream switches sequences over and over; the caller's overrun check or the oracle catches it.
}

void RgbDecoder::reset(const std::uint8_t* first) {
  for (int i = 0; i < 3; ++i) last_[i] = load<std::uint16_t>(first + 2 * i);
  byte_used_.reset();
  for (SymbolModel& m : diff_) m.reset();
}

void RgbDecoder::decode(ArithmeticDecoder& decoder, std::uint8_t* out) {
  std::array<std::uint16_t, 3> item{};
  const std::uint32_t used = decoder.decode_symbol(byte_used_);
  const auto fold = [](std::uint32_t v) { return static_cast<std::uint16_t>(v & 0xFF); };
  item[0] = (used & 1) ? fold(decoder.decode_symbol(diff_[0]) + (last_[0] & 0xFF)) : static_cast<std::uint16_t>(last_[0] & 0xFF);
  item[0] |= (used & 2) ? static_cast<std::uint16_t>(fold(decoder.decode_symbol(diff_[1]) + (last_[0] >> 8)) << 8)
                        : static_cast<std::uint16_t>(last_[0] & 0xFF00);
  if (used & 64) {
    int diff = (item[0] & 0xFF) - (last_[0] & 0xFF);
    item[1] = (used & 4) ? fold(decoder.decode_symbol(diff_[2]) + clamp_byte(diff + (last_[1] & 0xFF))) : static_cast<std::uint16_t>(last_[1] & 0xFF);
    if (used & 16) {
      diff = (diff + ((item[1] & 0xFF) - (last_[1] & 0xFF))) / 2;
      item[2] = fold(decoder.decode_symbol(diff_[4]) + clamp_byte(diff + (last_[2] & 0xFF)));
    } else {
      item[2] = static_cast<std::uint16_t>(last_[2] & 0xFF);
    }
    diff = (item[0] >> 8) - (last_[0] >> 8);
    item[1] |= (used & 8) ? static_cast<std::uint16_t>(fold(decoder.decode_symbol(diff_[3]) + clamp_byte(diff + (last_[1] >> 8))) << 8)
                          : static_cast<std::uint16_t>(last_[1] & 0xFF00);
    if (used & 32) {
      diff = (diff + ((item[1] >> 8) - (last_[1] >> 8))) / 2;
      item[2] |= static_cast<std::uint16_t>(fold(decoder.decode_symbol(diff_[5]) + clamp_byte(diff + (last_[2] >> 8))) << 8);
    } else {
      item[2] |= static_cast<std::uint16_t>(last_[2] & 0xFF00);
    }
  } else {
    item[1] = item[2] = item[0];
  }
  last_ = item;
  for (int i = 0; i < 3; ++i) store(out + 2 * i, item[i]);
}

ExtraBytesDecoder::ExtraBytesDecoder(std::size_t count) : last_(count, 0), models_(count, SymbolModel(256)) {}

void ExtraBytesDecoder::reset(const std::uint8_t* first) {
  std::memcpy(last_.data(), first, last_.size());
  for (SymbolModel& m : models_) m.reset();
}

void ExtraBytesDecoder::decode(ArithmeticDecoder& decoder, std::uint8_t* out) {
  for (std::size_t i = 0; i < last_.size(); ++i) last_[i] = static_cast<std::uint8_t>(last_[i] + decoder.decode_symbol(models_[i]));
  std::memcpy(out, last_.data(), last_.size());
}

}  // namespace sharpmesh::io::laz
