// libFuzzer entry point of one reader, chosen at compile time by
// SHARPMESH_FUZZ_READER (see reader_harness.h and scripts/fuzz).
#include <cstddef>
#include <cstdint>
#include <string>

#include "reader_harness.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const sharpmesh::fuzz::Workspace workspace;
  sharpmesh::fuzz::run_reader(SHARPMESH_FUZZ_READER, std::string(reinterpret_cast<const char*>(data), size), workspace);
  return 0;
}
