// SPDX-License-Identifier: MIT
// Domain::band_width: the width of S across a point within a plane, the quantity that limits
// steps where M ∩ S is a band narrower than them.
#include "tessera/core/domain.h"

#include <gtest/gtest.h>

#include <Eigen/Core>
#include <cmath>
#include <limits>

namespace tessera {
namespace {

// The slab 0 ≤ y ≤ 0.3 in R^3 (and a far face x ≥ −5 that no pair uses).
Domain slab() {
  Domain domain(3);
  domain.add_half_space(Eigen::Vector3d(0, 1, 0), Eigen::Vector3d(0, 0, 0), "y >= 0");
  domain.add_half_space(Eigen::Vector3d(0, -1, 0), Eigen::Vector3d(0, 0.3, 0), "y <= 0.3");
  domain.add_half_space(Eigen::Vector3d(1, 0, 0), Eigen::Vector3d(-5, 0, 0), "x >= -5");
  return domain;
}

Eigen::MatrixXd plane(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  Eigen::MatrixXd T(3, 2);
  T.col(0) = a.normalized();
  T.col(1) = b.normalized();
  return T;
}

TEST(DomainBandWidth, IsTheSlabsWidthInAPlaneAcrossIt) {
  const Domain domain = slab();
  const Eigen::MatrixXd xy = plane({1, 0, 0}, {0, 1, 0});
  EXPECT_NEAR(domain.band_width(Eigen::Vector3d(0, 0.1, 0), xy, 1.0), 0.3, 1e-12);
  // The point's position across the band does not matter, nor does a point on a face.
  EXPECT_NEAR(domain.band_width(Eigen::Vector3d(2, 0.3, 0), xy, 1.0), 0.3, 1e-12);
}

TEST(DomainBandWidth, GrowsAsThePlaneTiltsTowardsTheFaces) {
  // A plane at angle φ to the faces' normal meets the slab in a band 0.3 / cos φ wide.
  const double phi = 1.0;
  const Eigen::MatrixXd tilted =
      plane({1, 0, 0}, {0, std::cos(phi), std::sin(phi)});
  EXPECT_NEAR(slab().band_width(Eigen::Vector3d(0, 0.1, 0), tilted, 10.0), 0.3 / std::cos(phi),
              1e-12);
}

TEST(DomainBandWidth, IsInfiniteWithoutTwoOpposedFacesWithinReach) {
  const Domain domain = slab();
  const Eigen::MatrixXd xy = plane({1, 0, 0}, {0, 1, 0});
  const double infinity = std::numeric_limits<double>::infinity();
  // Both faces farther than the reach within the plane.
  EXPECT_EQ(domain.band_width(Eigen::Vector3d(0, 0.15, 0), xy, 0.1), infinity);
  // A plane parallel to the faces never crosses them.
  const Eigen::MatrixXd xz = plane({1, 0, 0}, {0, 0, 1});
  EXPECT_EQ(domain.band_width(Eigen::Vector3d(0, 0.1, 0), xz, 1.0), infinity);
  // Two faces at a right angle (a corner of a box) are no band.
  Domain corner(3);
  corner.add_half_space(Eigen::Vector3d(0, 1, 0), Eigen::Vector3d(0, 0, 0));
  corner.add_half_space(Eigen::Vector3d(1, 0, 0), Eigen::Vector3d(0, 0, 0));
  EXPECT_EQ(corner.band_width(Eigen::Vector3d(0.1, 0.1, 0), xy, 1.0), infinity);
  EXPECT_EQ(Domain(3).band_width(Eigen::Vector3d(0, 0, 0), xy, 1.0), infinity);
}

TEST(DomainBandWidth, UsesTheSparseSupportOfBoundsOnCoordinates) {
  // In R^6 with bounds on coordinate 4 only (as the catalogue's PDE problems bound λ and ε).
  Domain domain(6);
  Eigen::VectorXd normal = Eigen::VectorXd::Zero(6);
  Eigen::VectorXd point = Eigen::VectorXd::Zero(6);
  normal(4) = 1.0;
  domain.add_half_space(normal, point, "x4 >= 0");
  normal(4) = -1.0;
  point(4) = 0.5;
  domain.add_half_space(normal, point, "x4 <= 0.5");
  Eigen::MatrixXd T = Eigen::MatrixXd::Zero(6, 2);
  T(0, 0) = 1.0;
  T(4, 1) = 0.6;  // the plane crosses x4 at 0.6 per unit length
  T(5, 1) = 0.8;
  Eigen::VectorXd x = Eigen::VectorXd::Zero(6);
  x(4) = 0.2;
  EXPECT_NEAR(domain.band_width(x, T, 10.0), 0.5 / 0.6, 1e-12);
}

}  // namespace
}  // namespace tessera
