// SPDX-License-Identifier: MIT
// Repairing pinched vertices: where the triangles at a vertex form several fans that share no
// edge there, the mesh is not vertex-manifold.
#pragma once

#include <vector>

#include "tessera/geometry/triangle_mesh.h"

namespace tessera {

/// Which triangles to keep so that every vertex has a single fan: at each pinched vertex the
/// largest fan is kept (of equal ones, the fan of the lowest-numbered triangle) and the others
/// are dropped, repeatedly, since a drop can pinch a neighbour. Covering methods use it on the
/// ragged edge of an unfinished mesh, where it removes a few triangles; a complete mesh is
/// returned unchanged.
/// \return keep[t] for each triangle t. \pre indices in [0, vertex_count).
std::vector<bool> keep_largest_fans(int vertex_count, const std::vector<Triangle>& triangles);

}  // namespace tessera
