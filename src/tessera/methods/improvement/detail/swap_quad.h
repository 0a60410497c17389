// SPDX-License-Identifier: MIT
// One edge swap, as the sweeps of improve_by_edge_swaps (edge_swap_sweeps.cpp) and the
// single-edge entry points (edge_swap.cpp) share it: the quadrilateral of an edge, the
// criterion's verdict on it, and the check that the swap keeps the mesh valid on M.
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstddef>
#include <memory>
#include <unordered_map>
#include <utility>
#include <vector>

#include "tessera/core/ambient_space.h"
#include "tessera/core/factorisation_cache.h"
#include "tessera/core/implicit_problem.h"
#include "tessera/core/linearization.h"
#include "tessera/geometry/triangle_mesh.h"
#include "tessera/methods/improvement/edge_swap.h"

namespace tessera::detail {

// The edge {a, b} with its two triangles: t1 = (a, b, c) traverses it a -> b, t2 = (b, a, d).
struct Quad {
  int t1 = -1;
  int t2 = -1;
  int a = -1;
  int b = -1;
  int c = -1;
  int d = -1;
};

// Fills a, b, c, d from the two triangles of an edge {u, v}; false if they traverse it alike.
bool orient_quad(const std::vector<Triangle>& triangles, int t1, int t2, int u, int v, Quad& q);

// The quad's five sides and two diagonals in R^n: ab, bc, ca, ad, db, cd.
constexpr int kQuadSides = 6;
std::array<std::pair<int, int>, 6> quad_sides(const Quad& q) {
  return {{{q.a, q.b}, {q.b, q.c}, {q.c, q.a}, {q.a, q.d}, {q.d, q.b}, {q.c, q.d}}};
}

// What the criterion says of replacing triangles (a, b, c), (b, a, d) by (c, a, d), (d, b, c).
enum class Verdict {
  Improves,  ///< by more than the relative tolerance
  DoesNotImprove,
  ProjectionFailed,  ///< MidpointDistance: the old edge's midpoint could not be projected
};

// Evaluates the criterion alone (no validity check): the angle and normal criteria cost a few
// dot products, far less than the five factorisations of the convexity check. `measured`: the
// quad's kQuadSides lengths if the caller has them (a split mesh measures a sweep's quads at
// once). `workspace` is used by the distance criterion only.
Verdict judge_swap(const TriangleMesh& mesh, const ImplicitProblem& problem, const Quad& q,
                   const ImprovementOptions& options, Linearization& workspace,
                   const double* measured);

// Tangent bases at the mesh's vertices (whose points a swap never moves), kept for the
// vertices seen last: neighbouring quadrilaterals share corners, so most corners are factored
// once per run instead of once per check. Bounded, so that a sweep over a mesh of large n holds
// O(1) n-vectors.
class CornerTangents {
 public:
  explicit CornerTangents(const ImplicitProblem& problem)
      : problem_(problem), space_(problem.space()) {}

  /// A linearisation at vertex v, made now unless v was the last one: one that borrows a kept
  /// factorisation near v where that is worth it (FactorisationLenders, within four
  /// `edge_length`s), else v's own, kept as a lender.
  const Linearization* factorisation(const TriangleMesh& mesh, int v, double edge_length);
  /// T at vertex v (n×2, orthonormal), oriented like `reference`; false where DF is rank
  /// deficient.
  bool tangent(const TriangleMesh& mesh, int v, const Eigen::MatrixXd& reference,
               Eigen::MatrixXd& T);

 private:
  // At most 256 bases and 32 MB of them (at n = 10⁵ a basis is 1.6 MB).
  static constexpr std::size_t kCapacity = 256;
  static constexpr std::size_t kCapacityBytes = std::size_t{32} << 20;
  void remember(int v, const Eigen::MatrixXd& T);

  const ImplicitProblem& problem_;
  const std::shared_ptr<const AmbientSpace> space_;
  Linearization linearization_;
  FactorisationLenders lenders_{4, std::size_t{256} << 20};
  int sharing_ = -1;  // worth_sharing of the first factorisation; −1 before it
  int factored_vertex_ = -1;
  bool is_factored_ = false;
  std::unordered_map<int, Eigen::MatrixXd> tangents_;
};

// Projects the midpoint of a and b onto M (the chord frozen at a, Gauss–Newton where it does
// not contract) and checks that the quadrilateral a, d, b, c is strictly convex, with the old
// triangles' orientation, in the tangent planes at its four corners.
SwapCheck check_quad_geometry(const TriangleMesh& mesh, const ImplicitProblem& problem,
                              const Quad& q, const ImprovementOptions& options,
                              Linearization& workspace, CornerTangents& corners_tangents);

// The mesh and the problem live in the same space (a split mesh: the problem's rows).
// \throw InvalidArgument otherwise.
void check_dimensions(const TriangleMesh& mesh, const ImplicitProblem& problem);

}  // namespace tessera::detail
