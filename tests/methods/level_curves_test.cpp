// SPDX-License-Identifier: MIT
// Level curves of a functional on M (methods/folds/level_curves): held to curves known in closed
// form (great and small circles of the sphere, the CSTR at fixed B) and, for max:u, to the
// definition itself.
#include "tessera/methods/folds/level_curves.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "tessera/core/error.h"
#include "tessera/geometry/mesh_topology.h"
#include "tessera/methods/covering_methods.h"
#include "tessera/problems/catalogue.h"
#include "tessera/problems/examples.h"

namespace tessera {
namespace {

double polyline_length(const LevelCurve& curve) {
  double length = 0.0;
  const std::size_t m = curve.points.size();
  for (std::size_t i = 0; i + 1 < m; ++i) {
    length += (curve.points[i + 1].x - curve.points[i].x).norm();
  }
  if (curve.is_closed && m > 1) {
    length += (curve.points.front().x - curve.points.back().x).norm();
  }
  return length;
}

double longest_edge(const TriangleMesh& mesh) {
  const MeshTopology topology(mesh);
  double longest = 0.0;
  for (const auto& edge : topology.edges()) {
    longest = std::max(longest, (mesh.point(edge[1]) - mesh.point(edge[0])).norm());
  }
  return longest;
}

CoveringResult cover_catalogue(const ProblemSetup& setup) {
  CoveringResult covering = cover(setup, covering_methods().front(), {});
  EXPECT_TRUE(covering.summary.is_complete()) << covering.summary.message;
  return covering;
}

// x = 0 on the unit sphere is a great circle: one closed polyline whose points lie on the sphere
// and on the plane to solver tolerance. Its chords are shorter than the arcs they cut, by at most
// s³/24 for a chord s ≤ the longest edge h (a chord crosses one triangle): 0 ≤ 2π − L ≤ 2π h²/24.
TEST(LevelCurves, TheLevelSetXZeroOfTheUnitSphereIsAGreatCircle) {
  const ProblemSetup setup = make_catalogue_problem("sphere");
  const CoveringResult covering = cover_catalogue(setup);
  const LevelCurves level =
      find_level_curves(*setup.problem, covering.mesh, parse_level_set("x=0", *setup.problem));
  ASSERT_EQ(level.curves.size(), 1u);
  const LevelCurve& circle = level.curves[0];
  EXPECT_TRUE(circle.is_closed);
  EXPECT_EQ(level.unrefined_count, 0);
  EXPECT_EQ(level.point_count(), level.crossing_count);
  EXPECT_GT(level.crossing_count, 20);
  for (const LevelPoint& point : circle.points) {
    ASSERT_TRUE(point.is_refined);
    EXPECT_NEAR(point.x.norm(), 1.0, 1e-10) << point.x.transpose();
    EXPECT_NEAR(point.x(0), 0.0, 1e-10) << point.x.transpose();
    EXPECT_LE(point.residual, 1e-9);
  }
  const double h = longest_edge(covering.mesh);
  const double length = polyline_length(circle);
  EXPECT_LE(length, 2 * std::numbers::pi);
  EXPECT_LE(2 * std::numbers::pi - length, 2 * std::numbers::pi * h * h / 24) << "h = " << h;
  // Newton from the linear estimate converges quadratically: a few iterations per point.
  EXPECT_LE(level.max_point_iterations, 5);
  EXPECT_LE(level.max_residual, 1e-9);
  EXPECT_GT(level.work.factorisations, 0);
}

// An expression, unnamed: x² + y² = 1/2 on the unit sphere is the two circles z = ±1/√2.
TEST(LevelCurves, AnExpressionLevelSetOfTheSphereIsTwoSmallCircles) {
  const ProblemSetup setup = make_catalogue_problem("sphere");
  const CoveringResult covering = cover_catalogue(setup);
  const LevelSet set = parse_level_set("x^2 + y^2 = 0.5", *setup.problem);
  const LevelCurves level = find_level_curves(*setup.problem, covering.mesh, set);
  ASSERT_EQ(level.curves.size(), 2u);
  EXPECT_EQ(level.unrefined_count, 0);
  for (const LevelCurve& curve : level.curves) {
    EXPECT_TRUE(curve.is_closed);
    for (const LevelPoint& point : curve.points) {
      EXPECT_NEAR(std::abs(point.x(2)), std::sqrt(0.5), 1e-10) << point.x.transpose();
      EXPECT_NEAR(point.x.norm(), 1.0, 1e-10);
    }
  }
}

// The CSTR at fixed B is the curve x₂ = b x₁, Da = x₁e^{−x₂}/(1 − x₁), b = B/(1 + β)
// (StirredTankReactor::point_on_manifold). B = 6 crosses the box [0.02, 1] × [0, 8] × [0, 0.3] ×
// [1, 12] from x₁ = 0.02 to Da = 0.3: one open curve whose ends lie at the clipped mesh's
// boundary, in order of x₁ along it.
TEST(LevelCurves, TheStirredTankAtFixedBIsItsExactParametrisationAcrossTheClippedBox) {
  const ProblemSetup setup = make_catalogue_problem("cstr:beta=0.5");
  const auto& reactor = dynamic_cast<const StirredTankReactor&>(*setup.problem);
  const CoveringResult covering = cover_catalogue(setup);
  const LevelCurves level =
      find_level_curves(*setup.problem, covering.mesh, parse_level_set("B = 6", *setup.problem));
  ASSERT_EQ(level.curves.size(), 1u);
  const LevelCurve& curve = level.curves[0];
  EXPECT_FALSE(curve.is_closed);
  EXPECT_EQ(level.unrefined_count, 0);
  EXPECT_GT(curve.points.size(), 10u);
  double largest_error = 0.0;
  for (const LevelPoint& point : curve.points) {
    ASSERT_TRUE(point.is_refined);
    EXPECT_NEAR(point.x(3), 6.0, 1e-12);
    const Eigen::VectorXd exact = reactor.point_on_manifold(point.x(0), 6.0);
    largest_error = std::max(largest_error, (point.x - exact).norm());
  }
  EXPECT_LT(largest_error, 1e-9);
  const double direction = curve.points.back().x(0) - curve.points.front().x(0);
  for (std::size_t i = 1; i < curve.points.size(); ++i) {
    EXPECT_GT((curve.points[i].x(0) - curve.points[i - 1].x(0)) * direction, 0.0) << i;
  }
  // The ends: at x₁ = 0.02 and at Da = 0.3, within a mesh edge.
  const double h = longest_edge(covering.mesh);
  const Eigen::VectorXd& low = direction > 0 ? curve.points.front().x : curve.points.back().x;
  const Eigen::VectorXd& high = direction > 0 ? curve.points.back().x : curve.points.front().x;
  EXPECT_LT(std::abs(low(0) - 0.02), h) << low.transpose();
  EXPECT_LT(std::abs(high(2) - 0.3), h) << high.transpose();
}

// A hemisphere (the triangles of the sphere above z = 0): x = 0 is a half circle, open, from the
// cut to the cut.
TEST(LevelCurves, AHalfGreatCircleOnAHemisphereIsOpenWithBothEndsAtTheBoundary) {
  const ProblemSetup setup = make_catalogue_problem("sphere");
  const CoveringResult covering = cover_catalogue(setup);
  std::vector<Triangle> upper;
  for (const Triangle& t : covering.mesh.triangles()) {
    if (covering.mesh.point(t[0])(2) + covering.mesh.point(t[1])(2) + covering.mesh.point(t[2])(2) >
        0.0) {
      upper.push_back(t);
    }
  }
  const TriangleMesh hemisphere(covering.mesh.points(), upper);
  const LevelCurves level =
      find_level_curves(*setup.problem, hemisphere, parse_level_set("x=0", *setup.problem));
  ASSERT_EQ(level.curves.size(), 1u);
  const LevelCurve& arc = level.curves[0];
  EXPECT_FALSE(arc.is_closed);
  const double h = longest_edge(covering.mesh);
  EXPECT_LT(std::abs(arc.points.front().x(2)), h);
  EXPECT_LT(std::abs(arc.points.back().x(2)), h);
  for (const LevelPoint& point : arc.points) {
    ASSERT_TRUE(point.is_refined);
    EXPECT_NEAR(point.x(0), 0.0, 1e-10);
    EXPECT_NEAR(point.x.norm(), 1.0, 1e-10);
  }
}

// max:u is not differentiable where the maximum changes place; Newton holds the coordinate that
// attains it and the point is accepted only if it still does. On the Bratu BVP the maximum is the
// middle value, so every point is refined; mean:u (differentiable) likewise.
TEST(LevelCurves, BlockMaximumAndMeanLevelsOfTheBratuProblemHoldAtEveryPoint) {
  const int N = 20;
  const ProblemSetup setup = make_catalogue_problem("bvp:points=20");
  const CoveringResult covering = cover_catalogue(setup);
  for (const char* functional : {"max:u", "mean:u"}) {
    const View view = parse_view(functional, *setup.problem);
    const Eigen::MatrixXd values = view.evaluate_columns(covering.mesh.points());
    const double c = 0.5 * (values.minCoeff() + values.maxCoeff());
    const LevelCurves level = find_level_curves(*setup.problem, covering.mesh, view, c);
    EXPECT_GE(level.curves.size(), 1u) << functional;
    EXPECT_EQ(level.unrefined_count, 0) << functional;
    for (const LevelCurve& curve : level.curves) {
      for (const LevelPoint& point : curve.points) {
        ASSERT_TRUE(point.is_refined) << functional;
        EXPECT_NEAR(view.evaluate(point.x)(0), c, 1e-9 * (1 + c)) << functional;
        EXPECT_LE(point.residual, 1e-9);
      }
    }
    EXPECT_LE(level.max_point_iterations, 6) << functional;
    EXPECT_EQ(covering.mesh.ambient_dimension(), N + 2);
  }
}

TEST(LevelCurves, BadSpecificationsAreRefusedNamingTheMistake) {
  const ProblemSetup setup = make_catalogue_problem("sphere");
  auto message_of = [&](const std::string& specification) {
    try {
      parse_level_set(specification, *setup.problem);
    } catch (const InvalidArgument& error) {
      return std::string(error.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(message_of("x").find("no '='"), std::string::npos) << message_of("x");
  EXPECT_NE(message_of("x=").find("no value"), std::string::npos) << message_of("x=");
  EXPECT_NE(message_of("=1").find("no functional"), std::string::npos) << message_of("=1");
  EXPECT_NE(message_of("x=abc").find("'abc' is not a number"), std::string::npos);
  EXPECT_NE(message_of("x=inf").find("not finite"), std::string::npos) << message_of("x=inf");
  EXPECT_NE(message_of("x=nan").find("not finite"), std::string::npos);
  // The view parser's message: names the item and lists the coordinates.
  const std::string unknown = message_of("w=1");
  EXPECT_NE(unknown.find("'w' is no coordinate"), std::string::npos) << unknown;
  EXPECT_NE(unknown.find("x, y, z"), std::string::npos) << unknown;
  EXPECT_NE(message_of("x, y = 1").find("a level set needs one"), std::string::npos)
      << message_of("x, y = 1");
  EXPECT_NE(message_of("x^2 + = 1"), "no error");
  // Named expressions keep their own '='; the value is after the last one.
  const LevelSet named = parse_level_set("r = sqrt(x^2 + y^2) = 0.5", *setup.problem);
  EXPECT_EQ(named.functional.names()[0], "r");
  EXPECT_DOUBLE_EQ(named.value, 0.5);
  EXPECT_EQ(parse_level_set(named.specification(), *setup.problem).functional.specification(),
            named.functional.specification());
  // The mesh and the functional must be of the problem's R^n.
  const ProblemSetup pleat = make_catalogue_problem("bvp:points=20");
  EXPECT_THROW(find_level_curves(*pleat.problem, TriangleMesh(3), named), InvalidArgument);
  EXPECT_THROW(find_level_curves(*setup.problem, TriangleMesh(3), named.functional, NAN),
               InvalidArgument);
}

}  // namespace
}  // namespace tessera
