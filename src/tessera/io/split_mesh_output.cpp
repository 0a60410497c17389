// SPDX-License-Identifier: MIT
#include "tessera/io/split_mesh_output.h"

#include <algorithm>

#include "tessera/core/error.h"
#include "tessera/io/detail/root_writes.h"
#include "tessera/io/npy.h"
#include "tessera/io/view_mesh.h"

namespace tessera {

namespace {

// A split mesh with all n rows of every point on rank 0 (elsewhere: no points), gathered a
// bounded block of vertices at a time. Collective.
TriangleMesh gathered_on_root(const TriangleMesh& mesh) {
  const AmbientSpace& space = mesh.space();
  const int n = space.dimension();
  const int vertex_count = mesh.vertex_count();
  Eigen::MatrixXd whole(space.is_root() ? n : 0, space.is_root() ? vertex_count : 0);
  const int block = std::max(1, static_cast<int>(kStatesGatherBytes / (sizeof(double) * n)));
  const auto local = mesh.points();
  for (int begin = 0; begin < vertex_count; begin += block) {
    const int count = std::min(block, vertex_count - begin);
    space.gather_to_root(local.data() + static_cast<std::ptrdiff_t>(begin) * local.rows(), count,
                         space.is_root() ? whole.col(begin).data() : nullptr);
  }
  return TriangleMesh(whole, mesh.triangles());
}

}  // namespace

void check_split_mesh_output(const AmbientSpace& space, const View& view) {
  const int n = space.dimension();
  TESSERA_CHECK(!space.is_distributed() || !view.is_all_coordinates() ||
                    n <= kMaxGatheredDimension,
                "a mesh file of every coordinate of a mesh split over the ranks, in R^"
                    << n << ", would gather every vertex's " << n
                    << " coordinates to rank 0, which the split exists to avoid (gathered only "
                       "for n <= "
                    << kMaxGatheredDimension
                    << "); write the states to one NumPy file streamed from the ranks (--states "
                       "FILE.npy) and the mesh file in a view of a few functionals (--view, "
                       "e.g. max:B and norm:B of a block B)");
}

std::vector<std::string> write_mesh_output(const TriangleMesh& mesh, const MeshOutput& output) {
  const AmbientSpace& space = mesh.space();
  std::vector<std::string> written;
  if (!output.mesh_path.empty()) {
    if (!output.view.is_all_coordinates()) {
      write_mesh_in_view(output.mesh_path, mesh, output.view, output.options);
    } else if (!space.is_distributed()) {
      write_mesh(output.mesh_path, mesh, output.options);
    } else {
      check_split_mesh_output(space, output.view);
      const TriangleMesh whole = gathered_on_root(mesh);
      io_detail::write_on_root(space, "mesh", output.mesh_path,
                               [&] { write_mesh(output.mesh_path, whole, output.options); });
    }
    written.push_back(output.mesh_path);
  }
  if (!output.states_path.empty()) {
    write_states_npy(output.states_path, mesh);
    written.push_back(output.states_path);
    written.push_back(triangles_npy_path(output.states_path));
  }
  return written;
}

}  // namespace tessera
