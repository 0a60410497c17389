// SPDX-License-Identifier: MIT
// The shared run skeleton (methods/covering.h) and the registry (methods/covering_methods.h):
// what every method promises, checked the same way for each.
#include "tessera/methods/covering.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "geometry/mesh_examples.h"
#include "tessera/core/counted_problem.h"
#include "tessera/core/domain.h"
#include "tessera/core/parallel_for.h"
#include "tessera/geometry/mesh_quality.h"
#include "tessera/geometry/mesh_validation.h"
#include "tessera/methods/covering_methods.h"
#include "tessera/methods/start_point.h"
#include "tessera/problems/catalogue.h"

namespace tessera {
namespace {

struct MethodProblem {
  std::string method;
  std::string problem;
};

std::string name_of(const ::testing::TestParamInfo<MethodProblem>& info) {
  return info.param.method + "_" + info.param.problem;
}

// --tolerance means one thing for every method: every sampled point of every output triangle
// (centroids and edge midpoints, measured here independently of the method by projecting
// them onto M) lies within it of M, and the summary reports the distance it measured.
class ToleranceBound : public ::testing::TestWithParam<MethodProblem> {};

TEST_P(ToleranceBound, HoldsForEveryTriangle) {
  const MethodProblem& param = GetParam();
  const ProblemSetup setup = make_catalogue_problem(param.problem);
  MethodSettings settings;
  settings.tolerance = 0.004;
  const CoveringResult result = cover(setup, find_covering_method(param.method), settings);
  ASSERT_TRUE(result.summary.is_complete()) << result.summary.message;
  const MeshValidation validation = validate(result.mesh, *setup.problem, setup.domain);
  EXPECT_TRUE(validation.is_valid()) << validation.report();
  ASSERT_TRUE(setup.expected_euler_characteristic);
  EXPECT_EQ(validation.euler_characteristic, *setup.expected_euler_characteristic);
  const MeshQuality quality = measure_quality(result.mesh, *setup.problem);
  EXPECT_LT(quality.vertex_distance.max, 1e-8);
  // The check samples centroids, midpoints and circumcentres and refines above 0.97 ε; the
  // independent measurement here is of centroids and midpoints, so it stays below ε.
  EXPECT_LE(quality.centroid_distance.max, settings.tolerance);
  EXPECT_LE(quality.midpoint_distance.max, settings.tolerance);
  EXPECT_LE(result.summary.max_sampled_distance, settings.tolerance);
  EXPECT_GE(result.summary.max_sampled_distance,
            std::max(quality.centroid_distance.max, quality.midpoint_distance.max) * 0.99);
  EXPECT_EQ(result.summary.tolerance, settings.tolerance);
  if (param.method == "bezier") {
    EXPECT_EQ(static_cast<int>(result.patches.size()), result.mesh.triangle_count());
  }
}

INSTANTIATE_TEST_SUITE_P(
    Methods, ToleranceBound,
    ::testing::Values(MethodProblem{"atlas", "torus"}, MethodProblem{"front", "sphere"},
                      MethodProblem{"front", "torus"}, MethodProblem{"bezier", "sphere"},
                      MethodProblem{"bezier", "torus"}, MethodProblem{"bezier", "cstr"}),
    name_of);

// Without --tolerance the front keeps its own step and no bound is claimed.
TEST(Covering, WithoutToleranceNoBoundIsClaimed) {
  const ProblemSetup setup = make_catalogue_problem("sphere");
  const CoveringResult result = cover(setup, find_covering_method("front"), MethodSettings{});
  ASSERT_TRUE(result.summary.is_complete()) << result.summary.message;
  EXPECT_EQ(result.summary.tolerance, 0.0);
  EXPECT_EQ(result.summary.max_sampled_distance, -1.0);
  EXPECT_EQ(result.summary.refined_edges, 0);
}

// Progress: every method reports its build (every 1000 vertices or charts, or every second),
// then the skeleton reports each later stage once, as it begins, with the mesh's counts then.
TEST(Covering, ProgressReportsTheBuildThenEachLaterStageOnce) {
  const ProblemSetup setup = make_catalogue_problem("sphere_cut");
  for (const CoveringMethod& method : covering_methods()) {
    SCOPED_TRACE(method.name);
    std::vector<CoveringProgress> records;
    MethodSettings settings;
    settings.step = 0.05;  // a few thousand vertices each
    settings.bezier_max_step = 0.05;
    settings.progress = [&records](const CoveringProgress& progress) {
      records.push_back(progress);
    };
    const CoveringResult result = cover(setup, method, settings);
    ASSERT_TRUE(result.summary.is_complete()) << result.summary.message;
    ASSERT_FALSE(records.empty());
    std::vector<std::string> stages;
    for (const CoveringProgress& record : records) {
      if (stages.empty() || stages.back() != record.stage) {
        stages.emplace_back(record.stage);
      }
    }
    EXPECT_EQ(stages.front(), "build");
    const std::vector<std::string> later(stages.begin() + 1, stages.end());
    EXPECT_EQ(later, (std::vector<std::string>{"clip", "refine", "validate", "patches"}));
    EXPECT_GT(records.front().front_size, 0);
    EXPECT_EQ(records.back().vertex_count, result.mesh.vertex_count());  // nothing after it
  }
}

// A start that cannot be projected is an outcome with a summary, for every method.
TEST(Covering, StartFailureIsAnOutcomeForEveryMethod) {
  ProblemSetup setup = make_catalogue_problem("sphere");
  setup.start = Eigen::VectorXd::Constant(3, 100.0);
  for (const CoveringMethod& method : covering_methods()) {
    SCOPED_TRACE(method.name);
    const CoveringResult result = cover(setup, method, MethodSettings{});
    EXPECT_EQ(result.summary.termination, CoveringTermination::StartFailed);
    EXPECT_NE(result.summary.message.find("(100, 100, 100)"), std::string::npos)
        << result.summary.message;
    EXPECT_EQ(result.mesh.triangle_count(), 0);
    EXPECT_EQ(result.summary.method, method.name);
    EXPECT_GT(result.summary.function_evaluations, 0);
  }
}

// A completed run whose mesh has another topology than M's is a failure, not a success.
// --placement auto (MethodSettings' default): the hexagonal placement for a closed surface of a
// dense problem, about 30 % fewer vertices at the same tolerance; the disk rule on a bounded
// domain or where DF is sparse (docs/algorithms/atlas.md, "Placement").
TEST(Covering, AutomaticAtlasPlacementChoosesByJacobianAndDomain) {
  const CoveringMethod& atlas = find_covering_method("atlas");
  const auto run = [&](const std::string& name, const std::string& placement) {
    MethodSettings settings;
    settings.atlas_placement = placement;
    settings.tolerance = 0.01;
    return atlas.run(make_catalogue_problem(name), settings);
  };
  const CoveringResult automatic = run("sphere", "auto");
  ASSERT_TRUE(automatic.summary.is_complete()) << automatic.summary.message;
  EXPECT_EQ(automatic.summary.placement, "hexagonal");
  const CoveringResult disk = run("sphere", "disk");
  EXPECT_EQ(disk.summary.placement, "disk");
  EXPECT_LT(automatic.mesh.vertex_count(), 0.8 * disk.mesh.vertex_count());
  EXPECT_LE(automatic.summary.max_sampled_distance, 0.01);
  EXPECT_TRUE(validate(automatic.mesh).is_valid());
  EXPECT_EQ(run("sphere_cut", "auto").summary.placement, "disk");  // a bounded domain
  EXPECT_EQ(run("bvp:points=16", "auto").summary.placement, "disk");  // sparse DF
}

TEST(Covering, WrongTopologyIsAFailure) {
  ProblemSetup setup = make_catalogue_problem("sphere");
  setup.expected_euler_characteristic = 0;  // claims a torus
  const CoveringResult result = cover(setup, find_covering_method("front"), MethodSettings{});
  EXPECT_EQ(result.summary.termination, CoveringTermination::TriangulationFailed);
  EXPECT_NE(result.summary.message.find("Euler characteristic 2"), std::string::npos)
      << result.summary.message;
}

// An icosphere whose vertex 0 is moved (on M) across the edge opposite it in one of its
// triangles: its fan folds over.
TriangleMesh icosphere_with_a_folded_fan() {
  TriangleMesh mesh = examples::icosphere(2);
  const Eigen::VectorXd p = mesh.point(0);
  Eigen::VectorXd q;
  for (const Triangle& t : mesh.triangles()) {
    if (t[0] == 0 || t[1] == 0 || t[2] == 0) {
      const int a = t[0] == 0 ? t[1] : t[0];
      const int b = t[2] == 0 ? t[1] : t[2];
      q = 0.5 * (mesh.point(a) + mesh.point(b));
      break;
    }
  }
  Eigen::VectorXd moved = p + 2.2 * (q - p);
  moved.normalize();  // back onto the unit sphere
  mesh.mutable_point(0) = moved;
  return mesh;
}

// The skeleton's last word on validity: a build that returns a folded fan does not end with
// the fold. It is repaired locally (the bad triangles and their fans removed, the hole
// triangulated again), the result is valid with M's topology, and the summary says so.
TEST(Covering, FlippedTrianglesAreRepairedLocally) {
  const ProblemSetup setup = make_catalogue_problem("sphere");
  ASSERT_FALSE(validate(icosphere_with_a_folded_fan(), *setup.problem, setup.domain).is_valid());
  CoveringOptions options;
  options.step = 0.3;
  const CoveringResult result = run_covering(
      "planted", *setup.problem, setup.start, setup.domain, options,
      [](CoveringContext&, CoveringResult& built) { built.mesh = icosphere_with_a_folded_fan(); });
  EXPECT_TRUE(result.summary.is_complete()) << result.summary.message;
  EXPECT_GT(result.summary.removed_triangles, 0);
  EXPECT_EQ(result.summary.repaired_holes, 1);
  const MeshValidation validation = validate(result.mesh, *setup.problem, setup.domain);
  EXPECT_TRUE(validation.is_valid()) << validation.report();
  EXPECT_EQ(validation.euler_characteristic, 2);
  ASSERT_FALSE(result.summary.notes.empty());
  EXPECT_NE(result.summary.notes.back().find("flipped"), std::string::npos);
}

// What cannot be repaired locally is removed, and the run fails naming the place: here a
// vertex outside the domain (a box that cuts the top off the sphere's mesh by 1e-6).
TEST(Covering, VerticesOutsideTheDomainAreRemovedAndReported) {
  ProblemSetup setup = make_catalogue_problem("sphere");
  const TriangleMesh mesh = examples::icosphere(2);
  double top = -1.0;
  for (int v = 0; v < mesh.vertex_count(); ++v) {
    top = std::max(top, mesh.point(v)(2));
  }
  setup.domain = Domain::box(Eigen::Vector3d(-2, -2, -2), Eigen::Vector3d(2, 2, top - 1e-6));
  setup.start = Eigen::Vector3d(1, 0, 0);
  CoveringOptions options;
  options.step = 0.3;
  const CoveringResult result =
      run_covering("planted", *setup.problem, setup.start, setup.domain, options,
                   [&mesh](CoveringContext&, CoveringResult& built) { built.mesh = mesh; });
  EXPECT_EQ(result.summary.termination, CoveringTermination::TriangulationFailed);
  EXPECT_GT(result.summary.removed_triangles, 0);
  EXPECT_NE(result.summary.message.find("outside the domain"), std::string::npos)
      << result.summary.message;
  EXPECT_NE(result.summary.message.find("near ("), std::string::npos) << result.summary.message;
  const MeshValidation validation = validate(result.mesh, *setup.problem, setup.domain);
  EXPECT_TRUE(validation.is_valid()) << validation.report();
}

}  // namespace
}  // namespace tessera

namespace tessera {
namespace {

// The report's distances within a time budget: a spent budget still measures kMinDistanceSamples
// of each kind (a uniform sample: the counts say how many), and a stop request ends them.
TEST(MeasureQuality, ATimeBudgetKeepsAUniformSampleOfEachKind) {
  const ProblemSetup setup = make_catalogue_problem("sphere");
  const CoveringResult result = cover(setup, find_covering_method("atlas"), MethodSettings{});
  ASSERT_TRUE(result.summary.is_complete()) << result.summary.message;
  ASSERT_GT(result.mesh.vertex_count(), 2 * kMinDistanceSamples);
  QualityOptions spent;
  spent.max_seconds = 0.0;
  const MeshQuality sampled = measure_quality(result.mesh, *setup.problem, spent);
  EXPECT_EQ(sampled.vertex_distance.count, kMinDistanceSamples);
  EXPECT_EQ(sampled.centroid_distance.count, kMinDistanceSamples);
  EXPECT_EQ(sampled.midpoint_distance.count, kMinDistanceSamples);
  EXPECT_EQ(sampled.centroid_distance.population, result.mesh.triangle_count());
  EXPECT_EQ(sampled.vertex_residual.count, result.mesh.vertex_count());  // always all
  const MeshQuality all = measure_quality(result.mesh, *setup.problem);
  EXPECT_EQ(all.centroid_distance.count, result.mesh.triangle_count());
  EXPECT_LE(sampled.centroid_distance.max, all.centroid_distance.max);
  EXPECT_GT(sampled.centroid_distance.max, 0.0);
  // On one thread the stop request is polled before every sample; on several, before every
  // block, the first of them kMinDistanceSamples long.
  QualityOptions stopped;
  int polls = 0;
  stopped.stop_requested = [&polls] { return ++polls > 5; };
  {
    const ThreadCountScope one(1);
    const MeshQuality cut_short = measure_quality(result.mesh, *setup.problem, stopped);
    EXPECT_EQ(cut_short.centroid_distance.count, 5);
  }
  polls = 0;
  stopped.stop_requested = [&polls] { return ++polls > 1; };
  const ThreadCountScope two(2);
  const MeshQuality cut_short = measure_quality(result.mesh, *setup.problem, stopped);
  EXPECT_EQ(cut_short.centroid_distance.count, kMinDistanceSamples);
}

}  // namespace
}  // namespace tessera
