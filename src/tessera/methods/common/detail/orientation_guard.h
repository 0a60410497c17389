// SPDX-License-Identifier: MIT
// The orientation check of every change that clipping makes to a mesh of M (a snap, a cut, a
// collapse): each reshaped triangle must keep its orientation in M's tangent plane.
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstddef>
#include <memory>
#include <unordered_map>
#include <vector>

#include "tessera/core/ambient_space.h"
#include "tessera/core/factorisation_cache.h"
#include "tessera/core/implicit_problem.h"
#include "tessera/core/linearization.h"
#include "tessera/geometry/triangle_mesh.h"

namespace tessera::detail {

/// A triangle's three corners in R^n.
using Corners = std::array<Eigen::VectorXd, 3>;

Corners corners(const TriangleMesh& mesh, const Triangle& t);

/// The vertices that share a triangle with each vertex.
std::vector<std::vector<int>> vertex_neighbours(const TriangleMesh& mesh);

/// All corners lie on M, within a step or two of each other, so projecting onto the tangent
/// plane at one of them preserves orientation; the basis's own orientation does not matter,
/// only that before and after agree. Tangent planes are taken at mesh vertices and kept (n×2
/// each, for the few vertices near a face): a factorisation per vertex, not per change, and the
/// last one also serves the chord projections onto the faces near that vertex.
class OrientationGuard {
 public:
  /// `neighbours[v]`: the vertices sharing a triangle with v when the clipping began; `mesh`
  /// (read as it changes) gives their edges' lengths.
  OrientationGuard(const ImplicitProblem& problem, const TriangleMesh& mesh,
                   std::vector<std::vector<int>> neighbours);

  /// A factorisation of DF at vertex v (at x, its point) or, for sparse problems, at one of its
  /// neighbours (the chord from there converges as well, and one factorisation serves the
  /// vertices around it), or a linearisation at v that borrows a kept factorisation within four
  /// of v's longest edges (FactorisationLenders, where factorisations are worth sharing); null
  /// where DF is rank deficient. Valid until the next call.
  const Linearization* at_vertex(int v, const Eigen::VectorXd& x);

  /// True if `after` (a reshaped or cut part of `before`) has before's orientation in the
  /// tangent plane of M at vertex v (point x, near the corners) and is not degenerate there:
  /// twice its projected area stays above kMinAreaRatio times its longest edge squared.
  /// Where DF is rank deficient there is no tangent plane: the change is refused.
  bool keeps_orientation(int v, const Eigen::VectorXd& x, const Corners& before,
                         const Corners& after);

  static constexpr double kMinAreaRatio = 1e-6;

 private:
  // The orientation test needs the planes to a few digits only.
  static constexpr double kNearTangentTolerance = 1e-6;
  // Factorisations kept at once: the most recent, up to 16 and 256 MB (at n = 10⁵ on a 2-D grid
  // one holds about 100 MB, so there only the last two are kept). 64 held 100 MB more at
  // bvp:points=10000 for two factorisations fewer in 250.
  static constexpr std::size_t kMaxKept = 16;
  static constexpr std::size_t kMaxKeptBytes = std::size_t{256} << 20;
  // Tangent bases kept at once, in bytes: beyond it they are dropped and taken again where
  // needed (one DF and a few solves each). Unbounded, the bases of every vertex near a face
  // held 100 MB at n = 10⁴ (bvp:points=10000), half the mesh's own points.
  static constexpr std::size_t kMaxTangentBytes = std::size_t{32} << 20;

  void remember_tangent(int v, Eigen::MatrixXd T);

  const Linearization* cached(int v) const;
  const Linearization* factor_at(int v, const Eigen::VectorXd& x);

  const ImplicitProblem& problem_;
  const TriangleMesh& mesh_;
  const std::shared_ptr<const AmbientSpace> space_;  // points are its local rows
  const bool shares_factorisations_;
  std::vector<std::vector<int>> neighbours_;
  FactorisationCache kept_;
  FactorisationLenders lenders_{4, std::size_t{256} << 20};
  std::unordered_map<int, Eigen::MatrixXd> tangents_;
};

}  // namespace tessera::detail
