// SPDX-License-Identifier: MIT
// The stress harness's sampled checks of a mesh of M, independent of validate(): points of the
// triangles projected onto M (is any other triangle over them? how far is M?), and points of M
// drawn at random near the mesh (does a triangle cover them?). Issue 33: `bezier` meshes with
// crossing needles and M ∩ S left uncovered beyond the tolerance passed the validation; these
// checks look the way an independent judge looks.
#pragma once

#include <Eigen/Core>

#include <cstdint>
#include <functional>
#include <string>

#include "tessera/core/domain.h"
#include "tessera/core/implicit_problem.h"
#include "tessera/geometry/triangle_mesh.h"

namespace tessera::testing {

struct SampledCoverage {
  double min_angle_degrees = 180.0;  ///< the smallest corner angle in R^n
  /// The largest distance to M over ten points of every triangle (centroid, three points near
  /// the corners, three between centroid and corners, the edge midpoints); −1 if none measured.
  double max_distance = -1.0;
  /// Points of a triangle (projected onto M) that lie strictly inside another triangle over the
  /// same sheet of M: that part of M is covered twice.
  int doubly_covered = 0;
  /// Random points of M ∩ S near the mesh (within three of its longest edges) that no triangle
  /// covers and that lie farther than `gap` from every triangle: a hole, or M ∩ S beyond the
  /// boundary. `uncovered_distance` is the largest such distance.
  int uncovered = 0;
  double uncovered_distance = 0.0;
  int random_samples = 0;  ///< random points of M ∩ S near the mesh that were judged
  std::string example;     ///< the first finding, with coordinates
};

/// The exact distance from a point to M, for surfaces that have one in closed form; where a
/// singular curve lies on M (two sheets crossing) Gauss–Newton from a point near the crossing
/// can land on the farther sheet, and |P(x) − x| is then only an upper bound.
using ExactDistance = std::function<double(const Eigen::VectorXd&)>;

/// \param gap  a point of M ∩ S farther than this from the mesh is uncovered (the tolerance, or
///             for a run without one a tenth of its step); 0 skips the random samples.
/// \param random_points  how many random points to draw near the mesh and project onto M.
/// \param exact_distance  if given, max_distance uses it instead of the projection's length.
SampledCoverage sample_coverage(const TriangleMesh& mesh, const ImplicitProblem& problem,
                                const Domain& domain, double gap, int random_points,
                                std::uint64_t seed, const ExactDistance& exact_distance = {});

}  // namespace tessera::testing
