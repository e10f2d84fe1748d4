// One entry point per file reader, shared by the libFuzzer targets
// (fuzz_target.cpp, built by scripts/fuzz with clang) and by the regression
// test that replays the inputs kept under tests/fuzz/regressions in `make test`.
//
// An input is split into files on the separator line kFileSeparator (readers
// of several files: COLMAP's three, .ply + .vis, Strecha cameras + tracks,
// Bundler .out + list). A reader may accept the input or throw
// sharpmesh::Error; any other exception, a crash, a hang or a leak is a bug.
#pragma once

#include <string>
#include <vector>

namespace sharpmesh::fuzz {

inline constexpr const char* kFileSeparator = "\n--8<--\n";

/// The readers, by name: ply, xyz, off, obj, stl, las, polylines, tracks_ply,
/// colmap_text, colmap_binary, colmap_vis, strecha, bundler, nvm.
const std::vector<std::string>& reader_names();

/// A scratch folder for one reader's files, with the fixed companions some
/// readers need (two small PNG images for Bundler and NVM). Removed on destruction.
class Workspace {
 public:
  Workspace();
  ~Workspace();
  Workspace(const Workspace&) = delete;
  Workspace& operator=(const Workspace&) = delete;
  const std::string& dir() const { return dir_; }
  std::string path(const std::string& name) const { return dir_ + "/" + name; }

 private:
  std::string dir_;
};

/// Writes `data` as the reader's file(s) inside `workspace` and reads them.
/// True when the reader accepted the input, false when it threw sharpmesh::Error;
/// any other exception propagates (a bug).
bool run_reader(const std::string& reader, const std::string& data, const Workspace& workspace);

/// Valid inputs for a reader, in the split format above: the fuzzing seeds.
std::vector<std::string> seed_inputs(const std::string& reader);

}  // namespace sharpmesh::fuzz
