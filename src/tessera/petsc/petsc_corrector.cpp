// SPDX-License-Identifier: MIT
#include "tessera/petsc/petsc_corrector.h"

#include <cmath>

namespace tessera::petsc {

namespace {

// The iteration of core/corrector.cpp on PETSc vectors; `refactor` says whether DF is
// re-evaluated. Every norm is a global reduction, so all ranks take the same decisions.
CorrectorSummary iterate(const PetscProblem& problem, Vec x, const CorrectorOptions& options,
                         DistributedLinearization& linearization, bool refactor) {
  CorrectorSummary summary;
  Owned<Vec> start = problem.create_vector();
  Owned<Vec> F = problem.create_vector();
  Owned<Vec> dx = problem.create_vector();
  Owned<Vec> moved = problem.create_vector();
  check(VecCopy(x, start), "VecCopy");
  const auto norm = [](Vec v) {
    PetscReal value = 0.0;
    check(VecNorm(v, NORM_2, &value), "VecNorm");
    return static_cast<double>(value);
  };
  const auto displacement = [&]() {
    check(VecWAXPY(moved, -1.0, start, x), "VecWAXPY");
    return norm(moved);
  };
  double previous_correction = 0.0;
  for (int k = 0; k < options.max_iterations; ++k) {
    problem.evaluate(x, F);
    summary.residual_norm = norm(F);
    if (!std::isfinite(summary.residual_norm)) {
      summary.termination = CorrectorTermination::NonFiniteResidual;
      return summary;
    }
    if (refactor) {
      // The previous basis orients the new one and guides its border.
      const bool has_reference = linearization.is_factored();
      TangentPair reference;
      if (has_reference) {
        for (std::size_t c = 0; c < 2; ++c) {
          check(VecDuplicate(linearization.tangent_basis()[c], reference[c].out()), "VecDuplicate");
          check(VecCopy(linearization.tangent_basis()[c], reference[c]), "VecCopy");
        }
      }
      if (!linearization.factor(x, has_reference ? &reference : nullptr)) {
        summary.termination = CorrectorTermination::SingularJacobian;
        return summary;
      }
    }
    check(VecScale(F, -1.0), "VecScale");
    linearization.solve_minimum_norm(F, dx);
    check(VecAXPY(x, 1.0, dx), "VecAXPY");
    summary.iterations = k + 1;
    summary.correction_norm = norm(dx);
    summary.displacement = displacement();
    const double scale = options.tolerance * (1.0 + norm(x));
    if (k > 0 && previous_correction > 0) {
      const double theta = summary.correction_norm / previous_correction;
      summary.contraction = std::max(summary.contraction, theta);
      if (theta > options.max_contraction && summary.correction_norm > scale) {
        summary.termination = CorrectorTermination::Diverged;
        return summary;
      }
    }
    previous_correction = summary.correction_norm;
    if (summary.displacement > options.max_displacement) {
      summary.termination = CorrectorTermination::TooFar;
      return summary;
    }
    if (summary.correction_norm <= scale) {
      problem.evaluate(x, F);
      summary.residual_norm = norm(F);
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

CorrectorSummary project_gauss_newton(const PetscProblem& problem, Vec x,
                                      const CorrectorOptions& options,
                                      DistributedLinearization& workspace) {
  return iterate(problem, x, options, workspace, /*refactor=*/true);
}

CorrectorSummary project_chord(const PetscProblem& problem, const DistributedLinearization& frozen,
                               Vec x, const CorrectorOptions& options) {
  // `iterate` never refactors here, so the const_cast never mutates the factorisation.
  return iterate(problem, x, options, const_cast<DistributedLinearization&>(frozen),
                 /*refactor=*/false);
}

}  // namespace tessera::petsc
