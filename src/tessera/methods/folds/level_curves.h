// SPDX-License-Identifier: MIT
// Level curves of a functional on a surface M = {F = 0}: the curve where one view functional f
// (a coordinate, a block's mean or norm, an expression…) takes a given value c. Located on a
// finished mesh by marching triangles, then computed to solver tolerance by Newton's method on
// F(x) = 0, f(x) = c. docs/algorithms/level-curves.md has the mathematics.
#pragma once

#include <Eigen/Core>
#include <limits>
#include <string>
#include <vector>

#include "tessera/core/counted_problem.h"
#include "tessera/core/implicit_problem.h"
#include "tessera/geometry/triangle_mesh.h"
#include "tessera/problems/view.h"

namespace tessera {

/// The level set {x : f(x) = value} of one view functional f.
struct LevelSet {
  View functional;     ///< exactly one functional (parse_view)
  double value = 0.0;  ///< c, finite
  /// "x1 = 0.5", "mean:u = 1.5": a specification that parse_level_set reads back.
  std::string specification() const;
};

/// Parses "FUNCTIONAL = VALUE" (`tessera mesh --level`): FUNCTIONAL one item of a view
/// specification (parse_view: a coordinate, mean:B, norm:B, max:B, min:B, absmax:B, norm, or
/// NAME = EXPRESSION), VALUE a finite number. The text is split at its last '=', so an
/// expression item keeps its own: "r = sqrt(x^2 + y^2) = 1". An expression without a name
/// ("x^2 + y^2 = 1") is read as "level = x^2 + y^2" when the functional is not a view item.
///
/// \throw InvalidArgument (ViewSpecificationError for the functional, with the view parser's
///        message naming the item and listing what is available) for a missing '=', a missing
///        or non-numeric or non-finite value, an unknown functional, or more than one functional.
LevelSet parse_level_set(const std::string& specification, const ImplicitProblem& problem);

struct LevelOptions {
  /// Newton on F = 0, f = c has converged when its last correction ‖dx‖ ≤ tolerance·(1 + ‖x‖)
  /// (in the problem's metric) and ‖F(x)‖ ≤ residual_tolerance: the corrector's defaults
  /// (CorrectorOptions, as FoldOptions), so level points lie on M as the mesh vertices do.
  double tolerance = 1e-10;
  /// The converged point must also satisfy |f(x) − c| ≤ residual_tolerance·(1 + |c|), f
  /// evaluated as the view does: for max:B, min:B and absmax:B this checks that the coordinate
  /// Newton held at c is still the extremal one.
  double residual_tolerance = 1e-9;
  int max_iterations = 20;
  /// A point found on a mesh edge may move at most this many edge lengths while Newton
  /// converges; farther, it has found another part of the level set (or none) and is kept
  /// unrefined. The mesh resolves M, so the true curve crosses near the estimate.
  double max_displacement_in_edges = 2.0;
};

/// A point of a level curve.
struct LevelPoint {
  Eigen::VectorXd x;        ///< n coordinates
  bool is_refined = false;  ///< Newton converged: x is on M and on f = c to solver tolerance;
                            ///< false: x is the mesh's linear estimate on an edge
  double residual = std::numeric_limits<double>::quiet_NaN();        ///< ‖F(x)‖
  double level_residual = std::numeric_limits<double>::quiet_NaN();  ///< |f(x) − c|
  int iterations = 0;  ///< Newton iterations spent on this point (all tries)
};

/// A level curve as a polyline through points in order along it.
struct LevelCurve {
  std::vector<LevelPoint> points;
  bool is_closed = false;  ///< the last point joins the first
};

/// What find_level_curves found and what it cost.
struct LevelCurves {
  std::vector<LevelCurve> curves;
  int crossing_count = 0;   ///< mesh edges across which f − c changes sign
  int unrefined_count = 0;  ///< points where Newton failed (kept at the mesh's estimate)
  /// Vertices where f could not be evaluated (not finite, e.g. log of a negative number): no
  /// crossing on their edges, so a curve may end there.
  int undefined_vertex_count = 0;
  int newton_iterations = 0;        ///< over all points
  int max_point_iterations = 0;     ///< the most any one point took
  double max_residual = 0.0;        ///< largest ‖F‖ over the refined points
  double max_level_residual = 0.0;  ///< largest |f − c| over the refined points
  WorkCounts work;                  ///< evaluations of F and DF, factorisations
  double seconds = 0.0;

  int point_count() const;
};

/// Finds the curves on M where f(x) = value, refines every point onto them and orders the points
/// into polylines.
///
/// 1. f(x_v) − c at every vertex; marching triangles (find_zero_set_curves) gives the edges
///    where it changes sign, chained into polylines, each with the zero of the linear
///    interpolant as estimate.
/// 2. Each estimate is refined by Newton's method on F(x) = 0, f(x) = c (n − 1 equations) with
///    minimum-norm corrections in the problem's metric: dx = −DF⁺F + T·a, T the tangent basis,
///    a the smallest tangent step that corrects f to first order. One factorisation of DF per
///    iteration (sparse for sparse problems); no second derivatives.
///
/// f may be any view functional. The differentiable ones (coordinates, mean:B, norm:B, norm,
/// expressions) use their gradient. max:B, min:B and absmax:B are handled where they are
/// smooth: Newton holds the coordinate that attains the extremum at the estimate at c; the
/// point is accepted only if f(x) = c holds at the converged point (that coordinate is still
/// the extremal one), else Newton restarts from the estimate with the coordinate extremal
/// there, at most twice. Where the extremum changes place along the curve, the curve has a
/// corner, which the polyline cuts at mesh resolution; every accepted point is exact.
///
/// \param mesh  a mesh of M (vertices on M) in the problem's coordinates.
/// \param functional  one functional (a View of size 1) for points of the problem's R^n.
/// \throw InvalidArgument if dimensions disagree, the view has not one functional, or value is
///        not finite.
LevelCurves find_level_curves(const ImplicitProblem& problem, const TriangleMesh& mesh,
                              const View& functional, double value,
                              const LevelOptions& options = {});

/// The same for a parsed level set.
LevelCurves find_level_curves(const ImplicitProblem& problem, const TriangleMesh& mesh,
                              const LevelSet& level, const LevelOptions& options = {});

}  // namespace tessera
