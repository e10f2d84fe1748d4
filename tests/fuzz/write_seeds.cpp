// Writes the seed corpus of every reader: write_seeds OUT_DIR creates
// OUT_DIR/<reader>/seed-<i> (scripts/fuzz runs it before fuzzing).
#include <filesystem>
#include <fstream>
#include <iostream>

#include "reader_harness.h"

int main(int argc, char** argv) {
  if (argc != 2) {
    std::cerr << "usage: write_seeds OUT_DIR\n";
    return 2;
  }
  for (const std::string& reader : sharpmesh::fuzz::reader_names()) {
    const std::filesystem::path dir = std::filesystem::path(argv[1]) / reader;
    std::filesystem::create_directories(dir);
    const auto seeds = sharpmesh::fuzz::seed_inputs(reader);
    for (std::size_t i = 0; i < seeds.size(); ++i)
      std::ofstream(dir / ("seed-" + std::to_string(i)), std::ios::binary) << seeds[i];
  }
  return 0;
}
