// SPDX-License-Identifier: MIT
// Projection of the user's start point onto M inside the domain, shared by all methods.
#pragma once

#include <Eigen/Core>

#include "tessera/core/corrector.h"
#include "tessera/core/domain.h"
#include "tessera/core/linearization.h"

namespace tessera {

struct StartPoint {
  Eigen::VectorXd x;            ///< on M to corrector tolerance, inside the domain
  Linearization linearization;  ///< factorised at x
  CorrectorSummary corrector;
};

/// Projects `guess` onto M with full Gauss–Newton (minimum-norm steps). For a distributed
/// problem `guess` and the point found are this rank's rows, `domain` holds the same rows
/// (Domain::distributed), and every rank calls this alike.
/// \throw ComputationFailed with a message naming the guess and the reason when F is not finite
///        there, DF loses rank, the iteration does not converge, the projection moves farther
///        than `max_distance`, or the projected point lies outside `domain`.
/// \throw InvalidArgument if guess has the wrong size or is not finite.
StartPoint project_start_point(const ImplicitProblem& problem, const Eigen::VectorXd& guess,
                               const Domain& domain, double max_distance);

}  // namespace tessera
