// SPDX-License-Identifier: MIT
// Gauss–Newton and chord correctors on distributed vectors: tessera's correctors
// (core/corrector.h) with the same options, tests and summaries, collective over the ranks.
#pragma once

#include "tessera/core/corrector.h"
#include "tessera/petsc/petsc_linearization.h"

namespace tessera::petsc {

/// Full Gauss–Newton, dx = −DF(x)⁺F(x) with DF refactored at every iterate (as
/// tessera::project_gauss_newton). The workspace keeps the last factorisation, so that a chord
/// from the projected point needs no new one.
/// \param x overwritten with the final iterate (check the summary).
CorrectorSummary project_gauss_newton(const PetscProblem& problem, Vec x,
                                      const CorrectorOptions& options,
                                      DistributedLinearization& workspace);

/// Chord Gauss–Newton with the factorisation frozen at `frozen`'s point (as tessera::project_chord):
/// every correction lies in range DFᵀ there, so x moves orthogonally to that tangent plane.
CorrectorSummary project_chord(const PetscProblem& problem, const DistributedLinearization& frozen,
                               Vec x, const CorrectorOptions& options);

}  // namespace tessera::petsc
