// SPDX-License-Identifier: MIT
// Approximate equidistribution (EQUID, Sweby; Malcolm section 4(9)): an edge costs the
// integral along it of the directional second derivative to the power 3/2.
#include "tessera/methods/planar/equidistribution_criterion.h"

#include <array>
#include <cmath>
#include <utility>

#include "tessera/core/error.h"

namespace tessera {
namespace {

// Gauss–Legendre nodes and weights on [0, 1] (4 points: exact for polynomials of degree 7).
constexpr std::array<double, 4> kNodes = {0.0694318442029737, 0.3300094782075719,
                                          0.6699905217924281, 0.9305681557970263};
constexpr std::array<double, 4> kWeights = {0.1739274225687269, 0.3260725774312731,
                                            0.3260725774312731, 0.1739274225687269};

}  // namespace

EquidistributionCriterion::EquidistributionCriterion(HessianFunction hessian)
    : hessian_(std::move(hessian)) {
  TESSERA_CHECK(static_cast<bool>(hessian_), "EquidistributionCriterion: the Hessian is empty");
}

double EquidistributionCriterion::edge_cost(const PlanarTriangulation& triangulation,
                                            const EdgeQuadrilateral& q, CostOrdering) const {
  const Eigen::Vector2d a = triangulation.point(q.a);
  const Eigen::Vector2d edge = triangulation.point(q.b) - a;
  const double length = edge.norm();
  const Eigen::Vector2d e = edge / length;
  double integral = 0.0;
  for (std::size_t i = 0; i < kNodes.size(); ++i) {
    const Eigen::Vector2d x = a + kNodes[i] * edge;
    const double second_derivative = e.dot(hessian_(x.x(), x.y()) * e);
    integral += kWeights[i] * std::pow(std::abs(second_derivative), 1.5);
  }
  return integral * length;
}

}  // namespace tessera
