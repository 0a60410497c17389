// SPDX-License-Identifier: MIT
// Closing notches in the boundary of a clipped mesh: boundary vertices that lie inside S.
#pragma once

#include "tessera/core/domain.h"
#include "tessera/core/implicit_problem.h"
#include "tessera/geometry/triangle_mesh.h"

namespace tessera {

struct NotchClosing {
  int added_triangles = 0;  ///< the new triangles, the last ones of the mesh
};

/// After clipping, every boundary vertex of a complete covering lies on ∂S. A boundary vertex v
/// strictly inside S, between boundary neighbours a and b, is a notch: M ∩ S next to it is not
/// covered (the atlas leaves one where a hole among its charts touches a chart of its margin that
/// is never completed; seen on bratu2d at step 0.4 and on a sphere's belt). The notch is closed
/// by the triangle (a, b, v) (the edge a→b becomes the boundary), repeatedly, while:
///   - the triangle keeps the orientation of the triangle on edge a→v in the tangent plane of M
///     at v (so it lies on the uncovered side of both edges), and is not degenerate there;
///   - its new edge a–b is at most `max_edge` long and its smallest angle at least 10°;
///   - the mesh stays valid around a, b and v (validate_around), else it is taken back.
/// Normal runs have no such vertex and are left unchanged. What cannot be closed so stays for the
/// coverage check to report. New triangles may be farther from M than the tolerance: refinement
/// comes after.
NotchClosing close_boundary_notches(const ImplicitProblem& problem, const Domain& domain,
                                    TriangleMesh& mesh, double max_edge);

}  // namespace tessera
