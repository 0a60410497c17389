// SPDX-License-Identifier: MIT
// Pairs of triangles of a mesh in R^n that lie close to each other, found with a multi-level
// hash grid in expected linear time (the candidate pairs of the overlap check in validate()).
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <memory>
#include <span>
#include <utility>
#include <vector>

#include "tessera/core/ambient_space.h"
#include "tessera/geometry/triangle_mesh.h"

namespace tessera {

/// Every pair (s, t), s < t, of triangles whose distance in R^n is at most margins[s] +
/// margins[t], and possibly some farther ones: those whose bounding boxes, enlarged by the
/// margins, overlap both in R^n and in the hashed three-dimensional view (see below).
///
/// The grid hashes a three-dimensional view of R^n: the coordinates themselves for n ≤ 3, the
/// projection onto three fixed pseudo-random orthonormal directions for n > 3 (a unit-norm
/// projection never increases distances, so no close pair is lost). Triangles of very
/// different sizes (atlas radii vary 100×) go to different levels: level ℓ has cells of side
/// c·2^ℓ, c being the smallest enlarged box extent, and a triangle lives on the level whose
/// cells are at least as large as its box, stored once, in the cell of its box's lower corner.
/// Each triangle looks for partners on its own level and the coarser ones only (a pair is found
/// by its smaller member), in at most 3×3×3 cells per level.
///
/// Cost: O(N·L + P·n) expected time and O(N) memory for N triangles, L non-empty levels
/// (≤ log2(largest/smallest box) + 1) and P candidate pairs tested in R^n, when a cell holds a
/// bounded number of triangles of its own level, i.e. when M ∩ (a cell) has bounded area
/// relative to the cell's triangles, as for a surface meshed at its local feature size.
///
/// \param points n×V vertex coordinates; the vertices of the included triangles must be finite.
/// \param triangles vertex indices, all in range for the included triangles.
/// \param margins one per triangle, ≥ 0; a negative margin leaves the triangle out.
/// \param space where the points live: this rank's rows of a distributed space give the same
///        pairs on every rank (null: R^n in one process).
/// \throw InvalidArgument if margins.size() != triangles.size().
std::vector<std::pair<int, int>> nearby_triangle_pairs(
    const Eigen::Ref<const Eigen::MatrixXd>& points, std::span<const Triangle> triangles,
    std::span<const double> margins, std::shared_ptr<const AmbientSpace> space = nullptr);

}  // namespace tessera
