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

// The 33-node set has one cocircular quadrilateral; the report used its diagonal
// (0.8, 0.4)–(0.85, 0.25). Swaps the other diagonal to that one if needed.
void use_reports_diagonal(PlanarTriangulation& triangulation) {
  const auto is_at = [&](int v, double x, double y) {
    return std::abs(triangulation.point(v).x() - x) < 1e-12 &&
           std::abs(triangulation.point(v).y() - y) < 1e-12;
  };
  for (int t = 0; t < triangulation.triangle_count(); ++t) {
    for (int k = 0; k < 3; ++k) {
      if (!triangulation.is_interior_edge(t, k)) {
        continue;
      }
      const int a = triangulation.triangle(t)[k];
      const int b = triangulation.triangle(t)[(k + 1) % 3];
      const bool ends_at_report_points = (is_at(a, 0.8, 0.4) || is_at(b, 0.8, 0.4)) &&
                                         (is_at(a, 0.85, 0.25) || is_at(b, 0.85, 0.25));
      if (ends_at_report_points) {
        return;  // already the report's diagonal
      }
    }
  }
  // Not present: find the quadrilateral whose other diagonal joins the two points and swap.
  for (int t = 0; t < triangulation.triangle_count(); ++t) {
    for (int k = 0; k < 3; ++k) {
      if (!triangulation.is_interior_edge(t, k) || !triangulation.is_swap_valid(t, k)) {
        continue;
      }
      PlanarTriangulation trial = triangulation;
      trial.swap(t, k);
      bool found = false;
      for (int s = 0; s < trial.triangle_count() && !found; ++s) {
        for (int r = 0; r < 3 && !found; ++r) {
          const int a = trial.triangle(s)[r];
          const int b = trial.triangle(s)[(r + 1) % 3];
          found = (is_at(a, 0.8, 0.4) && is_at(b, 0.85, 0.25)) ||
                  (is_at(a, 0.85, 0.25) && is_at(b, 0.8, 0.4));
        }
      }
      if (found) {
        triangulation = trial;
        return;
      }
    }
  }
  FAIL() << "the report's diagonal (0.8, 0.4)–(0.85, 0.25) is not reachable by one swap";
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
    PlanarTriangulation triangulation =
        delaunay_triangulation(data.points, sample(function, data.points));
    use_reports_diagonal(triangulation);
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
  PlanarTriangulation start = delaunay_triangulation(data.points, sample(f, data.points));
  use_reports_diagonal(start);
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
