// SPDX-License-Identifier: MIT
// Needles removed from a mesh of M: the short edge of a triangle much thinner than it is long is
// collapsed onto one of its ends, where that keeps the mesh valid and improves its angles.
#pragma once

#include <functional>
#include <string>

#include "tessera/core/implicit_problem.h"
#include "tessera/geometry/triangle_mesh.h"

namespace tessera {

struct NeedleCollapseOptions {
  /// Triangles with a smaller angle are looked at. Edge swaps (improve_by_edge_swaps) repair a
  /// cap, whose small angles sit at the ends of its longest edge; a needle, whose small angle is
  /// opposite a short edge, needs that edge collapsed: no swap removes it.
  double min_angle_degrees = 15.0;
  /// A triangle is a needle when its shortest edge is at most this fraction of the next
  /// shortest (a cap's two shorter edges are alike).
  double needle_edge_ratio = 0.5;
  /// A collapse must leave every new triangle facing the way its fan faced, in M's tangent
  /// planes at both ends of the edge, with signed area above this fraction of its longest edge
  /// squared (1e-3: no new sliver, an equilateral triangle has 0.43).
  double min_area_ratio = 1e-3;
  /// Passes over the needles; each collapses edges whose ends no earlier collapse of the pass
  /// touched.
  int max_passes = 8;
  /// Polled once per needle; true ends the collapses there, the mesh valid.
  std::function<bool()> stop_requested;
};

struct NeedleCollapseSummary {
  int collapsed_edges = 0;
  int passes = 0;
  int refused = 0;  ///< needles whose collapse would fold a triangle or not improve the angles
  bool interrupted = false;
  /// e.g. "collapsed 12 short edges of needles in 2 passes (3 refused)".
  std::string brief_report() const;
};

/// For each triangle with an angle below options.min_angle_degrees whose shortest edge (u, v)
/// is at most options.needle_edge_ratio of its next shortest, shortest needles first: merges
/// u into v (or v into u) when
///  - the removed end is not on the mesh's boundary (the boundary and its vertices on ∂S stay),
///  - the link condition holds (u and v share exactly the neighbours opposite their edge), so
///    the mesh stays a manifold with the same Euler characteristic,
///  - every triangle that gains the kept end faces the way its fan did, in M's tangent planes at
///    u and at v (no fold), with no new sliver (options.min_area_ratio), and
///  - the smallest angle of the new triangles exceeds that of the triangles they replace.
/// Vertices never move, so every vertex stays on M; the vertices no longer used are dropped (the
/// others keep their order). Two factorisations of DF per needle judged.
/// \pre mesh.ambient_dimension() == problem.ambient_dimension(); the mesh is not split over
///      ranks (InvalidArgument otherwise).
NeedleCollapseSummary collapse_needles(TriangleMesh& mesh, const ImplicitProblem& problem,
                                       const NeedleCollapseOptions& options = {});

}  // namespace tessera
