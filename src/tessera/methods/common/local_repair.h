// SPDX-License-Identifier: MIT
// Local repair of a mesh of M: triangles found defective (flipped, overlapping) are removed
// together with the fans around them, and each hole is triangulated again in M's tangent plane.
#pragma once

#include <string>
#include <vector>

#include "tessera/core/implicit_problem.h"
#include "tessera/geometry/triangle_mesh.h"

namespace tessera {

struct LocalRepair {
  int removed_triangles = 0;  ///< triangles taken out (the defective ones and their fans)
  int filled_holes = 0;       ///< holes triangulated again
  int added_triangles = 0;    ///< the new triangles, the last ones of the mesh
  bool is_repaired = false;   ///< every hole was filled; the caller must validate again
  std::string message;        ///< why a hole could not be filled, with coordinates
};

/// For each connected region made of the `defective` triangles and the triangles sharing a
/// vertex with them (`rings` times grown by their neighbours' fans): removes the region and,
/// if it is a disk whose boundary is a simple polygon in the tangent plane of M at its centre,
/// triangulates that polygon by ear clipping (largest smallest angle first), oriented like the
/// triangles around it. The boundary of the region is kept as it was, so boundary edges on ∂S
/// stay on ∂S. Vertices inside the region are dropped.
///
/// On failure (a region that is not a disk, a polygon that folds over itself in the tangent
/// plane) the mesh is left unchanged and `message` says where. Interior points are not added:
/// the new triangles may be larger than the removed ones, so the caller checks the distance
/// bound and validity again.
///
/// A split mesh of a distributed problem (TriangleMesh::set_space) is repaired as in one
/// process: each hole's tangent coordinates and side lengths are summed over the ranks at once,
/// and the message's coordinates are gathered. \throw InvalidArgument if the mesh does not
/// hold the problem's rows (check_mesh_of_problem).
LocalRepair repair_locally(const ImplicitProblem& problem, TriangleMesh& mesh,
                           const std::vector<int>& defective, int rings = 1);

}  // namespace tessera
