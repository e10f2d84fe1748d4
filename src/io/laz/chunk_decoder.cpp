// The LASzip container and chunk decoding (chunk_decoder.h).
#include "io/laz/chunk_decoder.h"

#include <cstring>

#include "io/laz/arithmetic_decoder.h"
#include "io/laz/items.h"
#include "sharpmesh/errors.h"

namespace sharpmesh::io::laz {
namespace {

// Item types of the LASzip VLR.
constexpr std::uint16_t kByte = 0, kPoint10 = 6, kGpsTime11 = 7, kRgb12 = 8;

template <class T>
T load(const std::uint8_t* p) {
  T v;
  std::memcpy(&v, p, sizeof v);
  return v;
}

std::string item_name(std::uint16_t type) {
  static const char* const names[] = {"BYTE", "SHORT", "INT", "LONG", "FLOAT", "DOUBLE", "POINT10", "GPSTIME11", "RGB12",
                                      "WAVEPACKET13", "POINT14", "RGB14", "RGBNIR14", "WAVEPACKET14", "BYTE14"};
  return type < std::size(names) ? names[type] : "item type " + std::to_string(type);
}

}  // namespace

std::size_t LaszipVlr::record_length() const {
  std::size_t length = 0;
  for (const Item& item : items) length += item.size;
  return length;
}

LaszipVlr parse_laszip_vlr(const std::uint8_t* data, std::size_t size, const std::string& path) {
  if (size < 34) throw InvalidInput(path + ": the LASzip VLR is too short (" + std::to_string(size) + " bytes)");
  LaszipVlr vlr;
  vlr.compressor = load<std::uint16_t>(data);
  vlr.coder = load<std::uint16_t>(data + 2);
  vlr.version_major = data[4];
  vlr.version_minor = data[5];
  vlr.revision = load<std::uint16_t>(data + 6);
  vlr.chunk_size = load<std::uint32_t>(data + 12);
  const std::uint16_t item_count = load<std::uint16_t>(data + 32);
  if (size < 34 + 6u * item_count) throw InvalidInput(path + ": the LASzip VLR lists more items than it holds");
  for (std::uint16_t i = 0; i < item_count; ++i) {
    const std::uint8_t* p = data + 34 + 6 * i;
    vlr.items.push_back({load<std::uint16_t>(p), load<std::uint16_t>(p + 2), load<std::uint16_t>(p + 4)});
  }
  if (vlr.coder != 0) throw InvalidInput(path + ": LASzip coder " + std::to_string(vlr.coder) + " is unknown (only the arithmetic coder exists)");
  if (vlr.compressor == 3)
    throw InvalidInput(path + ": layered LAZ (LAS 1.4 point formats 6-10) is not supported yet; point formats 0-3 are");
  if (vlr.compressor != 1 && vlr.compressor != 2) throw InvalidInput(path + ": unknown LASzip compressor " + std::to_string(vlr.compressor));
  if (vlr.items.empty() || vlr.items[0].type != kPoint10) throw InvalidInput(path + ": the LASzip items do not start with POINT10");
  for (const Item& item : vlr.items) {
    const bool known = (item.type == kPoint10 && item.size == 20) || (item.type == kGpsTime11 && item.size == 8) ||
                       (item.type == kRgb12 && item.size == 6) || (item.type == kByte && item.size > 0);
    if (!known) throw InvalidInput(path + ": LAZ item " + item_name(item.type) + " (" + std::to_string(item.size) + " bytes) is not supported");
    if (item.version != 2)
      throw InvalidInput(path + ": LAZ item " + item_name(item.type) + " version " + std::to_string(item.version) +
                         " is not supported (version 2, LASzip 2.0 and later, is; recompress with a current laszip)");
  }
  if (vlr.compressor == 2 && vlr.chunk_size == 0) throw InvalidInput(path + ": the LASzip chunk size is 0");
  return vlr;
}

void decode_chunk_table(const std::uint8_t* data, std::size_t size, std::uint32_t chunks, bool variable_counts,
                        std::vector<std::uint64_t>& bytes, std::vector<std::uint64_t>& counts, const std::string& path) {
  ArithmeticDecoder decoder(data, data + size);
  IntegerDecompressor sizes(32, 2);
  bytes.assign(chunks, 0);
  counts.assign(variable_counts ? chunks : 0, 0);
  std::int32_t last_count = 0, last_bytes = 0;
  for (std::uint32_t i = 0; i < chunks; ++i) {
    if (variable_counts) counts[i] = static_cast<std::uint32_t>(last_count = sizes.decompress(decoder, last_count, 0));
    bytes[i] = static_cast<std::uint32_t>(last_bytes = sizes.decompress(decoder, last_bytes, 1));
  }
  if (decoder.overrun()) throw InvalidInput(path + ": the LAZ chunk table is truncated");
}

struct ChunkDecoder::Items {
  std::vector<Item> layout;
  Point10Decoder point;
  GpsTimeDecoder time;
  RgbDecoder rgb;
  std::vector<ExtraBytesDecoder> extra;
};

ChunkDecoder::ChunkDecoder(const LaszipVlr& vlr) : items_(std::make_unique<Items>()), record_length_(vlr.record_length()) {
  items_->layout = vlr.items;
  for (const Item& item : vlr.items)
    if (item.type == kByte) items_->extra.emplace_back(item.size);
}

ChunkDecoder::~ChunkDecoder() = default;

bool ChunkDecoder::decode(const std::uint8_t* bytes, std::size_t size, std::size_t count, std::uint8_t* records) {
  if (count == 0) return true;
  if (size < record_length_) return false;
  // The first record is stored raw and seeds every item's prediction.
  std::memcpy(records, bytes, record_length_);
  std::size_t offset = 0, extra = 0;
  for (const Item& item : items_->layout) {
    const std::uint8_t* field = records + offset;
    if (item.type == kPoint10) items_->point.reset(field);
    else if (item.type == kGpsTime11) items_->time.reset(field);
    else if (item.type == kRgb12) items_->rgb.reset(field);
    else items_->extra[extra++].reset(field);
    offset += item.size;
  }
  ArithmeticDecoder decoder(bytes + record_length_, bytes + size);
  for (std::size_t i = 1; i < count; ++i) {
    std::uint8_t* record = records + i * record_length_;
    offset = extra = 0;
    for (const Item& item : items_->layout) {
      if (item.type == kPoint10) items_->point.decode(decoder, record + offset);
      else if (item.type == kGpsTime11) items_->time.decode(decoder, record + offset);
      else if (item.type == kRgb12) items_->rgb.decode(decoder, record + offset);
      else items_->extra[extra++].decode(decoder, record + offset);
      offset += item.size;
    }
    if (decoder.overrun()) return false;
  }
  return true;
}

}  // namespace sharpmesh::io::laz
