// SPDX-License-Identifier: MIT
// Fuzzes the .npy reader (read_states_npy: the states and the triangles of `tessera mesh
// --states`, or arrays numpy.save wrote): an array of the promised shape, or InvalidArgument.
#include <string_view>

#include "fuzz/fuzz_support.h"
#include "tessera/io/detail/mesh_parsers.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view content(reinterpret_cast<const char*>(data), size);
  tessera::fuzzing::expect_only_invalid_argument([&] {
    const Eigen::MatrixXd points = tessera::io_detail::parse_npy_points(content, "fuzz.npy");
    if (points.rows() < 1) {
      tessera::fuzzing::fail("states with " + std::to_string(points.rows()) + " coordinates");
    }
  });
  // The same bytes as triangles of a mesh with 100 vertices.
  tessera::fuzzing::expect_only_invalid_argument([&] {
    constexpr int kVertexCount = 100;
    for (const tessera::Triangle& triangle :
         tessera::io_detail::parse_npy_triangles(content, "fuzz.npy", kVertexCount)) {
      for (const int vertex : triangle) {
        if (vertex < 0 || vertex >= kVertexCount) {
          tessera::fuzzing::fail("triangle index " + std::to_string(vertex));
        }
      }
    }
  });
  return 0;
}
