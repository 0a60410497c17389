// SPDX-License-Identifier: MIT
// Malcolm's Table 1, Delaunay row: the mean pointwise error of the piecewise linear
// interpolant on Franke's 33-node set over a 33×33 grid of the unit square.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>

#include "support/test_support.h"
#include "tessera/io/scattered_data_csv.h"
#include "tessera/methods/planar/delaunay.h"
#include "tessera/methods/planar/franke_functions.h"
#include "tessera/methods/planar/interpolation_error.h"
#include "tessera/methods/planar/local_optimisation.h"

namespace tessera {
namespace {

// True if the triangulation has the edge between the points at p and q.
bool has_edge_between(const PlanarTriangulation& triangulation, const Eigen::Vector2d& p,
                      const Eigen::Vector2d& q) {
  for (const auto& [a, b] : triangulation.edges()) {
    const Eigen::Vector2d u = triangulation.point(a);
    const Eigen::Vector2d v = triangulation.point(b);
    if ((u == p && v == q) || (u == q && v == p)) {
      return true;
    }
  }
  return false;
}

// The 33-node set has one cocircular quadrilateral, (0.75, 0.35), (0.85, 0.25), (0.9, 0.35),
// (0.8, 0.4) (centre (0.825, 0.325)); the report used its diagonal (0.8, 0.4)–(0.85, 0.25).
// The library's input-order rule must choose it without help.
TEST(MalcolmTable1, DelaunayUsesTheReportsDiagonalOfTheCocircularQuadrilateral) {
  const ScatteredData data =
      read_scattered_data_csv(testing::source_path("examples/data/franke33.csv"));
  DelaunaySummary summary;
  const PlanarTriangulation triangulation =
      delaunay_triangulation(data.points, Eigen::VectorXd(), &summary);
  EXPECT_EQ(summary.cocircular_edges, 1);
  EXPECT_TRUE(has_edge_between(triangulation, {0.8, 0.4}, {0.85, 0.25}));
  EXPECT_FALSE(has_edge_between(triangulation, {0.75, 0.35}, {0.9, 0.35}));
}

TEST(MalcolmTable1, DelaunayRowFor33PointsMatchesTheReport) {
  const ScatteredData data =
      read_scattered_data_csv(testing::source_path("examples/data/franke33.csv"));
  ASSERT_EQ(data.points.cols(), 33);
  // Report, Table 1 (33 points), row DELAUNAY: mean pointwise error, printed to 5 digits.
  const std::pair<FrankeFunction, double> expected[] = {{FrankeFunction::F1, 0.04886},
                                                        {FrankeFunction::F2, 0.01604},
                                                        {FrankeFunction::F7, 0.06866},
                                                        {FrankeFunction::F8, 0.15210},
                                                        {FrankeFunction::F9, 0.05042}};
  for (const auto& [function, value] : expected) {
    const PlanarTriangulation triangulation =
        delaunay_triangulation(data.points, sample(function, data.points));
    const InterpolationError error = interpolation_error(
        triangulation, [function](double x, double y) { return evaluate(function, x, y); });
    std::cout << to_string(function) << ": mean " << error.mean << " (report " << value << ")\n";
    // F1, F2, F7 and F9 round to the printed digits; F8 gives 0.152108 against the printed
    // 0.15210 (the report probably computed in single precision), so the tolerance is one
    // unit of the last printed digit.
    EXPECT_NEAR(error.mean, value, 1.0e-5) << to_string(function);
  }
}

}  // namespace
}  // namespace tessera

namespace tessera {
namespace {

// The data-dependent rows depend on the sweep order, which the report does not give. Over 20
// orders (index order and 19 random permutations) the report's value for F2 on 33 points lies
// within the spread we measure for each of these rows (EQUID does not: see docs/algorithms/ddt.md).
TEST(MalcolmTable1, ReportedDataDependentRowsForF2LieWithinTheSweepOrderSpread) {
  const ScatteredData data =
      read_scattered_data_csv(testing::source_path("examples/data/franke33.csv"));
  const FrankeFunction f = FrankeFunction::F2;
  const PlanarTriangulation start = delaunay_triangulation(data.points, sample(f, data.points));
  const struct {
    CriterionKind kind;
    CostOrdering ordering;
    double report;
  } rows[] = {{CriterionKind::MinimumWeight3d, CostOrdering::L2, 0.01585},
              {CriterionKind::AngleBetweenNormals, CostOrdering::L1, 0.00619},
              {CriterionKind::AngleBetweenNormals, CostOrdering::L2, 0.00610},
              {CriterionKind::JumpInNormalDerivatives, CostOrdering::L1, 0.01176},
              {CriterionKind::JumpInNormalDerivatives, CostOrdering::L2, 0.01107},
              {CriterionKind::PlaneFit, CostOrdering::L1, 0.00618},
              {CriterionKind::PlaneFit, CostOrdering::L2, 0.01190},
              {CriterionKind::PlaneDistance, CostOrdering::L1, 0.00618},
              {CriterionKind::PlaneDistance, CostOrdering::L2, 0.01188}};
  for (const auto& row : rows) {
    double lowest = 1e300;
    double highest = -1e300;
    for (unsigned seed = 0; seed < 20; ++seed) {
      PlanarTriangulation triangulation = start;
      LocalOptimisationOptions options;
      options.criterion = row.kind;
      options.ordering = row.ordering;
      options.sweep_order_seed = seed;
      ASSERT_TRUE(optimise_locally(triangulation, options).is_locally_optimal());
      const double mean = interpolation_error(triangulation, [f](double x, double y) {
                            return evaluate(f, x, y);
                          }).mean;
      lowest = std::min(lowest, mean);
      highest = std::max(highest, mean);
    }
    EXPECT_LE(lowest, row.report + 1e-5) << to_string(row.kind);
    EXPECT_GE(highest, row.report - 1e-5) << to_string(row.kind);
  }
}

}  // namespace
}  // namespace tessera
