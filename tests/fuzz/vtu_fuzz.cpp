// SPDX-License-Identifier: MIT
// Fuzzes read_vtu (the VTU files tessera writes, and others): a mesh or InvalidArgument.
#include "fuzz/fuzz_support.h"
#include "tessera/io/vtk.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return tessera::fuzzing::fuzz_mesh_reader(
      data, size, ".vtu", [](const std::string& path) { return tessera::read_vtu(path); });
}
