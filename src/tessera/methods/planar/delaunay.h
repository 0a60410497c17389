// SPDX-License-Identifier: MIT
// Delaunay triangulation of scattered points in the plane (CGAL, exact predicates).
#pragma once

#include <Eigen/Core>

#include "tessera/methods/planar/planar_triangulation.h"

namespace tessera {

struct DelaunaySummary {
  /// Interior edges whose quadrilateral is exactly cocircular (exact in-circle test on the
  /// doubles as given): either diagonal is Delaunay, and the input-order rule chose.
  int cocircular_edges = 0;
  /// Swaps the input-order rule made on the triangulation CGAL returned.
  int rule_swaps = 0;
};

/// The Delaunay triangulation of `points`, carrying `values`, with counter-clockwise
/// triangles. Predicates are exact (CGAL's Epick kernel), so the result is Delaunay for the
/// points as given in double precision.
///
/// Cocircular points (input-order rule): where four or more points lie exactly on an empty
/// circle, several triangulations are Delaunay. We return the one that the report's own
/// construction gives (Malcolm section 4(a)(1): nodes inserted one by one in input order, a
/// triangle removed only if the new node is strictly inside its circumcircle): a node on the
/// circle of earlier nodes is treated as just outside it. For a cocircular quadrilateral this
/// means: the diagonal is the one that avoids the quadrilateral's node with the largest index.
/// On Franke's 33-node set this gives the report's diagonal (0.8, 0.4)–(0.85, 0.25). The
/// report does not state its rule; see docs/algorithms/ddt.md. Exception: a cocircular
/// quadrilateral with a nearly flat corner (refused by PlanarTriangulation::is_swap_valid)
/// keeps CGAL's diagonal rather than become a sliver.
///
/// \param points 2×N, one point per column, N ≥ 3. \param values N values (may be empty:
///        then all values are 0). \param summary if not null, receives the cocircular counts.
/// \throw InvalidArgument for fewer than three points, a non-finite coordinate, two equal
///        points (the message names both columns) or all points on one line.
/// \see \cite malcolm_1990, section 4(a)(1).
PlanarTriangulation delaunay_triangulation(const Eigen::Ref<const Eigen::Matrix2Xd>& points,
                                           const Eigen::Ref<const Eigen::VectorXd>& values,
                                           DelaunaySummary* summary = nullptr);

}  // namespace tessera
