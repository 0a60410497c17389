// SPDX-License-Identifier: MIT
#include "tessera/methods/start_point.h"

#include <memory>
#include <sstream>

#include "tessera/core/describe.h"
#include "tessera/core/error.h"

namespace tessera {
StartPoint project_start_point(const ImplicitProblem& problem, const Eigen::VectorXd& guess,
                               const Domain& domain, double max_distance) {
  // A distributed problem (SPMD): the guess and the point found are this rank's rows, and the
  // domain is cut to them (Domain::distributed); every check below reduces over the ranks.
  const std::shared_ptr<const AmbientSpace> shared_space = problem.space();
  const AmbientSpace& space = *shared_space;
  const int n = problem.ambient_dimension();
  const int rows = space.local_rows();
  if (space.is_distributed()) {
    TESSERA_CHECK(guess.size() == rows,
                  "start point has " << guess.size() << " rows here, problem '" << problem.name()
                                     << "' is distributed and holds " << rows << " of its n = "
                                     << n << " on this rank");
  } else {
    TESSERA_CHECK(guess.size() == n, "start point has " << guess.size()
                                                        << " coordinates, problem '"
                                                        << problem.name() << "' has n = " << n);
  }
  TESSERA_CHECK(domain.is_unbounded() || domain.ambient_dimension() == rows,
                "project_start_point: the domain's normals have " << domain.ambient_dimension()
                    << " rows, the start point " << rows
                    << (space.is_distributed() ? " (use Domain::distributed)" : ""));
  TESSERA_CHECK(space.all_finite(guess),
                "start point " << describe_point(guess, space) << " is not finite");
  StartPoint start;
  start.x = guess;
  CorrectorOptions options;
  // From a user's guess the first steps may contract slowly; accept any θ < 1 (Deuflhard's
  // criterion for a convergent Newton-type iteration) and allow more iterations.
  options.max_contraction = 0.99;
  options.max_iterations = 50;
  options.max_displacement = max_distance;
  start.corrector = project_gauss_newton(problem, start.x, options, start.linearization);
  // Only on failure (the coordinates of a distributed point are gathered from the ranks).
  const auto where = [&] { return "start point " + describe_point(guess, space); };
  switch (start.corrector.termination) {
    case CorrectorTermination::Converged:
      break;
    case CorrectorTermination::NonFiniteResidual:
      throw ComputationFailed(where() + ": F is not finite (NaN or infinity) at " +
                              describe_point(start.x, space) +
                              "; is the start inside the domain of F?");
    case CorrectorTermination::SingularJacobian:
      throw ComputationFailed(where() + ": the Jacobian DF is rank deficient at " +
                              describe_point(start.x, space) +
                              "; M is not a smooth surface there (a singular point). Choose "
                              "another start point");
    case CorrectorTermination::TooFar: {
      std::ostringstream message;
      message << where() << " is too far from M: Gauss–Newton moved it more than " << max_distance
              << " (the limit is a multiple of the step; pass a start closer to F = 0 or raise "
                 "--max-start-distance)";
      throw ComputationFailed(message.str());
    }
    case CorrectorTermination::Diverged:
    case CorrectorTermination::MaxIterations:
      throw ComputationFailed(where() + " could not be projected onto M: Gauss–Newton " +
                              start.corrector.brief_report() +
                              "; pass a start closer to F = 0");
  }
  if (!domain.contains(start.x, 1e-12)) {
    const auto nearest = domain.boundary_distance(start.x);
    std::ostringstream message;
    message << where() << " projects onto M at " << describe_point(start.x, space)
            << ", which lies outside the domain: it violates '"
            << domain.half_spaces()[nearest.nearest_half_space].label << "' by "
            << -nearest.signed_distance
            << ". Choose a start inside the domain, or check that the domain is not empty";
    throw ComputationFailed(message.str());
  }
  // Refactor exactly at the converged point so that its tangent basis is current.
  const bool ok = start.linearization.factor(problem, start.x);
  if (!ok) {
    throw ComputationFailed(where() + ": the Jacobian is rank deficient at the projected point " +
                            describe_point(start.x, space));
  }
  return start;
}

}  // namespace tessera
