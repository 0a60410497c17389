// SPDX-License-Identifier: MIT
// Seeds spread over a bounded region for the search for every component of M in it: the
// points of a Halton sequence in the box that the region's coordinate bounds span.
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "tessera/core/domain.h"

namespace tessera {

/// The box the seeds fill: the coordinates bounded on both sides by faces of the domain that
/// bound one coordinate (a --box's), with their bounds. The other coordinates are not seeded.
struct SeededBox {
  std::vector<int> coordinates;  ///< ascending; empty if no coordinate is bounded on both sides
  Eigen::VectorXd lower;         ///< one entry per seeded coordinate
  Eigen::VectorXd upper;
  bool is_empty() const { return coordinates.empty(); }
};

/// The box of `domain` (S ⊂ R^n; faces with more than one nonzero entry in their normal are
/// ignored: they only cut seeds off, which the projection's check of S handles).
SeededBox seeded_box(const Domain& domain);

/// `count` seeds: the Halton points 1 … count (bases 2, 3, 5, … per seeded coordinate) in
/// `box`, the coordinates that the box does not seed taken from `reference`. Column k is seed
/// k + 1.
/// \pre !box.is_empty(), reference.size() = n, count ≥ 1.
Eigen::MatrixXd halton_seeds(const SeededBox& box, const Eigen::VectorXd& reference, int count);

/// The mean spacing of `count` seeds in `box`, (volume / count)^(1/d), with the box's sides
/// measured in the metric with weights `weights` (empty: Euclidean).
double seed_spacing(const SeededBox& box, int count, const Eigen::VectorXd& weights);

}  // namespace tessera
