#include "reader_harness.h"

#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <opencv2/imgcodecs.hpp>
#include <stdexcept>

#include "sharpmesh/errors.h"
#include "sharpmesh/io.h"
#include "sharpmesh/stereo_io.h"

namespace sharpmesh::fuzz {
namespace fs = std::filesystem;
namespace {

const char* const kImages[] = {"a.png", "b.png"};

std::vector<std::string> split_files(const std::string& data) {
  std::vector<std::string> parts;
  const std::string separator = kFileSeparator;
  std::size_t begin = 0;
  for (std::size_t end; (end = data.find(separator, begin)) != std::string::npos; begin = end + separator.size())
    parts.push_back(data.substr(begin, end - begin));
  parts.push_back(data.substr(begin));
  return parts;
}

std::string join_files(const std::vector<std::string>& parts) {
  std::string out;
  for (std::size_t i = 0; i < parts.size(); ++i) out += (i ? kFileSeparator : "") + parts[i];
  return out;
}

void write_bytes(const std::string& path, const std::string& bytes) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  if (!out) throw std::runtime_error("fuzz harness: cannot write " + path);
}

std::string read_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

/// Empties the workspace of the previous input's files, keeping the images.
void clear(const Workspace& workspace) {
  for (const auto& entry : fs::directory_iterator(workspace.dir())) {
    const std::string name = entry.path().filename().string();
    if (name != kImages[0] && name != kImages[1]) fs::remove_all(entry.path());
  }
}

/// The cameras of the colmap_vis reader's sparse model: three views of the origin.
std::vector<Camera> vis_cameras() {
  std::vector<Camera> cameras(3);
  for (int i = 0; i < 3; ++i) {
    Camera& c = cameras[i];
    c.image_name = "view_" + std::to_string(i) + ".png";
    c.width = 64, c.height = 48, c.fx = c.fy = 60, c.cx = 32, c.cy = 24;
    c.translation = {0.2 * i, 0, 5};
  }
  return cameras;
}

StereoModel seed_model() {
  StereoModel model;
  model.cameras = vis_cameras();
  for (int i = 0; i < 4; ++i) {
    Track t;
    t.position = {0.1 * i, -0.05 * i, 0.02 * i * i};
    t.views = {0, static_cast<std::uint32_t>(1 + i % 2)};
    t.color = {static_cast<std::uint8_t>(60 * i), 20, 200};
    model.tracks.push_back(t);
  }
  return model;
}

PointSet seed_points(bool normals, bool colors) {
  PointSet p;
  p.points = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0.5, 0.5, 1e-3}};
  if (normals) p.normals.assign(4, {0, 0, 1});
  if (colors) p.colors = {{255, 0, 0}, {0, 255, 0}, {0, 0, 255}, {9, 9, 9}};
  return p;
}

SurfaceMesh seed_mesh() {
  SurfaceMesh m;
  m.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  m.faces = {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {0, 3, 2}};
  return m;
}

std::string las_seed(int format, int record_length) {
  std::string data(227, '\0');
  auto put = [&](std::size_t offset, const auto& value) { std::memcpy(data.data() + offset, &value, sizeof value); };
  data.replace(0, 4, "LASF");
  data[24] = 1, data[25] = 2;
  put(94, std::uint16_t{227});
  put(96, std::uint32_t{227});
  data[104] = static_cast<char>(format);
  put(105, static_cast<std::uint16_t>(record_length));
  put(107, std::uint32_t{3});
  for (int k = 0; k < 3; ++k) put(131 + 8 * k, 0.001), put(155 + 8 * k, 10.0 * k);
  for (int i = 0; i < 3; ++i) {
    std::string record(record_length, '\0');
    for (int k = 0; k < 3; ++k) {
      const std::int32_t v = 1000 * i + 7 * k;
      std::memcpy(record.data() + 4 * k, &v, 4);
    }
    data += record;
  }
  return data;
}

/// A LAZ file of three points (format 1, LASzip pointwise, no chunk table):
/// the first record raw, then `stream` as the arithmetic-coded rest.
std::string laz_seed(const std::string& stream) {
  std::string data = las_seed(1, 28);
  data.resize(227);
  auto put = [&](std::size_t offset, const auto& value) { std::memcpy(data.data() + offset, &value, sizeof value); };
  put(96, std::uint32_t{227 + 54 + 46});
  put(100, std::uint32_t{1});
  data[104] = static_cast<char>(0x81);
  std::string vlr(54, '\0');
  vlr.replace(2, 14, "laszip encoded");
  const std::uint16_t record_id = 22204, length = 46;
  std::memcpy(vlr.data() + 18, &record_id, 2);
  std::memcpy(vlr.data() + 20, &length, 2);
  std::string payload(46, '\0');
  const std::uint16_t fields[] = {1, 0};  // pointwise, arithmetic coder
  std::memcpy(payload.data(), fields, 4);
  payload[4] = 2, payload[5] = 2;
  const std::uint16_t items[] = {2, 6, 20, 2, 7, 8, 2};  // count, then (type, size, version) per item
  std::memcpy(payload.data() + 32, items, sizeof items);
  std::string record(28, '\0');
  record[14] = 9;  // return 1 of 1
  record[15] = 2;
  return data + vlr + payload + record + stream;
}

std::string binary_stl_seed() {
  std::string data(80, ' ');
  const std::uint32_t count = 2;
  data.append(reinterpret_cast<const char*>(&count), 4);
  const float tris[2][12] = {{0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0}, {0, 0, 1, 1, 0, 0, 1, 1, 0, 0, 1, 0}};
  for (const auto& t : tris) {
    data.append(reinterpret_cast<const char*>(t), sizeof t);
    data.append(2, '\0');
  }
  return data;
}

}  // namespace

const std::vector<std::string>& reader_names() {
  static const std::vector<std::string> names = {"ply",         "xyz",           "off",        "obj",     "stl",
                                                 "las",         "laz",           "polylines",     "tracks_ply", "colmap_text",
                                                 "colmap_binary", "colmap_vis", "strecha",    "bundler", "nvm"};
  return names;
}

Workspace::Workspace() {
  const char* shm = "/dev/shm";
  const char* tmp = std::getenv("TMPDIR");
  std::string pattern = std::string(fs::is_directory(shm) ? shm : (tmp ? tmp : "/tmp")) + "/sharpmesh-fuzz-XXXXXX";
  if (!mkdtemp(pattern.data())) throw std::runtime_error("fuzz harness: cannot create a scratch folder");
  dir_ = pattern;
  for (const char* name : kImages) cv::imwrite(path(name), cv::Mat(48, 64, CV_8UC1, cv::Scalar(128)));
}

Workspace::~Workspace() {
  std::error_code ignored;
  fs::remove_all(dir_, ignored);
}

/// The readers of one entry point; `write(name, part)` stores a part of the input.
template <class Write>
void read_single(const std::string& reader, const std::vector<std::string>& parts, const Workspace& workspace, Write&& write) {
  if (reader == "xyz") {
    read_point_set(write("in.xyz", 0));
  } else if (reader == "obj") {
    read_mesh(write("in.obj", 0));
  } else if (reader == "stl") {
    read_mesh(write("in.stl", 0));
  } else if (reader == "las") {
    read_point_set(write("in.las", 0));
  } else if (reader == "laz") {
    read_point_set(write("in.laz", 0));
  } else if (reader == "polylines") {
    read_polylines(write("in.polylines.txt", 0));
  } else if (reader == "tracks_ply") {
    std::vector<bool> outliers;
    read_tracks_ply(write("tracks.ply", 0), &outliers);
  } else if (reader == "colmap_text" || reader == "colmap_binary") {
    const std::string ext = reader == "colmap_text" ? ".txt" : ".bin";
    write("cameras" + ext, 0), write("images" + ext, 1), write("points3D" + ext, 2);
    read_colmap_model(workspace.dir());
  } else if (reader == "colmap_vis") {
    const std::string ply = write("fused.ply", 0);
    write("fused.ply.vis", 1);
    std::vector<Vec3> normals;
    read_colmap_fused(ply, vis_cameras(), &normals);
  } else if (reader == "strecha") {
    // Every part but the last is a camera file; the last is the tracks PLY.
    fs::create_directory(workspace.path("cameras"));
    for (std::size_t i = 0; i + 1 < parts.size(); ++i) write("cameras/" + std::to_string(i) + ".png.camera", i);
    read_strecha(workspace.path("cameras"), write("tracks.ply", parts.size() - 1));
  } else if (reader == "bundler") {
    read_bundler(write("bundle.out", 0), write("list.txt", 1));
  } else if (reader == "nvm") {
    read_nvm(write("model.nvm", 0));
  } else {
    throw std::invalid_argument("fuzz harness: unknown reader '" + reader + "'");
  }
}

bool run_reader(const std::string& reader, const std::string& data, const Workspace& workspace) {
  clear(workspace);
  const std::vector<std::string> parts = split_files(data);
  auto write = [&](const std::string& name, std::size_t part) {
    const std::string file = workspace.path(name);
    write_bytes(file, part < parts.size() ? parts[part] : std::string());
    return file;
  };
  // Readers with several entry points (a PLY is a cloud or a mesh) try each:
  // the input is accepted when one of them accepts it.
  bool accepted = false;
  auto attempt = [&](auto&& read) {
    try {
      read();
      accepted = true;
    } catch (const Error&) {
      // a clear refusal is a correct answer to a malformed file
    }
  };
  if (reader == "ply" || reader == "off") {
    const std::string file = write("in." + reader, 0);
    attempt([&] { read_point_set(file); });
    attempt([&] { read_mesh(file); });
  } else {
    attempt([&] { read_single(reader, parts, workspace, write); });
  }
  return accepted;
}

std::vector<std::string> seed_inputs(const std::string& reader) {
  Workspace ws;
  auto file_of = [&](const std::string& name, auto&& write_it) {
    write_it(ws.path(name));
    return read_bytes(ws.path(name));
  };
  std::vector<std::string> seeds;
  if (reader == "ply") {
    for (PlyFormat format : {PlyFormat::Binary, PlyFormat::Ascii}) {
      seeds.push_back(file_of("p.ply", [&](const std::string& f) { write_point_set(f, seed_points(true, true), format); }));
      seeds.push_back(file_of("p.ply", [&](const std::string& f) { write_point_set(f, seed_points(false, false), format); }));
      seeds.push_back(file_of("m.ply", [&](const std::string& f) { write_mesh(f, seed_mesh(), format); }));
    }
  } else if (reader == "xyz") {
    seeds.push_back(file_of("p.xyz", [&](const std::string& f) { write_point_set(f, seed_points(false, false)); }));
    seeds.push_back("# comment\n0 0 0 0 0 1\n1 0 0 0 0 1\n0 1 0 0 0 1\n1e3 -2.5e-3 7 0 1 0\n");
  } else if (reader == "off") {
    seeds.push_back(file_of("m.off", [&](const std::string& f) { write_mesh(f, seed_mesh()); }));
    seeds.push_back("NOFF\n3 0 0\n0 0 0 0 0 1\n1 0 0 0 0 1\n0 1 0 0 0 1\n");
    seeds.push_back("COFF\n# c\n4 1 0\n0 0 0 255 0 0 255\n1 0 0 0 255 0 255\n0 1 0 0 0 255 255\n1 1 0 1 1 1 255\n4 0 1 3 2\n");
  } else if (reader == "obj") {
    seeds.push_back(file_of("m.obj", [&](const std::string& f) { write_mesh(f, seed_mesh()); }));
    seeds.push_back("v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvn 0 0 1\nf 1/1/1 2/1/1 3/1/1 4/1/1\nf -4//1 -2//1 -1//1\n");
  } else if (reader == "stl") {
    seeds.push_back("solid s\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendloop\nendfacet\nendsolid s\n");
    seeds.push_back(binary_stl_seed());
  } else if (reader == "las") {
    seeds.push_back(las_seed(0, 20));
    seeds.push_back(las_seed(2, 26));
  } else if (reader == "laz") {
    seeds.push_back(laz_seed(std::string(16, '\0')));
    std::string bytes(256, '\0');
    for (std::size_t i = 0; i < bytes.size(); ++i) bytes[i] = static_cast<char>((i * 37 + 11) & 0xFF);
    seeds.push_back(laz_seed(bytes));
  } else if (reader == "polylines") {
    seeds.push_back(file_of("p.txt", [&](const std::string& f) {
      write_polylines(f, {Polyline{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}}, Polyline{{0, 0, 1}, {0, 0, 2}}});
    }));
  } else if (reader == "tracks_ply") {
    const StereoModel model = seed_model();
    seeds.push_back(file_of("t.ply", [&](const std::string& f) { write_tracks_ply(f, model.tracks); }));
    seeds.push_back(file_of("t.ply", [&](const std::string& f) { write_tracks_ply(f, model.tracks, {true, false, false, true}); }));
  } else if (reader == "colmap_text" || reader == "colmap_binary") {
    const bool binary = reader == "colmap_binary";
    const std::string ext = binary ? ".bin" : ".txt";
    write_colmap_model(ws.dir(), seed_model(), binary);
    seeds.push_back(join_files({read_bytes(ws.path("cameras" + ext)), read_bytes(ws.path("images" + ext)), read_bytes(ws.path("points3D" + ext))}));
  } else if (reader == "colmap_vis") {
    write_colmap_fused(ws.path("fused.ply"), seed_model(), std::vector<Vec3>(4, Vec3{0, 0, 1}));
    seeds.push_back(join_files({read_bytes(ws.path("fused.ply")), read_bytes(ws.path("fused.ply.vis"))}));
  } else if (reader == "strecha") {
    const std::string camera = "500 0 319.5\n0 500 239.5\n0 0 1\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n0 0 -5\n640 480\n";
    const std::string shifted = "500 0 319.5\n0 500 239.5\n0 0 1\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n1 0 -5\n640 480\n";
    StereoModel model = seed_model();
    for (Track& t : model.tracks) t.views = {0, 1};
    seeds.push_back(join_files({camera, shifted, file_of("t.ply", [&](const std::string& f) { write_tracks_ply(f, model.tracks); })}));
  } else if (reader == "bundler") {
    seeds.push_back(join_files({"# Bundle file v0.3\n2 1\n500 0 0\n1 0 0\n0 1 0\n0 0 1\n0 0 -5\n500 0 0\n1 0 0\n0 1 0\n0 0 1\n1 0 -5\n"
                                "1 0.5 -10\n255 0 0\n2 0 17 3.3 1.6 1 4 -30 1.6\n",
                                "a.png 0 500\nb.png\n"}));
  } else if (reader == "nvm") {
    seeds.push_back("NVM_V3\n\n2\na.png 50 1 0 0 0 0 0 -5 0 0\nb.png 50 1 0 0 0 1 0 -5 0 0\n"
                    "2\n1 0.5 0 10 20 30 2 0 0 10 5 1 0 0 5\n0 0 0 1 1 1 2 0 0 0 0 1 1 -10 0\n0\n");
  } else {
    throw std::invalid_argument("fuzz harness: unknown reader '" + reader + "'");
  }
  return seeds;
}

}  // namespace sharpmesh::fuzz
