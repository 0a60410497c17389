// SPDX-License-Identifier: MIT
// Gauss–Newton correctors that project a point onto M = {F = 0}, with Deuflhard's contraction
// monitor. Numerical outcomes are values (CorrectorSummary), never exceptions.
#pragma once

#include <Eigen/Core>
#include <limits>
#include <string>
#include <vector>

#include "tessera/core/implicit_problem.h"
#include "tessera/core/linearization.h"

namespace tessera {

struct CorrectorOptions {
  /// Converged when the last correction ‖dx‖ ≤ tolerance·(1 + ‖x‖) and ‖F(x)‖ ≤
  /// residual_tolerance. 1e-10 is far below any mesh scale yet well above rounding.
  double tolerance = 1e-10;
  double residual_tolerance = 1e-9;
  int max_iterations = 25;
  /// Deuflhard's contraction θ_k = ‖dx_{k+1}‖/‖dx_k‖ above this means the iteration is not in
  /// its region of convergence (θ ≥ 1 diverges; 1/2 is the usual safety margin for chords).
  double max_contraction = 0.5;
  /// A projection that moves the point farther than this is rejected (e.g. a corrector that
  /// would jump across the narrow opening of a trough onto another sheet).
  double max_displacement = std::numeric_limits<double>::infinity();
  /// Gauss–Newton on a problem with a sparse Jacobian (where a factorisation costs tens of
  /// solves) keeps its last factorisation while a step with it contracts by
  /// kReuseContraction or better, and factors again only where it does not (the step is then
  /// redone with the new factorisation): Deuflhard's simplified Newton inside Gauss–Newton.
  /// The point reached is on M to the same tolerance, but the workspace then holds J at the
  /// last point factored, not at the final iterate: set this only where the caller does not
  /// use the workspace afterwards. Dense problems ignore it.
  bool reuse_factorisation = false;
  /// n×2 basis that guides the first factorisation (for sparse problems the border rows of
  /// [J; border] are chosen from it; it also orients the basis). Null: the workspace's last
  /// basis, if it holds one — which makes the result depend on the workspace's history; a
  /// caller that must be reproducible from its own inputs (the atlas's checkpoints) sets it.
  const Eigen::MatrixXd* first_reference = nullptr;
};

/// The contraction a step with a kept factorisation must reach (reuse_factorisation).
inline constexpr double kReuseContraction = 0.25;

enum class CorrectorTermination {
  Converged,
  MaxIterations,      ///< no convergence within max_iterations
  Diverged,           ///< contraction θ > max_contraction
  TooFar,             ///< ‖x − x₀‖ > max_displacement
  NonFiniteResidual,  ///< F(x) returned NaN or infinity
  SingularJacobian,   ///< DF(x) lost rank (full Gauss–Newton only)
};

const char* to_string(CorrectorTermination termination);

struct CorrectorSummary {
  CorrectorTermination termination = CorrectorTermination::MaxIterations;
  int iterations = 0;
  double residual_norm = std::numeric_limits<double>::quiet_NaN();  ///< ‖F(x)‖ at the end
  double correction_norm = 0.0;  ///< ‖dx‖ of the last step
  double contraction = 0.0;      ///< largest θ_k observed (0 if fewer than two steps)
  double displacement = 0.0;     ///< ‖x_end − x_start‖
  bool is_success() const { return termination == CorrectorTermination::Converged; }
  /// e.g. "Converged after 3 its, |F| 2e-15, theta 0.01".
  std::string brief_report() const;
};

/// Full Gauss–Newton with the minimum-norm correction dx = −J⁺F(x), J re-evaluated at each
/// iterate: converges to a point of M near x, moving (to first order) normal to M.
/// Used for the start point and to measure distances to M.
/// \param x n-vector, overwritten with the final iterate (even on failure; check the summary).
/// \param workspace reused between calls to avoid allocations; holds J at the last iterate.
CorrectorSummary project_gauss_newton(const ImplicitProblem& problem, Eigen::Ref<Eigen::VectorXd> x,
                                      const CorrectorOptions& options, Linearization& workspace);

/// Chord Gauss–Newton with the factorisation frozen at x_c (Brodzik–Rheinboldt's Proj):
/// x_{k+1} = x_k − J_c⁺ F(x_k). Every correction lies in range J_cᵀ, so the iteration solves
/// eq. (2.5): F(x) = 0 with U_cᵀ(x − x_pred) = 0, i.e. it projects x orthogonally to T_{x_c}M.
/// One factorisation serves all points projected from x_c.
CorrectorSummary project_chord(const ImplicitProblem& problem, const Linearization& frozen,
                               Eigen::Ref<Eigen::VectorXd> x, const CorrectorOptions& options);

/// An upper bound on the distance from x to M, good to `accuracy`, by as few chord steps as
/// that needs. The chord from `frozen` converges linearly with rate θ, so after step k the
/// point it lands on lies within θ/(1 − θ)·‖dx_k‖ of x_k (θ the largest ratio of successive
/// corrections seen): ‖x_k − x‖ plus that remainder bounds ‖x* − x‖ ≥ dist(x, M). At least three
/// steps are taken (θ is trusted from two ratios). A refinement that only asks "nearer than the
/// tolerance?" stops after three or four steps instead of the six or seven that solver tolerance needs.
/// Returns +∞ where the chord does not contract (θ above 0.8 and above options.max_contraction)
/// or does not settle within options.max_iterations: the caller measures another way.
///
/// A caller that only asks "below `clear_below`?" (a refinement's threshold with a margin)
/// lets a clear pass stop after two steps: when the first ratio is small (θ ≤ 1/8) and
/// ‖x_1 − x‖ + 4‖dx_1‖ ≤ clear_below, that sum is returned. 4‖dx_1‖ is 28 times the geometric
/// remainder; it also covers a chord whose later steps grow again along a curved M (cstr:
/// corrections 0.018, 0.0016, 0.0037, …, 4.6 times ‖dx_1‖ in all), and the margin of
/// clear_below below the threshold covers the rest. A pass after one step (8‖dx_0‖, valid for
/// any θ ≤ 7/8) was tried and refused: next to a singular curve of F (the `crossing` surface)
/// the chord's first step is small and its later ones are not, and 5 of the stress campaign's
/// 1120 cases then exceeded their tolerance by up to 16 %.
/// 0 (the default) never stops early.
double chord_distance_bound(const ImplicitProblem& problem, const Linearization& frozen,
                            const Eigen::Ref<const Eigen::VectorXd>& x, double accuracy,
                            const CorrectorOptions& options, double clear_below = 0.0);
/// chord_distance_bound for each column of `points` (n×k), the chords iterated in lockstep so
/// that every step is one solve with a column per point still iterating (cheaper per point at
/// large n than separate solves). The bounds are the same as one call per point would give.
std::vector<double> chord_distance_bounds(const ImplicitProblem& problem,
                                          const Linearization& frozen,
                                          const Eigen::Ref<const Eigen::MatrixXd>& points,
                                          double accuracy, const CorrectorOptions& options,
                                          double clear_below = 0.0);

}  // namespace tessera
