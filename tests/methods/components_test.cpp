// SPDX-License-Identifier: MIT
// Several components in one run (methods/components): the search over the region, several
// starts, the coverage test and the seeds. Every component is checked as a mesh of its own:
// valid against M and the domain, its χ and genus those of the surface, its vertices on M.
#include "tessera/methods/components/cover_components.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "tessera/core/error.h"
#include "tessera/geometry/mesh_quality.h"
#include "tessera/geometry/mesh_validation.h"
#include "tessera/methods/components/component_coverage.h"
#include "tessera/methods/components/component_seeds.h"
#include "tessera/methods/covering_methods.h"
#include "tessera/problems/catalogue.h"

namespace tessera {
namespace {

// The component's own mesh: its vertex and triangle ranges of the whole.
TriangleMesh component_mesh(const TriangleMesh& mesh, const ComponentRecord& component) {
  std::vector<Triangle> triangles;
  for (int t = component.first_triangle; t < component.first_triangle + component.triangle_count;
       ++t) {
    Triangle triangle = mesh.triangle(t);
    for (int& v : triangle) {
      EXPECT_GE(v, component.first_vertex);
      EXPECT_LT(v, component.first_vertex + component.vertex_count);
      v -= component.first_vertex;
    }
    triangles.push_back(triangle);
  }
  return TriangleMesh(mesh.points().middleCols(component.first_vertex, component.vertex_count),
                      std::move(triangles));
}

struct ExpectedComponent {
  int euler_characteristic;
  int boundary_loops;
};

// Each component valid on its own with the expected topology (in order of their χ), the ranges
// disjoint and covering the mesh, every vertex on M.
void expect_components(const CoveringResult& result, const ProblemSetup& setup,
                       std::vector<ExpectedComponent> expected) {
  ASSERT_TRUE(result.summary.is_complete()) << result.summary.message;
  const auto& components = result.summary.components;
  ASSERT_EQ(components.size(), expected.size());
  std::vector<ExpectedComponent> found;
  int next_vertex = 0;
  int next_triangle = 0;
  for (const ComponentRecord& component : components) {
    SCOPED_TRACE(component.origin);
    EXPECT_EQ(component.first_vertex, next_vertex);
    EXPECT_EQ(component.first_triangle, next_triangle);
    next_vertex += component.vertex_count;
    next_triangle += component.triangle_count;
    const TriangleMesh mesh = component_mesh(result.mesh, component);
    const MeshValidation validation = validate(mesh, *setup.problem, setup.domain);
    EXPECT_TRUE(validation.is_valid()) << validation.report();
    EXPECT_EQ(validation.component_count, 1);
    EXPECT_EQ(validation.euler_characteristic, component.euler_characteristic);
    EXPECT_EQ(validation.boundary_loop_count, component.boundary_loop_count);
    if (component.boundary_loop_count == 0) {
      EXPECT_EQ(component.genus, (2 - component.euler_characteristic) / 2);
    }
    // The start it came from lies on M and on its own component.
    Eigen::VectorXd F(setup.problem->equation_count());
    setup.problem->evaluate(component.start, F);
    EXPECT_LT(F.norm(), 1e-8);
    found.push_back({component.euler_characteristic, component.boundary_loop_count});
  }
  EXPECT_EQ(next_vertex, result.mesh.vertex_count());
  EXPECT_EQ(next_triangle, result.mesh.triangle_count());
  const auto order = [](const ExpectedComponent& a, const ExpectedComponent& b) {
    return a.euler_characteristic < b.euler_characteristic;
  };
  std::sort(found.begin(), found.end(), order);
  std::sort(expected.begin(), expected.end(), order);
  for (std::size_t k = 0; k < expected.size(); ++k) {
    EXPECT_EQ(found[k].euler_characteristic, expected[k].euler_characteristic);
    EXPECT_EQ(found[k].boundary_loops, expected[k].boundary_loops);
  }
  // The vertices lie on M to the corrector's tolerance.
  const MeshQuality quality = measure_quality(result.mesh, *setup.problem);
  EXPECT_LT(quality.vertex_distance.max, 1e-8);
}

CoveringResult search(ProblemSetup& setup, const std::string& method, int seeds = 512) {
  ComponentSearchOptions options;
  options.every_component = true;
  options.seed_count = seeds;
  return cover_components(setup, find_covering_method(method), MethodSettings{}, {}, options);
}

class EveryComponent : public ::testing::TestWithParam<std::string> {};

// Two disjoint spheres: the start's sphere first, the other found by the seeds; the whole mesh
// (both together) is valid too, no triangle of one overlapping the other.
TEST_P(EveryComponent, FindsBothOfTwoSpheres) {
  ProblemSetup setup = make_catalogue_problem("two_spheres");
  const CoveringResult result = search(setup, GetParam());
  expect_components(result, setup, {{2, 0}, {2, 0}});
  EXPECT_EQ(result.summary.components.front().origin, "start 1");
  EXPECT_EQ(result.summary.components.back().origin.rfind("seed ", 0), 0u);
  // One on each sphere, at x = +1 and x = −1.
  EXPECT_GT(result.summary.components[0].start.x(), 0.0);
  EXPECT_LT(result.summary.components[1].start.x(), 0.0);
  const MeshValidation whole = validate(result.mesh, *setup.problem, setup.domain);
  EXPECT_TRUE(whole.is_valid()) << whole.report();
  EXPECT_EQ(whole.component_count, 2);
  EXPECT_EQ(whole.euler_characteristic, 4);
  ASSERT_TRUE(result.summary.component_search);
  const ComponentSearchRecord& record = *result.summary.component_search;
  EXPECT_EQ(record.seeds_started, 1);
  EXPECT_EQ(record.seeds_started + record.seeds_on_covered + record.seeds_not_projected +
                record.seeds_not_tried,
            record.seed_count);
  // The box [-2, 2]×[-1, 1]² holds 16 units³: 512 seeds are 1/32 apiece, spacing 0.315.
  EXPECT_NEAR(record.seed_spacing, std::cbrt(16.0 / 512.0), 1e-12);
  // The expected topology is the first start's and was held to it alone.
  EXPECT_EQ(setup.expected_euler_characteristic, 2);
}

INSTANTIATE_TEST_SUITE_P(Methods, EveryComponent, ::testing::Values("atlas", "front", "bezier"));

TEST(EveryComponentAtlas, FindsTheTorusAndTheSphereInItsHole) {
  ProblemSetup setup = make_catalogue_problem("torus_and_sphere");
  const CoveringResult result = search(setup, "atlas");
  expect_components(result, setup, {{0, 0}, {2, 0}});
  EXPECT_EQ(result.summary.components.front().genus, 1);  // the start's torus
  EXPECT_EQ(result.summary.components.back().genus, 0);
}

// The crossing problem's two sheets, the sphere and the square of the plane z = 0 in the box,
// each covered as a component of its own (the atlas keeps to its sheet at the crossing circle).
// Their union crosses itself along the circle, as M does: valid, the crossing pairs counted.
TEST(EveryComponentAtlas, CoversBothSheetsOfTheCrossing) {
  ProblemSetup setup = make_catalogue_problem("crossing");
  const CoveringResult result = search(setup, "atlas");
  expect_components(result, setup, {{2, 0}, {1, 1}});
  const MeshValidation whole = validate(result.mesh, *setup.problem, setup.domain);
  EXPECT_TRUE(whole.is_valid()) << whole.report();
  EXPECT_GT(whole.crossing_pair_count, 0) << "the sheets cross along the circle";
  EXPECT_EQ(whole.component_count, 2);
  double area = 0.0;
  for (const ComponentRecord& component : result.summary.components) {
    area += measure_quality(component_mesh(result.mesh, component), *setup.problem).area;
  }
  // The sphere's 4π and the square's 9, to the tolerance's chord error.
  EXPECT_NEAR(area, 4.0 * M_PI + 9.0, 0.05);
}

// Too few seeds to land on the second sphere reliably still give a valid run of what was found:
// with one seed (the box's centre, between the spheres) at most the start's sphere and
// possibly one more.
TEST(EveryComponentAtlas, FewSeedsFindWhatTheyLandOn) {
  ProblemSetup setup = make_catalogue_problem("two_spheres");
  const CoveringResult result = search(setup, "atlas", 1);
  ASSERT_TRUE(result.summary.is_complete()) << result.summary.message;
  EXPECT_GE(result.summary.components.size(), 1u);
  EXPECT_EQ(result.summary.component_search->seed_count, 1);
}

TEST(SeveralStarts, EachStartsItsComponentOrSaysWhichOneCoveredIt) {
  ProblemSetup setup = make_catalogue_problem("two_spheres");
  std::vector<Eigen::VectorXd> starts(4, Eigen::VectorXd(3));
  starts[0] << 1.0, 0.0, 0.5;   // sphere at +1
  starts[1] << -1.0, 0.0, 0.6;  // sphere at −1
  starts[2] << 1.2, 0.4, 0.0;   // sphere at +1 again
  starts[3] << 0.0, 0.0, 0.0;   // between them: projects onto neither (∇F = 0 there)
  const CoveringResult result =
      cover_components(setup, find_covering_method("front"), MethodSettings{}, starts, {});
  expect_components(result, setup, {{2, 0}, {2, 0}});
  const auto& outcome = result.summary.starts;
  ASSERT_EQ(outcome.size(), 4u);
  EXPECT_EQ(outcome[0].component, 0);
  EXPECT_TRUE(outcome[0].started_component);
  EXPECT_EQ(outcome[1].component, 1);
  EXPECT_TRUE(outcome[1].started_component);
  EXPECT_EQ(outcome[2].component, 0);
  EXPECT_FALSE(outcome[2].started_component);
  EXPECT_EQ(outcome[3].component, -1);
  EXPECT_FALSE(outcome[3].message.empty());
  EXPECT_FALSE(result.summary.component_search);
}

TEST(SeveralStarts, NoneThatProjectsIsAStartFailure) {
  ProblemSetup setup = make_catalogue_problem("two_spheres");
  const std::vector<Eigen::VectorXd> starts(2, Eigen::VectorXd::Zero(3));
  const CoveringResult result =
      cover_components(setup, find_covering_method("atlas"), MethodSettings{}, starts, {});
  EXPECT_EQ(result.summary.termination, CoveringTermination::StartFailed);
  EXPECT_EQ(result.mesh.triangle_count(), 0);
}

TEST(EveryComponentInput, AnUnboundedRegionIsRefused) {
  ProblemSetup setup = make_catalogue_problem("sphere");
  EXPECT_THROW(search(setup, "atlas"), InvalidArgument);
  setup = make_catalogue_problem("sphere_cut");  // z ≥ −0.8 bounds z on one side only
  EXPECT_THROW(search(setup, "atlas"), InvalidArgument);
}

// --- the parts -------------------------------------------------------------------------------

TEST(ClosestPointOnTriangle, MatchesADenseSampleInR4) {
  Eigen::VectorXd a(4), b(4), c(4);
  a << 0, 0, 0, 0;
  b << 1, 0, 0.2, 0;
  c << 0.1, 1, 0, 0.3;
  std::vector<Eigen::VectorXd> points;
  for (double s : {-1.0, 0.3, 2.0}) {
    for (double t : {-0.5, 0.2, 1.5}) {
      Eigen::VectorXd p(4);
      p << s, t, 0.7 * s - t, 0.4;
      points.push_back(p);
    }
  }
  for (const Eigen::VectorXd& p : points) {
    const double distance = (closest_point_on_triangle(p, a, b, c) - p).norm();
    double sampled = std::numeric_limits<double>::infinity();
    const int k = 400;
    for (int i = 0; i <= k; ++i) {
      for (int j = 0; i + j <= k; ++j) {
        const Eigen::VectorXd q = a + (double(i) / k) * (b - a) + (double(j) / k) * (c - a);
        sampled = std::min(sampled, (q - p).norm());
      }
    }
    // The sample's spacing, 1/400 of an edge, bounds how far above the true minimum it lies.
    EXPECT_LE(distance, sampled + 1e-12);
    EXPECT_GE(distance, sampled - 0.01);
  }
}

TEST(ComponentCoverage, APointOnATriangleIsCoveredAFarOneIsNot) {
  Eigen::MatrixXd points(3, 3);
  points << 0, 1, 0,  //
      0, 0, 1,        //
      0, 0, 0;
  TriangleMesh mesh(points, {{0, 1, 2}});
  ComponentCoverage coverage(mesh, Eigen::VectorXd(), 0.0);
  EXPECT_EQ(coverage.covering_component(Eigen::Vector3d(0.2, 0.2, 0.0)), -1);  // none added yet
  coverage.add_component();
  EXPECT_EQ(coverage.covering_component(Eigen::Vector3d(0.2, 0.2, 0.1)), 0);
  // A quarter of the longest edge √2 is the reach: 0.36 above the triangle is beyond it.
  EXPECT_EQ(coverage.covering_component(Eigen::Vector3d(0.2, 0.2, 0.36)), -1);
  // In a metric that shrinks z tenfold it is within reach again.
  ComponentCoverage scaled(mesh, Eigen::Vector3d(1.0, 1.0, 0.1), 0.0);
  scaled.add_component();
  EXPECT_EQ(scaled.covering_component(Eigen::Vector3d(0.2, 0.2, 0.36)), 0);
}

TEST(ComponentSeeds, HaltonPointsFillTheBoxAndKeepTheOtherCoordinates) {
  Domain domain(3);
  domain.add_half_space(Eigen::Vector3d(1, 0, 0), Eigen::Vector3d(-2, 0, 0));
  domain.add_half_space(Eigen::Vector3d(-1, 0, 0), Eigen::Vector3d(2, 0, 0));
  domain.add_half_space(Eigen::Vector3d(0, 1, 0), Eigen::Vector3d(0, -1, 0));
  domain.add_half_space(Eigen::Vector3d(0, -1, 0), Eigen::Vector3d(0, 1, 0));
  domain.add_half_space(Eigen::Vector3d(0, 0, 1), Eigen::Vector3d(0, 0, 0));  // z ≥ 0 only
  const SeededBox box = seeded_box(domain);
  ASSERT_EQ(box.coordinates, (std::vector<int>{0, 1}));
  const Eigen::MatrixXd seeds = halton_seeds(box, Eigen::Vector3d(0, 0, 7), 100);
  ASSERT_EQ(seeds.cols(), 100);
  // Seed 1: the radical inverses of 1 in bases 2 and 3, 1/2 and 1/3, in the box.
  EXPECT_DOUBLE_EQ(seeds(0, 0), 0.0);
  EXPECT_DOUBLE_EQ(seeds(1, 0), -1.0 + 2.0 / 3.0);
  for (int j = 0; j < 100; ++j) {
    EXPECT_TRUE(domain.contains(seeds.col(j))) << seeds.col(j).transpose();
    EXPECT_EQ(seeds(2, j), 7.0);
  }
  EXPECT_DOUBLE_EQ(seed_spacing(box, 8, Eigen::VectorXd()), 1.0);  // 8 units² / 8 seeds
  EXPECT_TRUE(seeded_box(Domain(3)).is_empty());
}

}  // namespace
}  // namespace tessera
