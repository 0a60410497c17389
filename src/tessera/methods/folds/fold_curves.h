// SPDX-License-Identifier: MIT
// Fold curves and cusps of a surface M = {F = 0} over a parameter plane π: where M, seen from the
// plane, turns over. Located on a finished mesh, then computed to solver tolerance by Newton's
// method on an augmented system. docs/algorithms/folds.md has the mathematics.
#pragma once

#include <Eigen/Core>
#include <limits>
#include <vector>

#include "tessera/core/counted_problem.h"
#include "tessera/core/implicit_problem.h"
#include "tessera/geometry/triangle_mesh.h"
#include "tessera/methods/folds/parameter_plane.h"

namespace tessera {

struct FoldOptions {
  /// Newton on the augmented system has converged when its last correction ‖dx‖ ≤
  /// tolerance·(1 + ‖x‖) (in the problem's metric) and ‖F(x)‖ ≤ residual_tolerance: the
  /// corrector's defaults (CorrectorOptions), so fold points lie on M as the mesh vertices do.
  double tolerance = 1e-10;
  double residual_tolerance = 1e-9;
  int max_iterations = 20;
  /// A fold point found on a mesh edge may move at most this many edge lengths while Newton
  /// converges; farther, it has found another part of the fold set (or none) and is kept
  /// unrefined. The mesh resolves M, so the true curve crosses near the estimate.
  double max_displacement_in_edges = 2.0;
  /// Relative step of the central differences of DF that give the second derivatives D²F
  /// (h = step·(1 + ‖x‖∞)): about the cube root of the rounding unit, which balances the
  /// truncation error h² against the cancellation error ε/h.
  double difference_step = 1e-5;
};

/// A point of a fold curve.
struct FoldPoint {
  Eigen::VectorXd x;         ///< n coordinates
  bool is_refined = false;   ///< Newton converged: x is on the fold curve to solver tolerance;
                             ///< false: x is the mesh's linear estimate on an edge
  bool is_cusp = false;      ///< a cusp: the fold curve's tangent lies in the kernel of Dπ
  double residual = std::numeric_limits<double>::quiet_NaN();  ///< ‖F(x)‖
  /// det(Dπ·T) at x (T the oriented orthonormal tangent basis in the metric): 0 on the fold.
  double determinant = std::numeric_limits<double>::quiet_NaN();
};

/// A fold curve as a polyline through points in order along it.
struct FoldCurve {
  std::vector<FoldPoint> points;
  bool is_closed = false;  ///< the last point joins the first
};

/// What find_fold_curves found and what it cost.
struct FoldCurves {
  std::vector<FoldCurve> curves;
  int crossing_count = 0;     ///< mesh edges across which det(Dπ·T) changes sign
  int unrefined_count = 0;    ///< fold points where Newton failed (kept at the mesh's estimate)
  int cusp_count = 0;         ///< cusps found and refined (FoldPoint::is_cusp)
  int unrefined_cusp_count = 0;  ///< cusps bracketed but not refined (marked at the bracket)
  /// Triangles where det(Dπ·T) vanishes at all three corners to rounding: Dπ is singular on M's
  /// tangent planes over a region there (e.g. a cylinder over a plane curve, seen along its
  /// axis), so M does not fold along a curve; left out of the marching.
  int singular_triangle_count = 0;
  int newton_iterations = 0;  ///< over all fold and cusp points
  int tangent_evaluations = 0;  ///< vertices where det(Dπ·T) was evaluated exactly
  double max_residual = 0.0;    ///< largest ‖F‖ over the refined points
  WorkCounts work;            ///< evaluations of F and DF, factorisations
  double seconds = 0.0;

  int point_count() const;
};

/// Finds the fold curves of M over the plane π on a mesh of M, refines every point onto the true
/// fold set and orders the points into polylines; detects and refines cusps.
///
/// 1. det(Dπ·T) is evaluated at mesh vertices near a change of orientation of the projected
///    triangles, with T the tangent basis of M (one factorisation of DF) oriented like the mesh.
/// 2. On every edge where it changes sign, the linear estimate of its zero is the start of Newton's
///    method on F(x) = 0, det(Dπ(x)·T(x)) = 0 (n − 1 equations; minimum-norm corrections, second
///    derivatives of F by central differences of DF): a point of the fold curve to solver
///    tolerance, not to mesh resolution. Sparse problems use the sparse factorisations of the
///    corrector; nothing of size n×n is formed.
/// 3. The edge points are joined triangle by triangle into polylines (marching triangles).
/// 4. Where the image of the curve in the plane reverses direction between two neighbouring
///    points, a cusp is bracketed and located by regula falsi (Illinois) on the zero of the image
///    curve's speed, each trial point refined onto the fold curve.
///
/// \param mesh  a mesh of M (vertices on M), consistently oriented, in the problem's coordinates.
/// \throw InvalidArgument if dimensions disagree or the mesh is not consistently oriented.
FoldCurves find_fold_curves(const ImplicitProblem& problem, const TriangleMesh& mesh,
                            const ParameterPlane& plane, const FoldOptions& options = {});

}  // namespace tessera
