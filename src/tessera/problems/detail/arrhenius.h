// SPDX-License-Identifier: MIT
// The Arrhenius term of the Gelfand–Bratu problems, shared by the catalogue's serial problems
// (examples.cpp) and their PETSc counterparts (petsc/petsc_bratu.cpp).
#pragma once

#include <cmath>

namespace tessera::detail {

/// exp(φ(u)) with φ(u) = u/(1 + εu), and its partial derivatives.
struct Arrhenius {
  double value;               // exp(φ)
  double derivative_u;        // d exp(φ)/du = exp(φ) / (1 + εu)²
  double derivative_epsilon;  // d exp(φ)/dε = −exp(φ) u² / (1 + εu)²
};

inline Arrhenius arrhenius(double u, double epsilon) {
  const double denominator = 1.0 + epsilon * u;
  const double value = std::exp(u / denominator);
  const double inverse_square = 1.0 / (denominator * denominator);
  return {value, value * inverse_square, -value * u * u * inverse_square};
}

}  // namespace tessera::detail
