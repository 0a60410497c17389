// SPDX-License-Identifier: MIT
// Points of Hopf curves and Bogdanov–Takens points on M, computed to solver tolerance by Newton's
// method on minimally augmented systems (Govaerts, "Numerical Methods for Bifurcations of
// Dynamical Equilibria", SIAM 2000, §4.4 and §9.1; as MatCont and BifurcationKit do for large
// systems). docs/algorithms/stability.md has the equations.
#pragma once

#include <Eigen/Core>
#include <limits>

#include "tessera/core/counted_problem.h"
#include "tessera/core/implicit_problem.h"

namespace tessera {

struct HopfOptions {
  /// Newton has converged when its last correction ‖dy‖ ≤ tolerance·(1 + ‖y‖) in the problem's
  /// metric and |dω| ≤ tolerance·(1 + |ω|), with ‖F‖ ≤ residual_tolerance: the corrector's
  /// defaults, so Hopf points lie on M as the mesh vertices do.
  double tolerance = 1e-10;
  double residual_tolerance = 1e-9;
  int max_iterations = 25;
  /// Relative step of the central differences of DF that give the second derivatives of F.
  double difference_step = 1e-5;
};

/// A point refined onto a Hopf curve (or a Bogdanov–Takens point).
struct HopfPoint {
  Eigen::VectorXd x;        ///< n coordinates
  double omega = 0.0;       ///< the frequency: ±iω are eigenvalues of the pencil at x
  bool is_refined = false;  ///< Newton converged; false: the mesh's estimate
  int iterations = 0;
  double residual = std::numeric_limits<double>::quiet_NaN();  ///< ‖F(x)‖
  /// |Re μ|/|μ| for the eigenvalue μ ≈ iω of the pencil at x (the Rayleigh quotient of the
  /// bordered system's null vectors): how well x satisfies the Hopf condition.
  double condition_residual = std::numeric_limits<double>::quiet_NaN();
  /// Unit tangent of the Hopf curve at x (n-vector, sign arbitrary); empty when not refined.
  Eigen::VectorXd curve_tangent;
  /// A Bogdanov–Takens point (ω = 0, on a fold curve), where a Hopf curve ends.
  bool is_bogdanov_takens = false;
  /// A neutral saddle (refine_neutral_saddle_point): ±κ are eigenvalues, omega is 0.
  bool is_neutral_saddle = false;
  double kappa = 0.0;
  /// A fold–Hopf (zero-Hopf) point: 0 and ±iω are eigenvalues; a Hopf curve crosses a fold there.
  bool is_zero_hopf = false;
  /// A Bautin (generalised Hopf) point: the first Lyapunov coefficient vanishes.
  bool is_bautin = false;
  /// l₁ at a Hopf point (lyapunov.h): < 0 supercritical, > 0 subcritical; NaN where not
  /// computed (sparse problems, neutral saddles, other special points).
  double first_lyapunov_coefficient = std::numeric_limits<double>::quiet_NaN();
};

/// Newton's method from (x, ω) onto the Hopf set {F = 0, A − iωB singular}, A = s·D_uF, with
/// minimum-norm corrections in the problem's metric (the set is a curve on M: one direction is
/// free). The singularity is the vanishing of g(x, ω) in the complex bordered system
/// [A − iωB, b; cᴴ, 0]·[v; g] = [0; 1], b and c the left and right null vectors of the previous
/// iterate (inverse iteration at the start). Stops when the point moves farther than
/// `max_displacement` from x (in the metric).
/// \param work  evaluations of F and DF are added to it.
HopfPoint refine_hopf_point(const ImplicitProblem& problem, const Eigen::VectorXd& x, double omega,
                            double max_displacement, const HopfOptions& options, WorkCounts& work);

/// Newton's method from (x, κ) onto the neutral saddles {F = 0, A − κB and A + κB singular}: a
/// real pair ±κ, which the bialternate product's zero set shares with the Hopf points (the two
/// meet at Bogdanov–Takens points). Two real bordered systems, otherwise as refine_hopf_point;
/// condition_residual is max |μ ∓ κ|/max(1, κ) for the pair's Rayleigh quotients.
HopfPoint refine_neutral_saddle_point(const ImplicitProblem& problem, const Eigen::VectorXd& x,
                                      double kappa, double max_displacement,
                                      const HopfOptions& options, WorkCounts& work);

/// Newton's method from (x, ω) onto a fold–Hopf (zero-Hopf) point: F = 0, A − iωB singular and A
/// singular (n + 1 equations for x and ω: a point), where a Hopf curve crosses a fold curve
/// (n − 2 ≥ 3).
HopfPoint refine_zero_hopf_point(const ImplicitProblem& problem, const Eigen::VectorXd& x,
                                 double omega, double max_displacement, const HopfOptions& options,
                                 WorkCounts& work);

/// Newton's method from x onto a Bogdanov–Takens point: F = 0, A singular (the real bordered
/// system's g₁ = 0) and the null vectors B-orthogonal, wᵀBv = 0 (a Jordan block at 0): n
/// equations, a point. The returned omega is 0.
HopfPoint refine_bogdanov_takens_point(const ImplicitProblem& problem, const Eigen::VectorXd& x,
                                       double max_displacement, const HopfOptions& options,
                                       WorkCounts& work);

}  // namespace tessera
