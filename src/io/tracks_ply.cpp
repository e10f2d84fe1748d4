// Tracks as PLY: vertices with x y z (double), red green blue (uchar), a
// list `views` (uchar count, uint32 indices) and, for generated scenes, an
// `outlier` flag. Binary little endian, read back by the same layout.
#include <cstring>
#include <sstream>

#include "io/atomic_file.h"
#include "io/binary.h"
#include "io/formats.h"
#include "io/text.h"
#include "sharpmesh/errors.h"
#include "sharpmesh/stereo_io.h"

namespace sharpmesh {

void write_tracks_ply(const std::string& path, const std::vector<Track>& tracks, const std::vector<bool>& outliers) {
  const bool labelled = !outliers.empty();
  if (labelled && outliers.size() != tracks.size()) throw std::logic_error("write_tracks_ply: one label per track expected");
  std::ostringstream header;
  header << "ply\nformat binary_little_endian 1.0\ncomment sharpmesh tracks: views are camera indices in model order\n"
         << "element vertex " << tracks.size() << "\nproperty double x\nproperty double y\nproperty double z\n"
         << "property uchar red\nproperty uchar green\nproperty uchar blue\nproperty list uchar uint views\n"
         << (labelled ? "property uchar outlier\n" : "") << "end_header\n";
  io::BinaryWriter body;
  for (std::size_t i = 0; i < tracks.size(); ++i) {
    const Track& t = tracks[i];
    if (t.views.size() > 255) throw InvalidArgument(path + ": track " + format_number(i) + " has more than 255 views");
    for (double c : t.position) body.write<double>(c);
    for (std::uint8_t c : t.color) body.write<std::uint8_t>(c);
    body.write<std::uint8_t>(static_cast<std::uint8_t>(t.views.size()));
    for (std::uint32_t v : t.views) body.write<std::uint32_t>(v);
    if (labelled) body.write<std::uint8_t>(outliers[i] ? 1 : 0);
  }
  io::AtomicFile file(path);
  file.write(header.str());
  file.write(body.bytes());
  file.commit();
}

std::vector<Track> read_tracks_ply(const std::string& path, std::vector<bool>* outliers) {
  const std::string data = io::read_file(path);
  const std::size_t end = data.find("end_header\n");
  if (data.rfind("ply", 0) != 0 || end == std::string::npos) throw InvalidInput(path + ": not a PLY file");
  const std::string header = data.substr(0, end);
  const std::string expected =
      "property double x\nproperty double y\nproperty double z\nproperty uchar red\nproperty uchar green\nproperty uchar blue\n"
      "property list uchar uint views\n";
  if (header.find("format binary_little_endian 1.0") == std::string::npos || header.find(expected) == std::string::npos)
    throw InvalidInput(path + ": not a sharpmesh tracks PLY (binary little endian with x y z, red green blue, list views)");
  const bool labelled = header.find("property uchar outlier") != std::string::npos;
  const std::size_t at = header.find("element vertex ");
  std::int64_t count = -1;
  if (at != std::string::npos) {
    std::string_view rest(header.c_str() + at + 15);
    std::string_view token;
    io::next_token(rest, token);
    const std::size_t newline = token.find('\n');
    if (newline != std::string_view::npos) token = token.substr(0, newline);
    io::parse_integer(token, count);
  }
  if (count < 0) throw InvalidInput(path + ": missing or invalid 'element vertex' count");
  io::BinaryReader in(std::string_view(data).substr(end + 11), path);
  in.expect(static_cast<std::uint64_t>(count), 28, "track");
  std::vector<Track> tracks(static_cast<std::size_t>(count));
  if (outliers) outliers->assign(tracks.size(), false);
  for (std::size_t i = 0; i < tracks.size(); ++i) {
    Track& t = tracks[i];
    for (double& c : t.position) c = in.read<double>("a position");
    io::check_finite(t.position, path, "track " + std::to_string(i));
    for (std::uint8_t& c : t.color) c = in.read<std::uint8_t>("a colour");
    const auto n = in.read<std::uint8_t>("a view count");
    t.views.resize(n);
    for (std::uint32_t& v : t.views) v = in.read<std::uint32_t>("a view index");
    if (labelled) {
      const bool flag = in.read<std::uint8_t>("an outlier flag") != 0;
      if (outliers) (*outliers)[i] = flag;
    }
  }
  return tracks;
}

}  // namespace sharpmesh
