// SPDX-License-Identifier: MIT
// Points of a mesh in an order that keeps neighbours in space next to each other: where each
// point's work borrows the factorisation of DF made for the point before it (large n), an order
// along M decides how often that borrow succeeds.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "tessera/geometry/triangle_mesh.h"

namespace tessera {

/// The positions 0 … N−1 of the columns of `points` (3×N) in the order of a Hilbert curve
/// through them (CGAL::hilbert_sort, median policy): consecutive points are near each other
/// except at the curve's few long steps, unlike index order or a sort by one coordinate.
/// Deterministic: the same points give the same order on every run and thread count.
std::vector<int> hilbert_order(const Eigen::Ref<const Eigen::Matrix3Xd>& points);

/// `vertices` of `mesh` reordered along a Hilbert curve through their images in the mesh's
/// principal view (PrincipalView fitted to a sample of the mesh's points; the coordinates
/// themselves for n ≤ 3). A split mesh (each rank its rows) keeps the given order: the view
/// would need reductions per point, and the PETSc backend does not share factorisations.
/// Vertices with a coordinate that is not finite come last, in the given order.
std::vector<int> spatially_ordered(const TriangleMesh& mesh, std::vector<int> vertices);

}  // namespace tessera
