// SPDX-License-Identifier: MIT
// The tests' way to put a serial mesh on split states: each rank keeps its rows of every vertex.
#pragma once

#include <memory>

#include "tessera/core/ambient_space.h"
#include "tessera/geometry/triangle_mesh.h"

namespace tessera::petsc {

/// This rank's rows (space's split) of every vertex of `mesh`, the same triangles.
inline TriangleMesh split_rows(const TriangleMesh& mesh,
                               const std::shared_ptr<const AmbientSpace>& space) {
  Eigen::MatrixXd local(space->local_rows(), mesh.vertex_count());
  for (int v = 0; v < mesh.vertex_count(); ++v) {
    local.col(v) = mesh.point(v).segment(space->first_row(), space->local_rows());
  }
  TriangleMesh rows(local, mesh.triangles());
  rows.set_space(space);
  return rows;
}

}  // namespace tessera::petsc
