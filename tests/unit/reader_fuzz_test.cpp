// The fuzz harness in the ordinary test run (issue 7): every reader accepts
// its seeds (so the fuzzers start from valid files), and every input the
// fuzzers once crashed on, kept under tests/fuzz/regressions/<reader>/, now
// ends in acceptance or a sharpmesh::Error.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "reader_harness.h"

namespace fs = std::filesystem;
using sharpmesh::fuzz::reader_names;
using sharpmesh::fuzz::run_reader;
using sharpmesh::fuzz::seed_inputs;
using sharpmesh::fuzz::Workspace;

TEST(ReaderFuzz, EveryReaderAcceptsItsSeeds) {
  const Workspace workspace;
  for (const std::string& reader : reader_names()) {
    const auto seeds = seed_inputs(reader);
    ASSERT_FALSE(seeds.empty()) << reader;
    for (std::size_t i = 0; i < seeds.size(); ++i) EXPECT_TRUE(run_reader(reader, seeds[i], workspace)) << reader << " seed " << i;
  }
}

TEST(ReaderFuzz, CutSeedsAreRefusedOrRead) {
  // Every prefix of every seed: the cheapest fuzzing there is.
  const Workspace workspace;
  for (const std::string& reader : reader_names())
    for (const std::string& seed : seed_inputs(reader))
      for (std::size_t n = 0; n < seed.size(); n += 1 + seed.size() / 64) EXPECT_NO_THROW(run_reader(reader, seed.substr(0, n), workspace)) << reader;
}

TEST(ReaderFuzz, RegressionInputsAreRefusedOrRead) {
  const fs::path root = fs::path(SHARPMESH_FUZZ_REGRESSIONS);
  const Workspace workspace;
  int replayed = 0;
  for (const std::string& reader : reader_names()) {
    if (!fs::is_directory(root / reader)) continue;
    for (const auto& entry : fs::directory_iterator(root / reader)) {
      std::ifstream in(entry.path(), std::ios::binary);
      const std::string data((std::istreambuf_iterator<char>(in)), {});
      EXPECT_NO_THROW(run_reader(reader, data, workspace)) << entry.path();
      ++replayed;
    }
  }
  RecordProperty("replayed", replayed);
}
