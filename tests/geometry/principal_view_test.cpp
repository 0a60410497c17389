// SPDX-License-Identifier: MIT
// The 3-D view spatial hashes bucket points of R^n by: orthonormal (never shortens a distance
// more than the true one, so no neighbour is missed), and fitted to a surface of a discretised
// PDE it keeps the surface's extent instead of shrinking it by √(3/n).
#include "tessera/geometry/principal_view.h"

#include <gtest/gtest.h>

#include <Eigen/QR>
#include <algorithm>
#include <random>
#include <vector>

#include "tessera/methods/atlas/chart_index.h"
#include "tessera/methods/common/point_grid.h"

namespace tessera {
namespace {

// N points on a curved 2-D surface in R^n that lies near a random 3-D subspace.
Eigen::MatrixXd surface_points(int n, int N, unsigned seed) {
  std::mt19937_64 generator(seed);
  std::normal_distribution<double> normal;
  Eigen::MatrixXd random(n, 3);
  for (int i = 0; i < random.size(); ++i) {
    random(i) = normal(generator);
  }
  const Eigen::MatrixXd basis = Eigen::HouseholderQR<Eigen::MatrixXd>(random).householderQ() *
                                Eigen::MatrixXd::Identity(n, 3);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  Eigen::MatrixXd points(n, N);
  for (int j = 0; j < N; ++j) {
    const double s = uniform(generator), t = uniform(generator);
    points.col(j) = basis * Eigen::Vector3d(s, t, 0.5 * (s * s - t * t));
  }
  return points;
}

TEST(PrincipalView, IsTheCoordinatesUpToThreeDimensions) {
  const PrincipalView view(2);
  const Eigen::Vector3d y = view(Eigen::Vector2d(1.5, -2.0));
  EXPECT_EQ(y, Eigen::Vector3d(1.5, -2.0, 0.0));
}

TEST(PrincipalView, NeverLengthensADistanceAndKeepsASurfacesSpread) {
  const int n = 1000;
  const Eigen::MatrixXd points = surface_points(n, 400, 3);
  const PrincipalView unfitted(n);
  PrincipalView fitted(n);
  fitted.fit_sample(static_cast<int>(points.cols()), [&](int i) { return points.col(i); });
  double shrink_unfitted = 0.0;
  double shrink_fitted = 0.0;
  for (int j = 1; j < points.cols(); ++j) {
    const Eigen::VectorXd d = points.col(j) - points.col(0);
    const double true_distance = d.norm();
    for (const PrincipalView* view : {&unfitted, static_cast<const PrincipalView*>(&fitted)}) {
      EXPECT_LE(((*view)(points.col(j)) - (*view)(points.col(0))).norm(),
                true_distance * (1 + 1e-12));
    }
    shrink_unfitted += ((unfitted)(points.col(j)) - unfitted(points.col(0))).norm() / true_distance;
    shrink_fitted += (fitted(points.col(j)) - fitted(points.col(0))).norm() / true_distance;
  }
  shrink_unfitted /= points.cols() - 1;
  shrink_fitted /= points.cols() - 1;
  EXPECT_LT(shrink_unfitted, 0.2);  // a random view: about √(3/n) ≈ 0.05
  EXPECT_GT(shrink_fitted, 0.999);  // the surface lies in the fitted view's span
}

// The indexes refit their view as they grow; every disk that overlaps a query is found before
// and after (the view only changes which candidates are discarded early).
TEST(PrincipalView, IndexesFindEveryOverlapAcrossRefits) {
  const int n = 300;
  const Eigen::MatrixXd centers = surface_points(n, 300, 5);
  const double radius = 0.08;
  ChartIndex index(std::make_shared<const AmbientSpace>(n));
  PointGrid grid(n, 2 * radius);
  std::vector<int> candidates;
  for (int c = 0; c < centers.cols(); ++c) {
    index.insert(c, centers.col(c), radius);
    if (index.refit_due()) {
      index.refit(centers.leftCols(c + 1));
    }
    grid.insert(c, centers.col(c));
    grid.refit_if_due([&](int id) { return Eigen::VectorXd(centers.col(id)); });
    // Every earlier disk that overlaps this one is a candidate.
    index.candidates(centers.col(c), radius, candidates);
    const std::vector<int> near = grid.near(centers.col(c), 2 * radius,
                                            [&](int id) { return Eigen::VectorXd(centers.col(id)); });
    for (int m = 0; m <= c; ++m) {
      if ((centers.col(m) - centers.col(c)).norm() < 2 * radius) {
        EXPECT_NE(std::find(candidates.begin(), candidates.end(), m), candidates.end())
            << "chart " << m << " missed at " << c;
        EXPECT_NE(std::find(near.begin(), near.end(), m), near.end())
            << "point " << m << " missed at " << c;
      }
    }
  }
}

// A disk far larger than the indexed ones (radii 0.02 … 3 in one atlas) spans more cells of
// their level than are occupied; the index then visits the occupied cells instead of the box,
// and must still find every overlapping disk, and only nearby ones.
TEST(ChartIndex, LargeQueryAmongSmallDisksFindsEveryOverlap) {
  const int n = 5;
  ChartIndex index(std::make_shared<const AmbientSpace>(n));
  Eigen::MatrixXd centers(n, 400);
  std::vector<double> radii(400);
  for (int c = 0; c < 400; ++c) {
    const double t = 0.05 * c;
    centers.col(c) << std::cos(t) * (1 + 0.1 * t), std::sin(t) * (1 + 0.1 * t), 0.3 * t, 0.0, 0.01 * t;
    radii[c] = c % 50 == 0 ? 0.5 : 0.02;
    index.insert(c, centers.col(c), radii[c]);
    if (index.refit_due()) {
      index.refit(centers.leftCols(c + 1));
    }
  }
  std::vector<int> candidates;
  for (const double radius : {3.0, 0.02, 0.3}) {
    const Eigen::VectorXd query = centers.col(123);
    index.candidates(query, radius, candidates);
    int overlapping = 0;
    for (int m = 0; m < 400; ++m) {
      if ((centers.col(m) - query).norm() < radii[m] + radius) {
        ++overlapping;
        EXPECT_NE(std::find(candidates.begin(), candidates.end(), m), candidates.end())
            << "chart " << m << " missed by a query of radius " << radius;
      }
    }
    EXPECT_GE(static_cast<int>(candidates.size()), overlapping);
    std::vector<int> sorted = candidates;
    std::sort(sorted.begin(), sorted.end());
    EXPECT_EQ(std::adjacent_find(sorted.begin(), sorted.end()), sorted.end())
        << "a chart listed twice by a query of radius " << radius;
  }
}

}  // namespace
}  // namespace tessera
