// SPDX-License-Identifier: MIT
// Malcolm's Table 1, Delaunay row: the mean pointwise error of the piecewise linear
// interpolant on Franke's 33-node set over a 33×33 grid of the unit square.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <string>

#include "support/test_support.h"
#include "tessera/io/scattered_data_csv.h"
#include "tessera/methods/planar/delaunay.h"
#include "tessera/methods/planar/equidistribution_criterion.h"
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

// A row of Malcolm's Tables 1 and 2: a criterion with its cost-vector ordering.
enum class Row { Mwt3d, Abn1, Abn2, Jnd1, Jnd2, Pf1, Pf2, Pd1, Pd2, Equid };

const char* to_string(Row row) {
  constexpr const char* kNames[] = {"MWT-3D", "ABN-1", "ABN-2", "JND-1", "JND-2",
                                    "PF-1",   "PF-2",  "PD-1",  "PD-2",  "EQUID"};
  return kNames[static_cast<int>(row)];
}

// Mean pointwise error on the 33×33 grid after the LOP (global test, as in the command) with
// the row's criterion, sweeping the triangles in the order drawn with `seed` (0: index order).
double mean_error_after_lop(const PlanarTriangulation& start, FrankeFunction f, Row row,
                            unsigned seed) {
  PlanarTriangulation triangulation = start;
  LocalOptimisationOptions options;
  options.sweep_order_seed = seed;
  const bool is_l1 = row == Row::Abn1 || row == Row::Jnd1 || row == Row::Pf1 || row == Row::Pd1;
  options.ordering = is_l1 ? CostOrdering::L1 : CostOrdering::L2;
  LocalOptimisationSummary summary;
  if (row == Row::Equid) {
    const EquidistributionCriterion equid([f](double x, double y) { return hessian(f, x, y); });
    summary = optimise_locally(triangulation, equid, options);
  } else {
    switch (row) {
      case Row::Mwt3d:
        options.criterion = CriterionKind::MinimumWeight3d;
        break;
      case Row::Abn1:
      case Row::Abn2:
        options.criterion = CriterionKind::AngleBetweenNormals;
        break;
      case Row::Jnd1:
      case Row::Jnd2:
        options.criterion = CriterionKind::JumpInNormalDerivatives;
        break;
      case Row::Pf1:
      case Row::Pf2:
        options.criterion = CriterionKind::PlaneFit;
        break;
      default:
        options.criterion = CriterionKind::PlaneDistance;
        break;
    }
    summary = optimise_locally(triangulation, options);
  }
  EXPECT_TRUE(summary.is_locally_optimal()) << summary.brief_report();
  return interpolation_error(triangulation, [f](double x, double y) { return evaluate(f, x, y); })
      .mean;
}

// The data-dependent rows depend on the sweep order, which the report does not give. For each
// cell below, the report's printed value lies within the spread of our values over the 20
// sweep orders that `tessera ddt --orders 20` uses (seeds 0 … 19), up to half a unit of the
// printed last digit. The cells of Tables 1 and 2 that are not listed lie outside that spread;
// docs/algorithms/ddt.md has the full tables and says which and by how much.
TEST(MalcolmTables, ReportedDataDependentValuesLieWithinTheSweepOrderSpread) {
  using F = FrankeFunction;
  const struct {
    int points;
    F function;
    Row row;
    double report;  // Malcolm, Table 1 (33 points) or Table 2 (100 points)
  } cells[] = {
      // Table 1, 33 points: 44 of the 50 data-dependent cells.
      {33, F::F1, Row::Mwt3d, 0.05813},
      {33, F::F2, Row::Mwt3d, 0.01585},
      {33, F::F7, Row::Mwt3d, 0.06019},
      {33, F::F8, Row::Mwt3d, 0.09926},
      {33, F::F9, Row::Mwt3d, 0.04826},
      {33, F::F1, Row::Abn1, 0.04033},
      {33, F::F2, Row::Abn1, 0.00619},
      {33, F::F7, Row::Abn1, 0.04210},
      {33, F::F8, Row::Abn1, 0.13123},
      {33, F::F9, Row::Abn1, 0.04633},
      {33, F::F1, Row::Abn2, 0.03964},
      {33, F::F2, Row::Abn2, 0.00610},
      {33, F::F8, Row::Abn2, 0.07723},
      {33, F::F1, Row::Jnd1, 0.04033},
      {33, F::F2, Row::Jnd1, 0.01176},
      {33, F::F7, Row::Jnd1, 0.04562},
      {33, F::F8, Row::Jnd1, 0.10457},
      {33, F::F9, Row::Jnd1, 0.04639},
      {33, F::F1, Row::Jnd2, 0.04532},
      {33, F::F2, Row::Jnd2, 0.01107},
      {33, F::F7, Row::Jnd2, 0.04922},
      {33, F::F8, Row::Jnd2, 0.10456},
      {33, F::F9, Row::Jnd2, 0.04635},
      {33, F::F1, Row::Pf1, 0.04285},
      {33, F::F2, Row::Pf1, 0.00618},
      {33, F::F8, Row::Pf1, 0.14730},
      {33, F::F9, Row::Pf1, 0.04650},
      {33, F::F1, Row::Pf2, 0.04661},
      {33, F::F2, Row::Pf2, 0.01190},
      {33, F::F7, Row::Pf2, 0.05737},
      {33, F::F8, Row::Pf2, 0.15113},
      {33, F::F9, Row::Pf2, 0.04683},
      {33, F::F1, Row::Pd1, 0.05255},
      {33, F::F2, Row::Pd1, 0.00618},
      {33, F::F7, Row::Pd1, 0.04267},
      {33, F::F8, Row::Pd1, 0.11505},
      {33, F::F9, Row::Pd1, 0.04737},
      {33, F::F1, Row::Pd2, 0.05379},
      {33, F::F2, Row::Pd2, 0.01188},
      {33, F::F7, Row::Pd2, 0.04790},
      {33, F::F8, Row::Pd2, 0.11513},
      {33, F::F9, Row::Pd2, 0.04750},
      {33, F::F1, Row::Equid, 0.04541},
      {33, F::F9, Row::Equid, 0.04697},
      // Table 2, 100 points: 28 of the 50.
      {100, F::F7, Row::Mwt3d, 0.02869},
      {100, F::F2, Row::Abn1, 0.00145},
      {100, F::F7, Row::Abn1, 0.02027},
      {100, F::F1, Row::Abn2, 0.01550},
      {100, F::F2, Row::Abn2, 0.00147},
      {100, F::F7, Row::Abn2, 0.01727},
      {100, F::F8, Row::Abn2, 0.02839},
      {100, F::F1, Row::Jnd1, 0.01571},
      {100, F::F2, Row::Jnd1, 0.00145},
      {100, F::F7, Row::Jnd1, 0.02207},
      {100, F::F1, Row::Jnd2, 0.01533},
      {100, F::F2, Row::Jnd2, 0.00151},
      {100, F::F1, Row::Pf1, 0.01563},
      {100, F::F2, Row::Pf1, 0.00145},
      {100, F::F7, Row::Pf1, 0.01881},
      {100, F::F8, Row::Pf1, 0.03011},
      {100, F::F9, Row::Pf1, 0.01137},
      {100, F::F1, Row::Pf2, 0.01634},
      {100, F::F2, Row::Pf2, 0.00182},
      {100, F::F7, Row::Pf2, 0.02000},
      {100, F::F9, Row::Pf2, 0.01115},
      {100, F::F1, Row::Pd1, 0.01600},
      {100, F::F2, Row::Pd1, 0.00145},
      {100, F::F7, Row::Pd1, 0.02374},
      {100, F::F8, Row::Pd1, 0.02557},
      {100, F::F1, Row::Pd2, 0.01670},
      {100, F::F2, Row::Pd2, 0.00152},
      {100, F::F7, Row::Pd2, 0.02576},
  };
  constexpr unsigned kOrders = 20;
  constexpr double kHalfPrintedDigit = 0.5e-5 + 1e-12;
  for (const int points : {33, 100}) {
    const ScatteredData data = read_scattered_data_csv(testing::source_path(
        points == 33 ? "examples/data/franke33.csv" : "examples/data/franke100.csv"));
    for (const auto& cell : cells) {
      if (cell.points != points) {
        continue;
      }
      const PlanarTriangulation start =
          delaunay_triangulation(data.points, sample(cell.function, data.points));
      double lowest = 1e300;
      double highest = -1e300;
      for (unsigned seed = 0; seed < kOrders; ++seed) {
        const double mean = mean_error_after_lop(start, cell.function, cell.row, seed);
        lowest = std::min(lowest, mean);
        highest = std::max(highest, mean);
      }
      const std::string where = std::to_string(points) + " points, " + to_string(cell.row) + ", " +
                                to_string(cell.function);
      EXPECT_LE(lowest, cell.report + kHalfPrintedDigit)
          << where << ": spread " << lowest << " … " << highest;
      EXPECT_GE(highest, cell.report - kHalfPrintedDigit)
          << where << ": spread " << lowest << " … " << highest;
    }
  }
}

}  // namespace
}  // namespace tessera
