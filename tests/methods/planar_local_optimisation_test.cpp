// SPDX-License-Identifier: MIT
// Lawson's LOP: every criterion lowers (or keeps) its own total cost, terminates and keeps
// the triangulation valid.
#include "tessera/methods/planar/local_optimisation.h"

#include <gtest/gtest.h>

#include "methods/planar_test_support.h"
#include "tessera/core/error.h"
#include "tessera/methods/planar/delaunay.h"
#include "tessera/methods/planar/equidistribution_criterion.h"
#include "tessera/methods/planar/franke_functions.h"

namespace tessera {
namespace {

constexpr CriterionKind kAllCriteria[] = {
    CriterionKind::Delaunay,
    CriterionKind::MinimumWeight,
    CriterionKind::MaxMinAngle3d,
    CriterionKind::MinimumWeight3d,
    CriterionKind::AngleBetweenNormals,
    CriterionKind::JumpInNormalDerivatives,
    CriterionKind::PlaneFit,
    CriterionKind::PlaneDistance,
};
constexpr CostOrdering kAllOrderings[] = {CostOrdering::L1, CostOrdering::L2,
                                          CostOrdering::Lexicographic};

// True if the non-increasing vector `after` is lexicographically not greater than `before`,
// up to a relative `tolerance` per entry.
bool is_lexicographically_not_greater(const std::vector<double>& after,
                                      const std::vector<double>& before, double tolerance) {
  for (std::size_t i = 0; i < std::min(after.size(), before.size()); ++i) {
    const double scale = std::max({std::abs(after[i]), std::abs(before[i]), 1e-300});
    if (std::abs(after[i] - before[i]) > tolerance * scale) {
      return after[i] < before[i];
    }
  }
  return true;
}

void expect_same_shape(const PlanarTriangulation& before, const PlanarTriangulation& after,
                       const std::string& context) {
  std::string why;
  EXPECT_TRUE(after.is_valid(&why)) << context << ": " << why;
  EXPECT_EQ(after.triangle_count(), before.triangle_count()) << context;
  EXPECT_EQ(after.boundary_edges(), before.boundary_edges()) << context;
  EXPECT_EQ(after.points(), before.points()) << context;
}

// With the global test a swap changes only the costs it compares (the diagonal and the four
// outer edges), so the total cost in the chosen ordering cannot rise.
TEST(PlanarLocalOptimisation, GlobalTestLowersOrKeepsTheTotalCostOfEveryCriterion) {
  for (unsigned seed = 1; seed <= 4; ++seed) {
    const Eigen::Matrix2Xd points = testing::random_points(40, seed);
    const PlanarTriangulation delaunay =
        delaunay_triangulation(points, sample(FrankeFunction::F1, points));
    for (CriterionKind kind : kAllCriteria) {
      const auto criterion = make_criterion(kind);
      for (CostOrdering ordering : kAllOrderings) {
        const std::string context = to_string(kind) + " ordering " +
                                    std::to_string(static_cast<int>(ordering)) + " seed " +
                                    std::to_string(seed);
        PlanarTriangulation triangulation = delaunay;
        const auto costs_before = triangulation_costs(triangulation, *criterion, ordering);
        const double before = total_cost(triangulation, *criterion, ordering);
        const LocalOptimisationSummary summary = optimise_locally(
            triangulation, *criterion, {.ordering = ordering, .test = SwapTest::Global});
        EXPECT_TRUE(summary.is_locally_optimal()) << context << ": " << summary.brief_report();
        expect_same_shape(delaunay, triangulation, context);
        const auto costs_after = triangulation_costs(triangulation, *criterion, ordering);
        if (criterion->kind() == SwapCriterion::Kind::TriangleAngles ||
            ordering == CostOrdering::Lexicographic) {
          // Max-min angle criteria compare sorted (negated) angles lexicographically.
          EXPECT_TRUE(is_lexicographically_not_greater(costs_after, costs_before, 1e-9)) << context;
        } else {
          // Each swap lowers the total by more than the LOP's relative tolerance of the quad's
          // cost; rounding in the sum is far below 1e-9 relative.
          EXPECT_LE(total_cost(triangulation, *criterion, ordering), before * (1 + 1e-9))
              << context;
        }
      }
    }
  }
}

// f = x² + 10 y² + 3xy has a constant Hessian: EQUID then prefers the diagonal in the
// direction of least curvature, and its total cost must not rise.
TEST(PlanarLocalOptimisation, EquidistributionLowersItsTotalCost) {
  const EquidistributionCriterion equid([](double, double) {
    Eigen::Matrix2d H;
    H << 2, 3, 3, 20;
    return H;
  });
  for (unsigned seed = 31; seed <= 33; ++seed) {
    const Eigen::Matrix2Xd points = testing::random_points(40, seed);
    const PlanarTriangulation delaunay = delaunay_triangulation(points, Eigen::VectorXd());
    for (SwapTest test : {SwapTest::Local, SwapTest::Global}) {
      PlanarTriangulation triangulation = delaunay;
      const double before = total_cost(triangulation, equid, CostOrdering::L1);
      const LocalOptimisationSummary summary =
          optimise_locally(triangulation, equid, {.ordering = CostOrdering::L1, .test = test});
      EXPECT_TRUE(summary.is_locally_optimal()) << summary.brief_report();
      EXPECT_GT(summary.swaps, 0) << summary.brief_report();
      expect_same_shape(delaunay, triangulation, summary.brief_report());
      // The cost of an edge depends on the edge alone, so even the local test lowers the sum.
      EXPECT_LT(total_cost(triangulation, equid, CostOrdering::L1), before);
    }
  }
}

TEST(PlanarLocalOptimisation, LocalTestTerminatesAndKeepsTheTriangulationValid) {
  for (unsigned seed = 11; seed <= 13; ++seed) {
    const Eigen::Matrix2Xd points = testing::random_points(40, seed);
    const PlanarTriangulation delaunay =
        delaunay_triangulation(points, sample(FrankeFunction::F2, points));
    for (CriterionKind kind : kAllCriteria) {
      for (CostOrdering ordering : kAllOrderings) {
        PlanarTriangulation triangulation = delaunay;
        const LocalOptimisationSummary summary = optimise_locally(
            triangulation,
            {.criterion = kind, .ordering = ordering, .test = SwapTest::Local, .max_sweeps = 200});
        const std::string context = summary.brief_report() + " seed " + std::to_string(seed);
        EXPECT_TRUE(summary.is_locally_optimal()) << context;
        expect_same_shape(delaunay, triangulation, context);
      }
    }
  }
}

TEST(PlanarLocalOptimisation, DelaunayCriterionLeavesADelaunayTriangulationAlone) {
  const Eigen::Matrix2Xd points = testing::random_points(60, 21);
  PlanarTriangulation triangulation = delaunay_triangulation(points, Eigen::VectorXd());
  const LocalOptimisationSummary summary =
      optimise_locally(triangulation, {.criterion = CriterionKind::Delaunay});
  EXPECT_EQ(summary.swaps, 0) << summary.brief_report();
  EXPECT_EQ(summary.sweeps, 1);
}

// Lawson: swapping to the max-min angle diagonal from any triangulation reaches the Delaunay
// triangulation (here from the one ABN leaves, which has long thin triangles).
TEST(PlanarLocalOptimisation, DelaunayCriterionRestoresEmptyCircumcircles) {
  const Eigen::Matrix2Xd points = testing::random_points(50, 22);
  PlanarTriangulation triangulation =
      delaunay_triangulation(points, sample(FrankeFunction::F2, points));
  const LocalOptimisationSummary abn = optimise_locally(triangulation, {});
  ASSERT_GT(abn.swaps, 0) << "the test needs a triangulation that is not Delaunay";
  ASSERT_GT(testing::count_circumcircle_violations(triangulation), 0);
  const LocalOptimisationSummary summary =
      optimise_locally(triangulation, {.criterion = CriterionKind::Delaunay});
  EXPECT_TRUE(summary.is_locally_optimal());
  EXPECT_EQ(testing::count_circumcircle_violations(triangulation), 0);
}

TEST(PlanarLocalOptimisation, LinearDataNeedsNoSwapForTheNearlyC1AndPlanarCriteria) {
  const Eigen::Matrix2Xd points = testing::random_points(40, 23);
  const Eigen::VectorXd linear = (2.0 * points.row(0) - 3.0 * points.row(1)).transpose();
  for (CriterionKind kind :
       {CriterionKind::AngleBetweenNormals, CriterionKind::JumpInNormalDerivatives,
        CriterionKind::PlaneFit, CriterionKind::PlaneDistance}) {
    PlanarTriangulation triangulation = delaunay_triangulation(points, linear);
    const LocalOptimisationSummary summary = optimise_locally(triangulation, {.criterion = kind});
    EXPECT_EQ(summary.swaps, 0) << summary.brief_report();
  }
}

TEST(PlanarLocalOptimisation, AbnSwapsTowardsTheCliffOfF2) {
  // F2 has a cliff along y = x: ABN should align edges with it and lower its cost.
  const Eigen::Matrix2Xd points = testing::random_points(60, 24);
  PlanarTriangulation triangulation =
      delaunay_triangulation(points, sample(FrankeFunction::F2, points));
  const auto abn = make_criterion(CriterionKind::AngleBetweenNormals);
  const double before = total_cost(triangulation, *abn, CostOrdering::L2);
  const LocalOptimisationSummary summary = optimise_locally(triangulation, *abn, {});
  EXPECT_GT(summary.swaps, 0);
  EXPECT_LT(total_cost(triangulation, *abn, CostOrdering::L2), before);
}

// On a square grid both diagonals of every cell have the same length: MWT sees only
// equalities there, which strategies (i) and (ii) swap, and must still stop.
TEST(PlanarLocalOptimisation, StrategiesThatSwapOnEqualCostsTerminate) {
  const int m = 6;
  Eigen::Matrix2Xd points(2, m * m);
  for (int i = 0; i < m; ++i) {
    for (int j = 0; j < m; ++j) {
      points.col(i * m + j) = Eigen::Vector2d(i, j) / (m - 1);
    }
  }
  const PlanarTriangulation delaunay =
      delaunay_triangulation(points, sample(FrankeFunction::F1, points));
  for (SwapStrategy strategy :
       {SwapStrategy::Strict, SwapStrategy::EqualFirst, SwapStrategy::EqualSweep}) {
    for (CriterionKind kind : {CriterionKind::MinimumWeight, CriterionKind::AngleBetweenNormals,
                               CriterionKind::Delaunay}) {
      PlanarTriangulation triangulation = delaunay;
      const auto criterion = make_criterion(kind);
      const double before = total_cost(triangulation, *criterion, CostOrdering::L1);
      const LocalOptimisationSummary summary =
          optimise_locally(triangulation, *criterion,
                           {.ordering = CostOrdering::L1, .strategy = strategy, .max_sweeps = 100});
      const std::string context =
          summary.brief_report() + " strategy " + std::to_string(static_cast<int>(strategy));
      EXPECT_TRUE(summary.is_locally_optimal()) << context;
      expect_same_shape(delaunay, triangulation, context);
      if (criterion->kind() == SwapCriterion::Kind::EdgeCost) {
        EXPECT_LE(total_cost(triangulation, *criterion, CostOrdering::L1), before * (1 + 1e-9))
            << context;
      }
      if (strategy == SwapStrategy::Strict) {
        EXPECT_EQ(summary.equal_swaps, 0) << context;
      } else if (kind == CriterionKind::MinimumWeight) {
        EXPECT_GT(summary.equal_swaps, 0) << context;
      }
    }
  }
}

TEST(PlanarLocalOptimisation, SweepLimitIsReportedNotThrown) {
  const Eigen::Matrix2Xd points = testing::random_points(60, 25);
  PlanarTriangulation triangulation =
      delaunay_triangulation(points, sample(FrankeFunction::F2, points));
  const LocalOptimisationSummary summary = optimise_locally(triangulation, {.max_sweeps = 1});
  EXPECT_EQ(summary.termination, LocalOptimisationTermination::SweepLimit);
  EXPECT_NE(summary.brief_report().find("sweep limit"), std::string::npos);
  EXPECT_TRUE(triangulation.is_valid());
}

TEST(PlanarLocalOptimisation, RefusesInvalidOptions) {
  const Eigen::Matrix2Xd points = testing::random_points(10, 26);
  PlanarTriangulation triangulation = delaunay_triangulation(points, Eigen::VectorXd());
  EXPECT_THROW(optimise_locally(triangulation, {.max_sweeps = 0}), InvalidArgument);
  EXPECT_THROW(optimise_locally(triangulation, {.relative_tolerance = -1}), InvalidArgument);
}

TEST(PlanarLocalOptimisation, CriterionNamesRoundTrip) {
  for (CriterionKind kind : kAllCriteria) {
    EXPECT_EQ(parse_criterion(to_string(kind)), kind);
  }
  EXPECT_FALSE(parse_criterion("equid").has_value());
}

}  // namespace
}  // namespace tessera
