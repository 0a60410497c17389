// SPDX-License-Identifier: MIT
// Acceptance tests of the advancing-front method: every catalogue example it is meant to handle
// is covered by a valid mesh of the right topology that lies on M, inside S and reaches ∂S;
// the mesh converges to M at the rate of piecewise-linear interpolation; runs are reproducible;
// bad options and bad starts are refused with messages that name them.
#include "tessera/methods/front/advancing_front.h"

#include <gtest/gtest.h>

#include <Eigen/Core>
#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

#include "support/front_run.h"
#include "support/test_support.h"
#include "tessera/core/corrector.h"
#include "tessera/core/error.h"
#include "tessera/geometry/mesh_quality.h"
#include "tessera/geometry/mesh_topology.h"
#include "tessera/geometry/mesh_validation.h"
#include "tessera/methods/start_point.h"
#include "tessera/problems/catalogue.h"

namespace tessera {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInfinity = std::numeric_limits<double>::infinity();

// Every vertex is the end point of a corrector run that stopped at ‖F‖ ≤ residual_tolerance
// (1e-9): the method's chord projections, the start's Gauss–Newton and the clipping's projection
// onto M ∩ face all use the default. A factor 10 leaves room for rounding in F itself.
const double kOnManifoldTolerance = 10.0 * CorrectorOptions{}.residual_tolerance;
// Vertices clipped onto a face b·(x − p) = 0 satisfy that equation as part of the same corrected
// system, so their distance to the face obeys the same bound.
const double kOnFaceTolerance = kOnManifoldTolerance;
// Domain::contains tolerance: a vertex on a face may lie outside it by that residual, no more.
constexpr double kInsideTolerance = 1e-9;

using testing::FrontRun;
using testing::run_front;

std::string describe_point(const Eigen::VectorXd& x) {
  std::string text = "(";
  for (Eigen::Index i = 0; i < x.size(); ++i) {
    char number[32];
    std::snprintf(number, sizeof number, "%s%.6g", i ? ", " : "", x(i));
    text += number;
  }
  return text + ")";
}

// Largest ‖F(x)‖ over the vertices, and the vertex where it occurs.
std::pair<double, int> max_vertex_residual(const TriangleMesh& mesh,
                                           const ImplicitProblem& problem) {
  Eigen::VectorXd F(problem.equation_count());
  std::pair<double, int> worst{0.0, -1};
  for (int v = 0; v < mesh.vertex_count(); ++v) {
    problem.evaluate(mesh.point(v), F);
    const double residual = F.allFinite() ? F.norm() : kInfinity;
    if (residual > worst.first || worst.second < 0) {
      worst = {residual, v};
    }
  }
  return worst;
}

// Distance of x to the nearest bounding hyperplane of `domain`, whichever side it is on.
double distance_to_domain_boundary(const Domain& domain, const Eigen::VectorXd& x) {
  double nearest = kInfinity;
  for (int k = 0; k < static_cast<int>(domain.half_spaces().size()); ++k) {
    nearest = std::min(nearest, std::abs(domain.signed_distance(k, x)));
  }
  return nearest;
}

// --- Every example the method is meant to handle -------------------------------------------

class FrontCoversExample : public ::testing::TestWithParam<std::string> {};

TEST_P(FrontCoversExample, WithAValidMeshOfMIntersectS) {
  const FrontRun run = run_front(GetParam());
  const ProblemSetup& setup = run.setup;
  const TriangleMesh& mesh = run.result.mesh;
  const CoveringSummary& summary = run.result.summary;

  EXPECT_TRUE(summary.is_complete()) << to_string(summary.termination) << ": " << summary.message;
  EXPECT_EQ(summary.vertex_count, mesh.vertex_count());
  EXPECT_EQ(summary.triangle_count, mesh.triangle_count());
  ASSERT_GT(mesh.triangle_count(), 0);

  const MeshValidation validation = validate(mesh);
  EXPECT_TRUE(validation.is_valid()) << validation.report();
  // The method covers the one component of M ∩ S that contains the start.
  EXPECT_EQ(validation.component_count, 1) << validation.report();
  ASSERT_TRUE(setup.expected_euler_characteristic.has_value());
  EXPECT_EQ(validation.euler_characteristic, *setup.expected_euler_characteristic)
      << validation.report();

  const auto [residual, worst_vertex] = max_vertex_residual(mesh, *setup.problem);
  EXPECT_LE(residual, kOnManifoldTolerance)
      << "vertex " << worst_vertex << " " << describe_point(mesh.point(worst_vertex));

  int outside = 0;
  for (int v = 0; v < mesh.vertex_count(); ++v) {
    if (!setup.domain.contains(mesh.point(v), kInsideTolerance)) {
      if (outside++ < 3) {
        ADD_FAILURE() << "vertex " << v << " " << describe_point(mesh.point(v))
                      << " lies outside the domain by "
                      << -setup.domain.boundary_distance(mesh.point(v)).signed_distance;
      }
    }
  }
  EXPECT_EQ(outside, 0);

  if (setup.domain.is_unbounded()) {
    // M is compact and S = R^n: M itself is covered, so the mesh has no boundary.
    EXPECT_TRUE(validation.is_closed()) << validation.report();
    return;
  }
  // The boundary of M ∩ S lies on ∂S. A boundary vertex strictly inside S would be a hole or an
  // uncovered part of M ∩ S; every boundary vertex on ∂S means the mesh reaches the boundary.
  const MeshTopology topology(mesh);
  EXPECT_TRUE(topology.has_boundary());
  std::vector<char> is_boundary_vertex(mesh.vertex_count(), 0);
  for (const int e : topology.boundary_edges()) {
    for (const int v : topology.edge(e)) {
      is_boundary_vertex[v] = 1;
    }
  }
  int off_boundary = 0;
  for (int v = 0; v < mesh.vertex_count(); ++v) {
    if (!is_boundary_vertex[v]) {
      continue;
    }
    const double distance = distance_to_domain_boundary(setup.domain, mesh.point(v));
    if (distance > kOnFaceTolerance && off_boundary++ < 3) {
      ADD_FAILURE() << "boundary vertex " << v << " " << describe_point(mesh.point(v))
                    << " is at distance " << distance << " from the domain boundary";
    }
  }
  EXPECT_EQ(off_boundary, 0) << "boundary vertices off the domain boundary";
}

std::string test_name(const ::testing::TestParamInfo<std::string>& info) {
  std::string name = info.param;
  std::replace_if(
      name.begin(), name.end(), [](char c) { return !std::isalnum(static_cast<unsigned char>(c)); },
      '_');
  return name;
}

// bvp with N = 8 interior points (n = 10) keeps the test fast and still has both folds and the
// cusp; its suggested step scales with √N.
INSTANTIATE_TEST_SUITE_P(Catalogue, FrontCoversExample,
                         ::testing::Values("plane", "sphere", "sphere_cut", "torus",
                                           "equipotential", "whitney_pleat", "trough", "cstr",
                                           "bvp:points=8"),
                         test_name);

// --- Convergence -------------------------------------------------------------------------------

const std::vector<double> kSteps = {0.4, 0.2, 0.1, 0.05};

TEST(FrontConvergence, SphereCentroidDistanceAndAreaAreSecondOrder) {
  std::vector<double> centroid_distance;
  std::vector<double> area_error;
  for (const double h : kSteps) {
    const FrontRun run = run_front("sphere", h);
    ASSERT_TRUE(run.result.summary.is_complete())
        << "h = " << h << ": " << run.result.summary.message;
    const MeshValidation validation = validate(run.result.mesh);
    EXPECT_TRUE(validation.is_valid()) << "h = " << h << "\n" << validation.report();
    EXPECT_EQ(validation.euler_characteristic, 2) << "h = " << h;
    const MeshQuality quality = measure_quality(run.result.mesh, *run.setup.problem);
    EXPECT_EQ(quality.failed_projections, 0);
    centroid_distance.push_back(quality.centroid_distance.max);
    area_error.push_back(std::abs(quality.area - 4.0 * kPi));
    std::printf("sphere h = %-5g centroid distance %.3e  |area - 4π| %.3e\n", h,
                centroid_distance.back(), area_error.back());
  }
  // A flat triangle with edges O(h) on a surface of bounded curvature is O(h²) away from it,
  // and it misses O(h²) of the area of the patch it spans.
  const double distance_order = testing::observed_order(kSteps, centroid_distance);
  const double area_order = testing::observed_order(kSteps, area_error);
  std::printf("sphere: observed order %.3f (centroid distance), %.3f (area)\n", distance_order,
              area_order);
  EXPECT_NEAR(distance_order, 2.0, 0.3);
  EXPECT_GE(area_order, 1.7);
}

TEST(FrontConvergence, CutSphereAreaConverges) {
  std::vector<double> area_error;
  double exact_area = 0.0;
  for (const double h : kSteps) {
    const FrontRun run = run_front("sphere_cut", h);
    ASSERT_TRUE(run.result.summary.is_complete())
        << "h = " << h << ": " << run.result.summary.message;
    ASSERT_TRUE(run.setup.exact_area.has_value());
    exact_area = *run.setup.exact_area;
    const MeshValidation validation = validate(run.result.mesh);
    EXPECT_TRUE(validation.is_valid()) << "h = " << h << "\n" << validation.report();
    EXPECT_EQ(validation.euler_characteristic, 1) << "h = " << h;
    area_error.push_back(std::abs(surface_area(run.result.mesh) - exact_area));
    std::printf("sphere_cut h = %-5g |area - %.6f| %.3e\n", h, exact_area, area_error.back());
  }
  // Interior triangles lose O(h²) of area as on the sphere; the clipped rim is a polygon
  // inscribed in the circle z = cut with vertices on M ∩ ∂S, also O(h²), unless clipping leaves
  // boundary triangles of uneven size, hence the wider slack.
  const double order = testing::observed_order(kSteps, area_error);
  std::printf("sphere_cut: observed order %.3f (area)\n", order);
  EXPECT_GE(order, 1.5);
}

// --- Single examples ---------------------------------------------------------------------------

TEST(FrontTrough, StaysOnTheArchItStartedOn) {
  const FrontRun run = run_front("trough");
  ASSERT_TRUE(run.result.summary.is_complete()) << run.result.summary.message;
  // At the start (0, 0, b) = (0, 0, 0.25) F = ε and ∂F/∂z = −2a²b⁴, ∂F/∂x = ∂F/∂y = 0, so
  // Gauss–Newton moves it by ε / (2a²b⁴) = 5e-5 / 0.125 = 4e-4 along z, to first order; the
  // next term is smaller by O(shift / b) ≈ 2e-3, so 10% of the shift is a generous bound.
  const double a = 4.0;
  const double b = 0.25;
  const double epsilon = 5e-5;
  const double expected_shift = epsilon / (2.0 * a * a * std::pow(b, 4));
  const StartPoint start = project_start_point(*run.setup.problem, run.setup.start,
                                               run.setup.domain, 10.0 * run.setup.suggested_step);
  EXPECT_NEAR(start.x(2), b + expected_shift, 0.1 * expected_shift);
  EXPECT_NEAR(start.x(0), 0.0, 1e-12);

  // The arch lies in z > 0; the other component of M is a loop inside the lower lobe, z < 0.
  // Every vertex above z = 0 proves the front never jumped the O(ε) gap between them.
  double lowest = kInfinity;
  int lowest_vertex = -1;
  for (int v = 0; v < run.result.mesh.vertex_count(); ++v) {
    if (run.result.mesh.point(v)(2) < lowest) {
      lowest = run.result.mesh.point(v)(2);
      lowest_vertex = v;
    }
  }
  EXPECT_GT(lowest, 0.0) << "vertex " << lowest_vertex << " "
                         << describe_point(run.result.mesh.point(lowest_vertex));
}

TEST(FrontDeterminism, TwoRunsGiveIdenticalMeshes) {
  // whitney_pleat: clipping to a box, many merges; nothing may depend on addresses or timing.
  const FrontRun first = run_front("whitney_pleat");
  const FrontRun second = run_front("whitney_pleat");
  ASSERT_EQ(first.result.mesh.vertex_count(), second.result.mesh.vertex_count());
  ASSERT_EQ(first.result.mesh.triangle_count(), second.result.mesh.triangle_count());
  EXPECT_TRUE(first.result.mesh.points() == second.result.mesh.points());  // bit for bit
  EXPECT_TRUE(first.result.mesh.triangles() == second.result.mesh.triangles());
}

// --- Bad inputs ----------------------------------------------------------------------------

// Expects `action` to throw E with a message containing every string of `fragments`.
template <typename E, typename Action>
void expect_throw_naming(Action action, const std::vector<std::string>& fragments) {
  try {
    action();
    ADD_FAILURE() << "no exception; expected one naming '" << fragments.front() << "'";
  } catch (const E& error) {
    const std::string message = error.what();
    for (const std::string& fragment : fragments) {
      EXPECT_NE(message.find(fragment), std::string::npos)
          << "message '" << message << "' does not name '" << fragment << "'";
    }
  }
}

TEST(FrontOptionsValidate, DefaultsAreValid) { EXPECT_NO_THROW(FrontOptions{}.validate()); }

TEST(FrontOptionsValidate, RefusesEachOutOfRangeOptionByName) {
  struct Case {
    const char* field;
    void (*spoil)(FrontOptions&);
  };
  const Case cases[] = {
      {"step", [](FrontOptions& o) { o.step = 0.0; }},
      {"step", [](FrontOptions& o) { o.step = -0.1; }},
      {"step", [](FrontOptions& o) { o.step = kNaN; }},
      {"step", [](FrontOptions& o) { o.step = kInfinity; }},
      {"min_gap_angle", [](FrontOptions& o) { o.min_gap_angle = 0.0; }},
      {"min_gap_angle", [](FrontOptions& o) { o.min_gap_angle = kPi / 2; }},
      {"min_gap_angle", [](FrontOptions& o) { o.min_gap_angle = kNaN; }},
      {"max_valence", [](FrontOptions& o) { o.max_valence = 5; }},
      {"max_valence", [](FrontOptions& o) { o.max_valence = 13; }},
      {"min_step_fraction", [](FrontOptions& o) { o.min_step_fraction = 0.0; }},
      {"min_step_fraction", [](FrontOptions& o) { o.min_step_fraction = 1.0; }},
      {"collision_distance_fraction", [](FrontOptions& o) { o.collision_distance_fraction = 0.0; }},
      {"collision_distance_fraction", [](FrontOptions& o) { o.collision_distance_fraction = 1.0; }},
      {"boundary_snap_fraction", [](FrontOptions& o) { o.boundary_snap_fraction = -0.1; }},
      {"boundary_snap_fraction", [](FrontOptions& o) { o.boundary_snap_fraction = 0.5; }},
      {"boundary_snap_fraction", [](FrontOptions& o) { o.boundary_snap_fraction = kNaN; }},
      {"max_start_distance", [](FrontOptions& o) { o.max_start_distance = -1.0; }},
      {"max_start_distance", [](FrontOptions& o) { o.max_start_distance = kNaN; }},
      {"max_vertices", [](FrontOptions& o) { o.max_vertices = 6; }},
  };
  for (const Case& c : cases) {
    FrontOptions options;
    c.spoil(options);
    SCOPED_TRACE(c.field);
    expect_throw_naming<InvalidArgument>([&] { options.validate(); },
                                         {std::string("FrontOptions::") + c.field});
  }
}

TEST(FrontBadInput, TriangulateRefusesInvalidOptions) {
  const ProblemSetup setup = make_catalogue_problem("sphere");
  FrontOptions options;
  options.step = -1.0;
  expect_throw_naming<InvalidArgument>(
      [&] { triangulate_by_front(*setup.problem, setup.start, setup.domain, options); },
      {"FrontOptions::step", "-1"});
}

TEST(FrontBadInput, StartWithNaNIsAnInvalidArgument) {
  const ProblemSetup setup = make_catalogue_problem("sphere");
  Eigen::VectorXd start = setup.start;
  start(1) = kNaN;
  expect_throw_naming<InvalidArgument>(
      [&] { triangulate_by_front(*setup.problem, start, setup.domain, FrontOptions{}); },
      {"start point", "not finite"});
}

TEST(FrontBadInput, StartOfTheWrongSizeIsAnInvalidArgument) {
  const ProblemSetup setup = make_catalogue_problem("sphere");
  const Eigen::VectorXd start = Eigen::VectorXd::Ones(2);
  expect_throw_naming<InvalidArgument>(
      [&] { triangulate_by_front(*setup.problem, start, setup.domain, FrontOptions{}); },
      {"2 coordinates", "n = 3"});
}

// A start that cannot be projected is an outcome (StartFailed with the reason), not an
// exception: the caller still gets a summary.
TEST(FrontBadInput, StartFarFromMIsAStartFailure) {
  const ProblemSetup setup = make_catalogue_problem("sphere");
  // The unit sphere is ≈ 172 away; the default limit is 10 steps = 1.
  const Eigen::VectorXd start = Eigen::VectorXd::Constant(3, 100.0);
  const CoveringResult result =
      triangulate_by_front(*setup.problem, start, setup.domain, FrontOptions{});
  EXPECT_EQ(result.summary.termination, CoveringTermination::StartFailed);
  EXPECT_NE(result.summary.message.find("too far"), std::string::npos) << result.summary.message;
  EXPECT_EQ(result.mesh.triangle_count(), 0);
  EXPECT_GT(result.summary.function_evaluations, 0);
}

TEST(FrontBadInput, StartProjectingOutsideTheDomainIsAStartFailure) {
  ProblemSetup setup = make_catalogue_problem("sphere_cut");
  // The start (0, 0, 1) projects onto itself; the half-space z ≤ 0.5 excludes it.
  Eigen::VectorXd normal = Eigen::VectorXd::Zero(3);
  normal(2) = -1.0;
  Eigen::VectorXd point = Eigen::VectorXd::Zero(3);
  point(2) = 0.5;
  setup.domain.add_half_space(normal, point, "z <= 0.5");
  const CoveringResult result =
      triangulate_by_front(*setup.problem, setup.start, setup.domain, FrontOptions{});
  EXPECT_EQ(result.summary.termination, CoveringTermination::StartFailed);
  for (const char* part : {"outside the domain", "z <= 0.5"}) {
    EXPECT_NE(result.summary.message.find(part), std::string::npos) << result.summary.message;
  }
}

}  // namespace
}  // namespace tessera
