// SPDX-License-Identifier: MIT
// Named per-vertex data written next to a mesh, such as the residual |F(x)| at each vertex.
#pragma once

#include <string>
#include <vector>

namespace tessera {

/// One scalar per vertex, with a name. Written as a vertex property (PLY) or a point-data
/// array (VTK, VTU).
struct VertexScalars {
  std::string name{};            ///< no whitespace (PLY and legacy VTK headers split on it)
  std::vector<double> values{};  ///< values[j] belongs to vertex j; size == vertex_count()
};

}  // namespace tessera
