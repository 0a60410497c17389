// SPDX-License-Identifier: MIT
// Hopf curves on M: where a complex pair of eigenvalues of the dynamics crosses the imaginary
// axis. Located on a finished mesh from the eigenvalues at its vertices (compute_stability),
// refined onto the curve by Newton's method (hopf_point.h), joined into polylines; their ends
// inside the mesh are tried as Bogdanov–Takens points. docs/algorithms/stability.md.
#pragma once

#include <vector>

#include "tessera/core/counted_problem.h"
#include "tessera/core/implicit_problem.h"
#include "tessera/geometry/triangle_mesh.h"
#include "tessera/methods/stability/hopf_point.h"
#include "tessera/methods/stability/vertex_stability.h"

namespace tessera {

struct HopfCurveOptions {
  HopfOptions newton;
  /// A point found on a mesh edge may move at most this many edge lengths while Newton
  /// converges (as for the fold curves); farther, it is kept at the mesh's estimate.
  double max_displacement_in_edges = 2.0;
  /// An eigenvalue is complex when |Im μ| > this·max(1, |μ|).
  double complex_threshold = 1e-8;
};

struct HopfCurve {
  std::vector<HopfPoint> points;  ///< in order along the curve; a BT point at an end is marked
  bool is_closed = false;
  /// A curve of neutral saddles (real pairs ±κ) rather than Hopf points; the two kinds meet at
  /// Bogdanov–Takens points.
  bool is_neutral_saddle = false;
};

struct HopfCurves {
  std::vector<HopfCurve> curves;
  /// Mesh edges across which the sign of the bialternate product ∏(μᵢ + μⱼ) changes: a Hopf
  /// or a neutral saddle between their vertices.
  int crossing_count = 0;
  /// Crossings where Newton converged neither to a Hopf point nor to a neutral saddle: left
  /// out, so that every point written is on its curve to solver tolerance (the curve is cut).
  int unrefined_count = 0;
  /// Sparse problems: crossings left out because a real eigenvalue changes sign on the same edge
  /// (a fold, or an unstable pair turning real): the parity of the unstable pairs changed with
  /// no Hopf point between.
  int mixed_crossing_count = 0;
  int bogdanov_takens_count = 0;
  int zero_hopf_count = 0;  ///< fold–Hopf points found on the Hopf curves (marked in them)
  int bautin_count = 0;     ///< Bautin points found on the Hopf curves (dense problems)
  int hopf_point_count = 0;
  int neutral_saddle_point_count = 0;
  int newton_iterations = 0;
  double max_residual = 0.0;            ///< ‖F‖ over the refined points
  double max_condition_residual = 0.0;  ///< |Re μ|/|μ| over the refined Hopf points
  WorkCounts work;
  double seconds = 0.0;

  int point_count() const;
};

/// The Hopf curves of M on `mesh`, from the eigenvalues at its vertices.
///
/// A vertex's value for the marching is the bialternate product ∏_{i<j}(μᵢ + μⱼ) over its
/// computed eigenvalues, as its sign (the product of the signs of 2·Re μ over complex pairs and of
/// λᵢ + λⱼ over real pairs; the other factors are positive) times the smallest |μᵢ + μⱼ|: it
/// changes sign where a complex pair crosses the imaginary axis (Hopf) and where two real
/// eigenvalues sum to zero (neutral saddle), and does not care whether a pair is complex or real,
/// so its zero set runs through a Bogdanov–Takens point from the Hopf curve on to the neutral
/// saddle curve. Every crossing is refined by refine_hopf_point or refine_neutral_saddle_point
/// (the kind of its vertices' critical pair first); a change of kind along a curve is a
/// Bogdanov–Takens point, refined by refine_bogdanov_takens_point, as are the ends of Hopf curves
/// inside the mesh. Where the sign of the product of the real eigenvalues changes between two
/// neighbouring Hopf points (n − 2 ≥ 3), a fold–Hopf point is refined by refine_zero_hopf_point
/// and inserted. Dense problems: the first Lyapunov coefficient at every Hopf point, and where it
/// changes sign a Bautin point, located by regula falsi on l₁ along the curve (each trial point
/// refined onto the Hopf curve; l₁ has about 8 significant digits, so the Bautin point is found
/// to about 10⁻⁷ of the curve's scale).
/// \param stability  compute_stability(problem, mesh) (one entry per vertex).
/// \throw InvalidArgument if the sizes disagree or the problem has no dynamics.
HopfCurves find_hopf_curves(const ImplicitProblem& problem, const TriangleMesh& mesh,
                            const StabilityResult& stability, const HopfCurveOptions& options = {});

}  // namespace tessera
