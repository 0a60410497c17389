// SPDX-License-Identifier: MIT
// Projection onto M ∩ (bounding hyperplanes of a domain): the corrector for points on ∂S,
// shared by clipping, refinement and the methods that put vertices on faces themselves.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "tessera/core/corrector.h"
#include "tessera/core/domain.h"
#include "tessera/core/implicit_problem.h"
#include "tessera/core/linearization.h"

namespace tessera {

/// Puts x exactly onto the bounding hyperplanes of `faces` (\pre x already lies on them to
/// corrector tolerance): for a coordinate face (a box face) the coordinate is set to the bound
/// itself, so that b·(x − p) = 0 exactly; for other faces x moves along the normal, which leaves
/// |b·(x − p)| at rounding level. Boundary vertices must never lie outside S.
/// \pre the domain is not distributed (see the overload with a space).
void place_on_faces(const Domain& domain, const std::vector<int>& faces, Eigen::VectorXd& x);
/// The same where x is this rank's rows of a point split over `space`, and the domain is
/// distributed alike (Domain::distributed): a collective call, one reduction for which faces are
/// coordinate faces and one per other face and pass. In one process, the overload above.
void place_on_faces(const Domain& domain, const std::vector<int>& faces, Eigen::VectorXd& x,
                    const AmbientSpace& space);

/// A point within this distance of a bounding hyperplane, relative to 1 + ‖x‖, lies on it: the
/// clipping counts such vertices as on the face (not across it), and project_onto_faces leaves
/// out of its steps a face that x already lies on to this tolerance where that face coincides
/// with another on M.
inline constexpr double kOnFaceTolerance = 1e-9;

/// Projects x onto M ∩ {the bounding hyperplanes of `faces`} (at most two independent ones, as
/// M is a surface) by minimum-norm Gauss–Newton on F(x) = 0, b_f·(x − p_f) = 0. Each step
/// factors DF alone (dense or sparse, through Linearization), so it costs what an unconstrained
/// step costs and never forms a dense n×n matrix.
///
/// Faces that coincide on M near x are one constraint: where a face's row of BᵀT (B the
/// faces' normals, T M's tangent basis) is a multiple of another face's row, or two faces'
/// rows already span the tangent plane, and x lies on that face to kOnFaceTolerance from the
/// start, the steps leave the face out, and the point reached must still lie on it to that
/// tolerance. Bounds on twin coordinates of a symmetric solution do this (u25 ≤ 20 and
/// u26 ≤ 20 of an even grid, whose states have u25 = u26): the bordered system with both is
/// singular. A face reached only on the way stays in (and the projection fails as before).
///
/// \param x  n-vector (a distributed problem's local rows, with a domain distributed alike),
///        moved in place (unspecified on failure).
/// \param max_move  the projection fails if x moves farther than this from where it started.
/// \param first_contraction  if not null, receives Deuflhard's θ = ‖dx₁‖/‖dx₀‖ of the first
///        two steps (0 if the first step already converged): the step-size controls use it.
/// On success x lies on the faces exactly (place_on_faces).
/// \return false if it does not converge within 2·options.max_iterations steps, stops
///         contracting (θ > 0.9), moves farther than max_move, F is not finite, DF loses rank,
///         or a face is tangent to M there (the constrained point is then not isolated).
/// \param near  if not null and factored: a factorisation at a nearby point of M. The chord
///        iteration with it is tried first (no factorisation at all; at large n that is the
///        whole cost), Gauss–Newton only where the chord does not contract by options'
///        max_contraction per step.
bool project_onto_faces(const ImplicitProblem& problem, const Domain& domain,
                        const std::vector<int>& faces, Eigen::VectorXd& x, double max_move,
                        const CorrectorOptions& options, double* first_contraction = nullptr,
                        const Linearization* near = nullptr);

}  // namespace tessera
