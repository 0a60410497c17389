// SPDX-License-Identifier: MIT
#include "tessera/core/corrector.h"

#include <cmath>
#include <limits>
#include <sstream>

#include "tessera/core/ambient_space.h"

namespace tessera {

const char* to_string(CorrectorTermination termination) {
  switch (termination) {
    case CorrectorTermination::Converged:
      return "Converged";
    case CorrectorTermination::MaxIterations:
      return "MaxIterations";
    case CorrectorTermination::Diverged:
      return "Diverged";
    case CorrectorTermination::TooFar:
      return "TooFar";
    case CorrectorTermination::NonFiniteResidual:
      return "NonFiniteResidual";
    case CorrectorTermination::SingularJacobian:
      return "SingularJacobian";
  }
  return "Unknown";
}

std::string CorrectorSummary::brief_report() const {
  std::ostringstream out;
  out.precision(2);
  out << to_string(termination) << " after " << iterations << " its, |F| " << residual_norm
      << ", theta " << contraction;
  return out.str();
}

namespace {

// One shared iteration for both correctors: `refactor` says whether J is re-evaluated.
CorrectorSummary iterate(const ImplicitProblem& problem, Eigen::Ref<Eigen::VectorXd> x,
                         const CorrectorOptions& options, Linearization& linearization,
                         bool refactor) {
  // Local rows (all of them in one process) and global reductions: see AmbientSpace.
  const std::shared_ptr<const AmbientSpace> shared_space = problem.space();
  const AmbientSpace& space = *shared_space;
  CorrectorSummary summary;
  // Scratch kept between calls (a covering projects millions of points; at small n the
  // allocations would cost more than the arithmetic). iterate never calls itself.
  thread_local Eigen::VectorXd start;
  thread_local Eigen::VectorXd F;
  thread_local Eigen::VectorXd minus_F;
  thread_local Eigen::VectorXd dx;
  start = x;
  F.resize(space.local_equations());
  dx.resize(space.local_rows());
  double previous_correction = 0.0;
  // Steps with a kept factorisation contract by kReuseContraction at least, so they are
  // bounded; the factored steps stay limited by max_iterations.
  const bool reuse = refactor && options.reuse_factorisation && problem.has_sparse_jacobian();
  const int max_steps = reuse ? 3 * options.max_iterations : options.max_iterations;
  int factorisations = 0;
  for (int k = 0; k < max_steps; ++k) {
    problem.evaluate(x, F);
    summary.residual_norm = space.norm(F);
    if (!std::isfinite(summary.residual_norm)) {
      summary.termination = CorrectorTermination::NonFiniteResidual;
      return summary;
    }
    minus_F = -F;
    const auto factor_here = [&] {
      const Eigen::MatrixXd reference =
          factorisations == 0 && options.first_reference != nullptr ? *options.first_reference
          : linearization.is_factored()                             ? linearization.tangent_basis()
                                                                    : Eigen::MatrixXd();
      ++factorisations;
      return linearization.factor(problem, x, reference.size() ? &reference : nullptr);
    };
    if (refactor && (!reuse || k == 0)) {
      if (!factor_here()) {
        summary.termination = CorrectorTermination::SingularJacobian;
        return summary;
      }
    }
    linearization.solve_minimum_norm(minus_F, dx);
    double correction = space.norm(dx);  // a global reduction: taken once per solve
    if (reuse && k > 0 &&
        !(correction <= kReuseContraction * previous_correction ||
          correction <= options.tolerance * (1.0 + space.norm(x)))) {
      // The kept factorisation does not contract well here: the step is taken with a new one.
      if (factorisations >= options.max_iterations) {
        break;
      }
      if (!factor_here()) {
        summary.termination = CorrectorTermination::SingularJacobian;
        return summary;
      }
      linearization.solve_minimum_norm(minus_F, dx);
      correction = space.norm(dx);
    }
    x += dx;
    summary.iterations = k + 1;
    summary.correction_norm = correction;
    summary.displacement = space.distance(x, start);
    if (k > 0 && previous_correction > 0) {
      const double theta = summary.correction_norm / previous_correction;
      summary.contraction = std::max(summary.contraction, theta);
      if (theta > options.max_contraction &&
          summary.correction_norm > options.tolerance * (1.0 + space.norm(x))) {
        summary.termination = CorrectorTermination::Diverged;
        return summary;
      }
    }
    previous_correction = summary.correction_norm;
    if (summary.displacement > options.max_displacement) {
      summary.termination = CorrectorTermination::TooFar;
      return summary;
    }
    if (summary.correction_norm <= options.tolerance * (1.0 + space.norm(x))) {
      problem.evaluate(x, F);
      summary.residual_norm = space.norm(F);
      if (!std::isfinite(summary.residual_norm)) {
        summary.termination = CorrectorTermination::NonFiniteResidual;
        return summary;
      }
      if (summary.residual_norm <= options.residual_tolerance) {
        summary.termination = CorrectorTermination::Converged;
        return summary;
      }
    }
  }
  summary.termination = CorrectorTermination::MaxIterations;
  return summary;
}

}  // namespace

CorrectorSummary project_gauss_newton(const ImplicitProblem& problem, Eigen::Ref<Eigen::VectorXd> x,
                                      const CorrectorOptions& options, Linearization& workspace) {
  return iterate(problem, x, options, workspace, /*refactor=*/true);
}

CorrectorSummary project_chord(const ImplicitProblem& problem, const Linearization& frozen,
                               Eigen::Ref<Eigen::VectorXd> x, const CorrectorOptions& options) {
  // `iterate` never refactors here, so the const_cast never mutates the factorisation.
  return iterate(problem, x, options, const_cast<Linearization&>(frozen), /*refactor=*/false);
}

double chord_distance_bound(const ImplicitProblem& problem, const Linearization& frozen,
                            const Eigen::Ref<const Eigen::VectorXd>& x, double accuracy,
                            const CorrectorOptions& options, double clear_below) {
  return chord_distance_bounds(problem, frozen, x, accuracy, options, clear_below).front();
}

std::vector<double> chord_distance_bounds(const ImplicitProblem& problem,
                                          const Linearization& frozen,
                                          const Eigen::Ref<const Eigen::MatrixXd>& points,
                                          double accuracy, const CorrectorOptions& options,
                                          double clear_below) {
  // A bound needs the chord to contract, not to contract fast: a slow chord costs solves, a
  // refused one a factorisation or a Gauss–Newton projection (measured on bratu2d from an
  // anchor two edges away: θ = 0.5–0.62 for one sample in twenty).
  constexpr double kMaxBoundContraction = 0.8;
  const double max_theta = std::max(options.max_contraction, kMaxBoundContraction);
  const std::shared_ptr<const AmbientSpace> shared_space = problem.space();
  const AmbientSpace& space = *shared_space;
  constexpr double kInfinity = std::numeric_limits<double>::infinity();
  const auto count = static_cast<int>(points.cols());
  std::vector<double> bound(static_cast<std::size_t>(count), kInfinity);
  // The points still iterating, in lockstep: one solve with a column per point each step.
  std::vector<int> active(static_cast<std::size_t>(count));
  for (int j = 0; j < count; ++j) {
    active[static_cast<std::size_t>(j)] = j;
  }
  std::vector<double> previous(static_cast<std::size_t>(count), 0.0);
  std::vector<double> theta(static_cast<std::size_t>(count), 0.0);
  thread_local Eigen::MatrixXd Y;
  thread_local Eigen::MatrixXd F;
  thread_local Eigen::MatrixXd dx;
  thread_local Eigen::VectorXd residual;
  Y = points;
  residual.resize(space.local_equations());
  for (int k = 0; k < options.max_iterations && !active.empty(); ++k) {
    // −F at the active points; a point where F is not finite is dropped (bound +∞).
    F.resize(space.local_equations(), static_cast<Eigen::Index>(active.size()));
    Eigen::Index width = 0;
    std::vector<int> finite;
    for (const int j : active) {
      problem.evaluate(Y.col(j), residual);
      if (space.all_finite(residual)) {
        F.col(width++) = -residual;
        finite.push_back(j);
      }
    }
    active = std::move(finite);
    if (width == 0) {
      break;
    }
    dx.resize(space.local_rows(), width);
    frozen.solve_minimum_norm_columns(F.leftCols(width), dx);
    std::vector<int> still;
    for (Eigen::Index a = 0; a < width; ++a) {
      const int j = active[static_cast<std::size_t>(a)];
      const auto s = static_cast<std::size_t>(j);
      auto y = Y.col(j);
      y += dx.col(a);
      const double correction = space.norm(dx.col(a));
      const double displacement = space.distance(y, points.col(j));
      if (!std::isfinite(correction) || displacement > options.max_displacement) {
        continue;  // +∞
      }
      if (k > 0) {
        // Converged to solver tolerance: the remainder is rounding.
        if (correction <= options.tolerance * (1.0 + space.norm(y))) {
          bound[s] = displacement;
          continue;
        }
        theta[s] = std::max(theta[s], correction / previous[s]);
        if (theta[s] > max_theta) {
          continue;  // +∞
        }
        const double remainder = theta[s] / (1.0 - theta[s]) * correction;
        // A clear pass after two steps (see the header for the factor 4).
        if (k == 1 && theta[s] <= 0.125 && displacement + 4.0 * correction <= clear_below) {
          bound[s] = displacement + 4.0 * correction;
          continue;
        }
        // θ is trusted from two ratios (three steps), not one: a first step that overshoots
        // along a curved M can make the first ratio small and the second exceed 1 (cstr, a
        // chord from an edge's end: 0.018, 0.0016, 0.0037, ... landing 0.027 away, where one
        // ratio promised 0.0199).
        if (k >= 2 && remainder <= accuracy) {
          bound[s] = displacement + remainder;
          continue;
        }
      } else if (correction == 0.0) {
        bound[s] = 0.0;  // the point lies on M
        continue;
      }
      previous[s] = correction;
      still.push_back(j);
    }
    active = std::move(still);
  }
  return bound;
}

}  // namespace tessera
