// SPDX-License-Identifier: MIT
// Delaunay triangulation of scattered points in the plane (CGAL, exact predicates).
#pragma once

#include <Eigen/Core>

#include "tessera/methods/planar/planar_triangulation.h"

namespace tessera {

/// The Delaunay triangulation of `points`, carrying `values`, with counter-clockwise
/// triangles. Predicates are exact (CGAL's Epick kernel), so the result is Delaunay for the
/// points as given in double precision. Where four or more points are cocircular the choice
/// among the Delaunay triangulations is CGAL's.
///
/// \param points 2×N, one point per column, N ≥ 3. \param values N values (may be empty:
///        then all values are 0).
/// \throw InvalidArgument for fewer than three points, a non-finite coordinate, two equal
///        points (the message names both columns) or all points on one line.
/// \see \cite malcolm_1990, section 4(a)(1).
PlanarTriangulation delaunay_triangulation(const Eigen::Ref<const Eigen::Matrix2Xd>& points,
                                           const Eigen::Ref<const Eigen::VectorXd>& values);

}  // namespace tessera
