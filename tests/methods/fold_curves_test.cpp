// SPDX-License-Identifier: MIT
// Fold curves and cusps (methods/folds): held to exact curves (Whitney's pleat) and to an
// independent one-parameter fold computation (the Gelfand–Bratu BVP, amplitude continuation).
#include "tessera/methods/folds/fold_curves.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "tessera/core/error.h"
#include "tessera/methods/covering_methods.h"
#include "tessera/problems/catalogue.h"
#include "tessera/problems/examples.h"

namespace tessera {
namespace {

TEST(FoldCurves, WhitneyPleatFoldIsTheExactCurveAndItsCuspTheOrigin) {
  const ProblemSetup setup = make_catalogue_problem("whitney_pleat");
  MethodSettings settings;
  settings.tolerance = 0.01;
  const CoveringResult covering = cover(setup, covering_methods().front(), settings);
  ASSERT_TRUE(covering.summary.is_complete()) << covering.summary.message;
  const ParameterPlane plane = parse_parameter_plane("lambda,mu", *setup.problem);
  const FoldCurves folds = find_fold_curves(*setup.problem, covering.mesh, plane);

  // One fold curve, λ = 3x², μ = −2x³, crossing the box through the cusp at the origin.
  ASSERT_EQ(folds.curves.size(), 1u);
  EXPECT_FALSE(folds.curves[0].is_closed);
  EXPECT_EQ(folds.unrefined_count, 0);
  EXPECT_GT(folds.crossing_count, 20);
  ASSERT_EQ(folds.cusp_count, 1);
  double largest_error = 0.0;
  int cusps = 0;
  for (const FoldPoint& point : folds.curves[0].points) {
    ASSERT_TRUE(point.is_refined);
    const double x = point.x(0), lambda = point.x(1), mu = point.x(2);
    largest_error = std::max({largest_error, std::abs(lambda - 3 * x * x),
                              std::abs(mu + 2 * x * x * x), std::abs(x * x * x - lambda * x - mu)});
    if (point.is_cusp) {
      ++cusps;
      EXPECT_LT(point.x.norm(), 1e-8) << point.x.transpose();
    }
  }
  EXPECT_EQ(cusps, 1);
  EXPECT_LT(largest_error, 1e-8);
  // In order along the curve: x is monotone along the polyline.
  const auto& points = folds.curves[0].points;
  const double direction = points.back().x(0) - points.front().x(0);
  for (std::size_t i = 1; i < points.size(); ++i) {
    EXPECT_GT((points[i].x(0) - points[i - 1].x(0)) * direction, 0.0) << i;
  }
  // Both ends at the box: |λ| or |μ| = 1.5 ± a mesh edge.
  for (const FoldPoint* end : {&points.front(), &points.back()}) {
    EXPECT_GT(std::max(std::abs(end->x(1)), std::abs(end->x(2))), 1.3) << end->x.transpose();
  }
}

// The CSTR's steady states satisfy x2 = b x1 with b = B/(1 + β) and Da = x1 e^(−x2)/(1 − x1); over
// the (Da, B) plane M folds where d Da/d x1 = 0 at fixed B, i.e. b x1 (1 − x1) = 1, and the two
// fold branches meet in the cusp x1 = 1/2, b = 4: (Da, B) = (e^−2, 4(1 + β)).
TEST(FoldCurves, StirredTankReactorFoldsAreTheExactCurveWithTheCuspAtBFourOnePlusBeta) {
  const double beta = 0.5;
  const ProblemSetup setup = make_catalogue_problem("cstr:beta=0.5");
  const CoveringResult covering = cover(setup, covering_methods().front(), {});
  ASSERT_TRUE(covering.summary.is_complete()) << covering.summary.message;
  const FoldCurves folds =
      find_fold_curves(*setup.problem, covering.mesh, parse_parameter_plane("Da,B", *setup.problem));
  EXPECT_EQ(folds.unrefined_count, 0);
  ASSERT_EQ(folds.cusp_count, 1);
  int points = 0;
  for (const FoldCurve& curve : folds.curves) {
    for (const FoldPoint& point : curve.points) {
      ASSERT_TRUE(point.is_refined);
      ++points;
      const double x1 = point.x(0), x2 = point.x(1), Da = point.x(2), B = point.x(3);
      const double b = B / (1 + beta);
      EXPECT_NEAR(b * x1 * (1 - x1), 1.0, 1e-9) << point.x.transpose();
      EXPECT_NEAR(x2, b * x1, 1e-9 * (1 + std::abs(x2)));
      EXPECT_NEAR(Da, x1 * std::exp(-x2) / (1 - x1), 1e-9 * Da);
      if (point.is_cusp) {
        EXPECT_NEAR(x1, 0.5, 1e-8);
        EXPECT_NEAR(Da, std::exp(-2.0), 1e-9);
        EXPECT_NEAR(B, 4 * (1 + beta), 1e-8);
      }
    }
  }
  EXPECT_GT(points, 50);
}

// An independent one-parameter computation: at a fold point's ε, the branch of solutions with
// middle value a (ArrheniusBratu::point_with_amplitude, Newton's method with the amplitude fixed)
// has λ(a) extremal at the fold. Golden-section search finds the extremum without derivatives.
double extremal_lambda(const ArrheniusBratu& bvp, double epsilon, double amplitude, double width) {
  const int lambda = bvp.point_count();
  auto lambda_at = [&](double a) { return bvp.point_with_amplitude(a, epsilon)(lambda); };
  const double centre = lambda_at(amplitude);
  const double sign = lambda_at(amplitude - width) < centre ? 1.0 : -1.0;  // +1: a maximum
  double lo = amplitude - width, hi = amplitude + width;
  const double ratio = (std::sqrt(5.0) - 1) / 2;
  double c = hi - ratio * (hi - lo), d = lo + ratio * (hi - lo);
  double fc = sign * lambda_at(c), fd = sign * lambda_at(d);
  for (int iteration = 0; iteration < 60 && hi - lo > 1e-7; ++iteration) {
    if (fc > fd) {
      hi = d, d = c, fd = fc, c = hi - ratio * (hi - lo), fc = sign * lambda_at(c);
    } else {
      lo = c, c = d, fc = fd, d = lo + ratio * (hi - lo), fd = sign * lambda_at(d);
    }
  }
  return lambda_at(0.5 * (lo + hi));
}

TEST(FoldCurves, GelfandBratuFoldsAgreeWithOneParameterContinuationAndTheCuspIsNearTheLiterature) {
  const int N = 30;
  const ArrheniusBratu bvp(N);
  const ProblemSetup setup = make_catalogue_problem("bvp:points=30");
  const CoveringResult covering = cover(setup, covering_methods().front(), {});
  ASSERT_TRUE(covering.summary.is_complete()) << covering.summary.message;
  const FoldCurves folds = find_fold_curves(*setup.problem, covering.mesh,
                                            parse_parameter_plane("lambda,epsilon", *setup.problem));
  EXPECT_EQ(folds.unrefined_count, 0);
  ASSERT_EQ(folds.curves.size(), 1u);
  ASSERT_EQ(folds.cusp_count, 1);
  const auto& points = folds.curves[0].points;
  const int middle = (N + 1) / 2 - 1;
  int checked = 0;
  for (std::size_t i = 0; i < points.size(); i += points.size() / 8) {
    const Eigen::VectorXd& x = points[i].x;
    const double epsilon = x(N + 1);
    if (std::abs(epsilon - 0.2458) < 0.01 || epsilon < 0.01) {
      continue;  // at the cusp λ(a) is flat to third order: no sharp extremum to compare with;
                 // below ε = 0 (the box's edge, a fold point may lie just outside) no branch
    }
    const double expected = extremal_lambda(bvp, epsilon, x(middle), 0.05 * x(middle));
    EXPECT_NEAR(x(N), expected, 1e-8 * expected) << "fold point " << i << ", epsilon " << epsilon;
    ++checked;
  }
  EXPECT_GE(checked, 5);
  for (const FoldPoint& point : points) {
    if (point.is_cusp) {
      // Brown, Ibrahim & Shivaji: the continuous problem's cusp at ε ≈ 0.2457; 30 points are within
      // a few 10⁻⁴ of it (0.24578 at N = 100 and 1000, bench/RESULTS.md, "Fold curves and cusps").
      EXPECT_NEAR(point.x(N + 1), 0.2457, 2e-3);
    }
  }
}

// The torus (|x|² + R² − r²)² = 4R²(y² + z²) around the x axis, seen along it: M folds over the
// (y, z) plane along its outer and inner equators, two closed circles of radius R ± r, no cusps.
// Seen obliquely enough, the inner contour has four cusps, symmetric under (x, y, z) → (±x, ±y, ±z).
TEST(FoldCurves, TorusSeenAlongItsAxisFoldsAlongTwoCirclesAndObliquelyHasFourCusps) {
  const ProblemSetup setup = make_catalogue_problem("torus");
  const CoveringResult covering = cover(setup, covering_methods().front(), {});
  ASSERT_TRUE(covering.summary.is_complete()) << covering.summary.message;
  const FoldCurves along = find_fold_curves(*setup.problem, covering.mesh,
                                            parse_parameter_plane("y,z", *setup.problem));
  ASSERT_EQ(along.curves.size(), 2u);
  EXPECT_EQ(along.cusp_count, 0);
  std::vector<double> radii;
  for (const FoldCurve& curve : along.curves) {
    EXPECT_TRUE(curve.is_closed);
    const double radius = std::hypot(curve.points[0].x(1), curve.points[0].x(2));
    radii.push_back(radius);
    for (const FoldPoint& point : curve.points) {
      EXPECT_NEAR(point.x(0), 0.0, 1e-9);
      EXPECT_NEAR(std::hypot(point.x(1), point.x(2)), radius, 1e-9);
    }
  }
  std::sort(radii.begin(), radii.end());
  EXPECT_NEAR(radii[0], 0.6, 1e-9);
  EXPECT_NEAR(radii[1], 1.4, 1e-9);

  const FoldCurves oblique = find_fold_curves(
      *setup.problem, covering.mesh, parse_parameter_plane("y, w = z + 2*x", *setup.problem));
  EXPECT_EQ(oblique.unrefined_count, 0);
  ASSERT_EQ(oblique.cusp_count, 4);
  std::vector<Eigen::Vector3d> cusps;
  for (const FoldCurve& curve : oblique.curves) {
    for (const FoldPoint& point : curve.points) {
      if (point.is_cusp) {
        cusps.push_back(point.x.head<3>().cwiseAbs());
      }
    }
  }
  for (const Eigen::Vector3d& cusp : cusps) {
    EXPECT_LT((cusp - cusps[0]).norm(), 1e-8) << cusp.transpose() << " vs " << cusps[0].transpose();
  }
}

// The flat torus x1² + x2² = 1, x3² + x4² = 1 maps onto the unit circle of the (x1, x2) plane:
// Dπ·T has rank 1 everywhere, M folds along no curve, and every triangle is reported singular.
TEST(FoldCurves, APlaneSingularOnAllOfMGivesNoCurvesAndSaysSo) {
  const ProblemSetup setup = make_catalogue_problem("flat_torus");
  MethodSettings settings;
  settings.tolerance = 0.01;
  const CoveringResult covering = cover(setup, covering_methods().front(), settings);
  ASSERT_TRUE(covering.summary.is_complete()) << covering.summary.message;
  const FoldCurves folds = find_fold_curves(*setup.problem, covering.mesh,
                                            parse_parameter_plane("x1,x2", *setup.problem));
  EXPECT_EQ(folds.curves.size(), 0u);
  EXPECT_EQ(folds.singular_triangle_count, covering.mesh.triangle_count());
}

TEST(FoldCurves, RefusesANonDifferentiablePlaneAndAWrongDimension) {
  const ProblemSetup bvp = make_catalogue_problem("bvp:points=20");
  EXPECT_THROW(parse_parameter_plane("lambda,max:u", *bvp.problem), InvalidArgument);
  EXPECT_THROW(parse_parameter_plane("lambda", *bvp.problem), InvalidArgument);
  EXPECT_THROW(parse_parameter_plane("lambda,epsilon,mean:u", *bvp.problem), InvalidArgument);
  const ProblemSetup pleat = make_catalogue_problem("whitney_pleat");
  const ParameterPlane plane = parse_parameter_plane("lambda,mu", *pleat.problem);
  EXPECT_THROW(find_fold_curves(*bvp.problem, TriangleMesh(3), plane), InvalidArgument);
}

}  // namespace
}  // namespace tessera
