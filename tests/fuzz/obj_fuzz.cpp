// SPDX-License-Identifier: MIT
// Fuzzes read_obj: a mesh in R^3 or InvalidArgument.
#include "fuzz/fuzz_support.h"
#include "tessera/io/obj.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return tessera::fuzzing::fuzz_mesh_reader(
      data, size, ".obj", [](const std::string& path) { return tessera::read_obj(path); });
}
