// SPDX-License-Identifier: MIT
// The first Lyapunov coefficient of a Hopf point: whether the periodic orbits born there are
// stable (supercritical, l₁ < 0) or not (subcritical, l₁ > 0); where it vanishes along a Hopf
// curve lies a Bautin (generalised Hopf) point. Dense problems only: it needs the second and
// third derivatives of F in the state, here by differences of DF.
#pragma once

#include <Eigen/Core>

#include "tessera/core/implicit_problem.h"

namespace tessera {

/// l₁ at a Hopf point x of M with frequency ω (Kuznetsov, "Elements of Applied Bifurcation
/// Theory", 3rd ed., (3.20) and §10.2.2):
///     l₁ = Re[⟨p, C(q,q,q̄)⟩ − 2⟨p, B(q, A⁻¹B(q,q̄))⟩ + ⟨p, B(q̄, (2iω − A)⁻¹B(q,q))⟩] / (2ω),
/// with A q = iωq, Aᵀp = −iωp, ⟨p, q⟩ = p̄ᵀq = 1, A the dynamics' M⁻¹·s·D_uF and B, C its second
/// and third derivatives in the state (central differences of DF: about 8 significant digits).
/// The normal form ż = (μ + iω)z + c z|z|² in the coordinate z of x = z q + z̄ q̄, ‖q‖ = 1, has
/// l₁ = Re c/ω. Its size depends on that normalisation; its sign, which decides, does not.
/// \return NaN where it cannot be computed reliably: a problem with more than `dense_state_limit`
///         states, a mass matrix that is not diagonal and positive, no eigenvalue near iω.
double first_lyapunov_coefficient(const ImplicitProblem& problem, const Eigen::VectorXd& x,
                                  double omega, int dense_state_limit = 50);

}  // namespace tessera
