// SPDX-License-Identifier: MIT
// Fuzzes read_ply (ASCII, binary little and big endian): a mesh or InvalidArgument.
#include "fuzz/fuzz_support.h"
#include "tessera/io/ply.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return tessera::fuzzing::fuzz_mesh_reader(
      data, size, ".ply", [](const std::string& path) { return tessera::read_ply(path); });
}
