// SPDX-License-Identifier: MIT
// Criteria that decide which diagonal of a convex quadrilateral a triangulation should use
// (Malcolm's survey of Delaunay, minimum-weight and Dyn–Levin–Rippa's data-dependent costs).
#include "tessera/methods/planar/swap_criterion.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

#include "tessera/core/error.h"

namespace tessera {
namespace {

constexpr std::array<std::pair<CriterionKind, std::string_view>, 8> kCriterionNames = {{
    {CriterionKind::Delaunay, "delaunay"},
    {CriterionKind::MinimumWeight, "mwt"},
    {CriterionKind::MaxMinAngle3d, "maxmin3d"},
    {CriterionKind::MinimumWeight3d, "mwt3d"},
    {CriterionKind::AngleBetweenNormals, "abn"},
    {CriterionKind::JumpInNormalDerivatives, "jnd"},
    {CriterionKind::PlaneFit, "pf"},
    {CriterionKind::PlaneDistance, "pd"},
}};

// Angle between u and v in [0, π]; atan2 keeps small angles accurate where acos does not.
template <typename Vector>
double angle_between(const Vector& u, const Vector& v) {
  if constexpr (Vector::RowsAtCompileTime == 2) {
    return std::atan2(std::abs(u.x() * v.y() - u.y() * v.x()), u.dot(v));
  } else {
    return std::atan2(u.cross(v).norm(), u.dot(v));
  }
}

template <typename Vector>
std::array<double, 3> angles_of(const Vector& p, const Vector& q, const Vector& r) {
  return {angle_between<Vector>(q - p, r - p), angle_between<Vector>(r - q, p - q),
          angle_between<Vector>(p - r, q - r)};
}

Eigen::Vector3d lifted(const PlanarTriangulation& triangulation, int v) {
  return {triangulation.point(v).x(), triangulation.point(v).y(), triangulation.value(v)};
}

double combine(double h1, double h2, CostOrdering norm) {
  switch (norm) {
    case CostOrdering::L1:
      return h1 + h2;
    case CostOrdering::L2:
      return std::hypot(h1, h2);
    case CostOrdering::Lexicographic:
      return std::max(h1, h2);
  }
  return 0.0;
}

// Value at `v` of the linear interpolant on triangle (p, q, r), and that plane's gradient.
double plane_value(const PlanarTriangulation& triangulation, int p, int q, int r, int v,
                   Eigen::Vector2d* gradient) {
  *gradient = linear_gradient(triangulation, p, q, r);
  return triangulation.value(p) + gradient->dot(triangulation.point(v) - triangulation.point(p));
}

class AngleCriterion final : public SwapCriterion {
 public:
  explicit AngleCriterion(bool lifted) : lifted_(lifted) {}
  std::string name() const override { return lifted_ ? "maxmin3d" : "delaunay"; }
  Kind kind() const override { return Kind::TriangleAngles; }
  std::array<double, 3> triangle_angles(const PlanarTriangulation& triangulation, int a, int b,
                                        int c) const override {
    if (lifted_) {
      return angles_of<Eigen::Vector3d>(lifted(triangulation, a), lifted(triangulation, b),
                                        lifted(triangulation, c));
    }
    return angles_of<Eigen::Vector2d>(triangulation.point(a), triangulation.point(b),
                                      triangulation.point(c));
  }

 private:
  bool lifted_;
};

class LengthCriterion final : public SwapCriterion {
 public:
  explicit LengthCriterion(bool lifted) : lifted_(lifted) {}
  std::string name() const override { return lifted_ ? "mwt3d" : "mwt"; }
  Kind kind() const override { return Kind::EdgeCost; }
  double edge_cost(const PlanarTriangulation& triangulation, const EdgeQuadrilateral& q,
                   CostOrdering) const override {
    if (lifted_) {
      return (lifted(triangulation, q.b) - lifted(triangulation, q.a)).norm();
    }
    return (triangulation.point(q.b) - triangulation.point(q.a)).norm();
  }

 private:
  bool lifted_;
};

class NormalCriterion final : public SwapCriterion {
 public:
  explicit NormalCriterion(CriterionKind kind) : kind_(kind) {}
  std::string name() const override { return to_string(kind_); }
  Kind kind() const override { return Kind::EdgeCost; }
  double edge_cost(const PlanarTriangulation& triangulation, const EdgeQuadrilateral& q,
                   CostOrdering norm) const override {
    Eigen::Vector2d g1;
    Eigen::Vector2d g2;
    // P1 on (a, b, c) evaluated at d; P2 on (b, a, d) evaluated at c.
    const double p1_at_d = plane_value(triangulation, q.a, q.b, q.c, q.d, &g1);
    const double p2_at_c = plane_value(triangulation, q.b, q.a, q.d, q.c, &g2);
    switch (kind_) {
      case CriterionKind::AngleBetweenNormals: {
        // Normals (a_i, b_i, −1) of the two planes (Malcolm 4(c)(5)).
        const Eigen::Vector3d n1(g1.x(), g1.y(), -1.0);
        const Eigen::Vector3d n2(g2.x(), g2.y(), -1.0);
        return angle_between<Eigen::Vector3d>(n1, n2);
      }
      case CriterionKind::JumpInNormalDerivatives: {
        // n: unit normal of the edge in the plane (Malcolm 4(c)(6); the sign is irrelevant).
        const Eigen::Vector2d e = triangulation.point(q.b) - triangulation.point(q.a);
        const Eigen::Vector2d n = Eigen::Vector2d(-e.y(), e.x()).normalized();
        return std::abs(n.dot(g1 - g2));
      }
      case CriterionKind::PlaneFit:
        return combine(std::abs(p1_at_d - triangulation.value(q.d)),
                       std::abs(p2_at_c - triangulation.value(q.c)), norm);
      case CriterionKind::PlaneDistance:
        return combine(
            std::abs(p1_at_d - triangulation.value(q.d)) / std::sqrt(g1.squaredNorm() + 1.0),
            std::abs(p2_at_c - triangulation.value(q.c)) / std::sqrt(g2.squaredNorm() + 1.0), norm);
      default:
        TESSERA_ASSERT(false);
        return 0.0;
    }
  }

 private:
  CriterionKind kind_;
};

}  // namespace

std::string to_string(CriterionKind kind) {
  for (const auto& [k, name] : kCriterionNames) {
    if (k == kind) {
      return std::string(name);
    }
  }
  return "unknown";
}

std::optional<CriterionKind> parse_criterion(std::string_view name) {
  for (const auto& [k, n] : kCriterionNames) {
    if (n == name) {
      return k;
    }
  }
  return std::nullopt;
}

double SwapCriterion::edge_cost(const PlanarTriangulation&, const EdgeQuadrilateral&,
                                CostOrdering) const {
  throw InternalError(name() + ": edge_cost called on a criterion without edge costs");
}

std::array<double, 3> SwapCriterion::triangle_angles(const PlanarTriangulation&, int, int,
                                                     int) const {
  throw InternalError(name() + ": triangle_angles called on a criterion without angles");
}

std::unique_ptr<SwapCriterion> make_criterion(CriterionKind kind) {
  switch (kind) {
    case CriterionKind::Delaunay:
      return std::make_unique<AngleCriterion>(false);
    case CriterionKind::MaxMinAngle3d:
      return std::make_unique<AngleCriterion>(true);
    case CriterionKind::MinimumWeight:
      return std::make_unique<LengthCriterion>(false);
    case CriterionKind::MinimumWeight3d:
      return std::make_unique<LengthCriterion>(true);
    case CriterionKind::AngleBetweenNormals:
    case CriterionKind::JumpInNormalDerivatives:
    case CriterionKind::PlaneFit:
    case CriterionKind::PlaneDistance:
      return std::make_unique<NormalCriterion>(kind);
  }
  throw InvalidArgument("make_criterion: unknown criterion");
}

Eigen::Vector2d linear_gradient(const PlanarTriangulation& triangulation, int p, int q, int r) {
  Eigen::Matrix2d A;
  A.row(0) = (triangulation.point(q) - triangulation.point(p)).transpose();
  A.row(1) = (triangulation.point(r) - triangulation.point(p)).transpose();
  const Eigen::Vector2d dz(triangulation.value(q) - triangulation.value(p),
                           triangulation.value(r) - triangulation.value(p));
  // A is 2×2 and invertible for a non-degenerate triangle; the explicit inverse is exact
  // enough and cheap.
  return A.inverse() * dz;
}

}  // namespace tessera
