// SPDX-License-Identifier: MIT
// Extending a finished atlas (AtlasCheckpointing::extend, AtlasOptions::chart_tolerance): the
// charts of a cap of the unit sphere, z ≥ 0.2, continued into z ≥ −0.5 give a valid disk whose
// area is the larger cap's (2π·1.5), with the old mesh's vertices away from its boundary
// unchanged to the bit and a fraction of a fresh run's work; a stopped extension resumes to the
// same mesh; a domain that does not contain the old one is refused. A finer tolerance keeps
// the charts and meets it by refinement.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <memory>
#include <numbers>
#include <set>
#include <string>
#include <vector>

#include "support/test_support.h"
#include "tessera/core/error.h"
#include "tessera/geometry/mesh_quality.h"
#include "tessera/geometry/mesh_validation.h"
#include "tessera/methods/atlas/atlas.h"
#include "tessera/problems/catalogue.h"

namespace tessera {
namespace {

Domain cap_box(double lowest_z) {
  return Domain::box(Eigen::Vector3d(-2, -2, lowest_z), Eigen::Vector3d(2, 2, 2));
}

AtlasOptions cap_options() {
  AtlasOptions options;
  options.step = 0.6;
  options.tolerance = 0.006;
  options.checkpoint.is_due = [] { return false; };  // checkpointed runs (full pivoting)
  return options;
}

struct AtlasRun {
  CoveringResult result;
  std::string final_state;  // the state saved when the build ended
};

AtlasRun cover(const ProblemSetup& setup, const Domain& domain, AtlasOptions options) {
  AtlasRun run;
  options.checkpoint.save = [&run](std::string state) { run.final_state = std::move(state); };
  run.result = cover_by_atlas(*setup.problem, setup.start, domain, options);
  return run;
}

std::uint64_t bits(double x) { return std::bit_cast<std::uint64_t>(x); }

std::set<std::array<std::uint64_t, 3>> vertex_bits(const TriangleMesh& mesh) {
  std::set<std::array<std::uint64_t, 3>> all;
  for (int v = 0; v < mesh.vertex_count(); ++v) {
    const auto x = mesh.points().col(v);
    all.insert({bits(x(0)), bits(x(1)), bits(x(2))});
  }
  return all;
}

int euler_characteristic(const TriangleMesh& mesh) { return validate(mesh).euler_characteristic; }

class AtlasExtend : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    setup_ = new ProblemSetup(make_catalogue_problem("sphere"));
    setup_->start = Eigen::Vector3d(0, 0, 1);
    small_ = new AtlasRun(cover(*setup_, cap_box(0.2), cap_options()));
  }
  static void TearDownTestSuite() {
    delete small_;
    delete setup_;
  }
  static ProblemSetup* setup_;
  static AtlasRun* small_;
};
ProblemSetup* AtlasExtend::setup_ = nullptr;
AtlasRun* AtlasExtend::small_ = nullptr;

TEST_F(AtlasExtend, ALargerBoxGrowsTheAtlasAndKeepsTheOldVertices) {
  const CoveringResult& small = small_->result;
  ASSERT_TRUE(small.summary.is_complete()) << small.summary.message;
  ASSERT_FALSE(small_->final_state.empty());
  AtlasOptions options = cap_options();
  options.checkpoint.resume_from = std::make_shared<const std::string>(small_->final_state);
  options.checkpoint.extend = true;
  const AtlasRun extended = cover(*setup_, cap_box(-0.5), options);
  const CoveringResult& large = extended.result;
  ASSERT_TRUE(large.summary.is_complete()) << large.summary.message;
  EXPECT_EQ(euler_characteristic(large.mesh), 1);
  EXPECT_TRUE(validate(large.mesh, *setup_->problem, cap_box(-0.5)).is_valid());
  EXPECT_LE(large.summary.max_sampled_distance, options.tolerance);
  // The caps' areas, 2π(1 − z0), to 1 %: flat triangles whose chords lie within ε = 0.006 of
  // the unit sphere miss about ε of the relative area (measured 0.4 %).
  EXPECT_NEAR(surface_area(small.mesh), 2 * std::numbers::pi * 0.8, 0.01 * 2 * std::numbers::pi * 0.8);
  EXPECT_NEAR(surface_area(large.mesh), 2 * std::numbers::pi * 1.5, 0.01 * 2 * std::numbers::pi * 1.5);
  // Every vertex of the old mesh three chart radii or more inside the old box is a vertex of the
  // new one, bit for bit: the charts there were kept, their triangles and refinement too.
  const auto after = vertex_bits(large.mesh);
  int inner = 0;
  int kept = 0;
  for (int v = 0; v < small.mesh.vertex_count(); ++v) {
    const auto x = small.mesh.points().col(v);
    if (x(2) < 0.2 + 3 * small.summary.max_chart_radius) {
      continue;
    }
    ++inner;
    kept += after.contains({bits(x(0)), bits(x(1)), bits(x(2))});
  }
  ASSERT_GT(inner, 100);
  EXPECT_EQ(kept, inner) << "vertices of the old region that moved or vanished";
  EXPECT_GT(large.summary.charts, small.summary.charts);
  ASSERT_TRUE(large.summary.resumed_from.has_value());
  EXPECT_EQ(large.summary.resumed_from->charts, small.summary.charts);

  // Not recomputed: the extension's build factors about half what a fresh build of the larger
  // cap does (the old cap is 0.8 of its 1.5 of height; measured 380 against 783). The later
  // steps (refinement, validation) go over the whole mesh in both.
  const AtlasRun fresh = cover(*setup_, cap_box(-0.5), cap_options());
  ASSERT_TRUE(fresh.result.summary.is_complete());
  const auto build_factorisations = [](const CoveringSummary& summary) {
    for (const PhaseWork& phase : summary.work_by_phase) {
      if (phase.phase == std::string("build")) {
        return static_cast<double>(phase.counts.factorisations);
      }
    }
    ADD_FAILURE() << "no build phase";
    return 0.0;
  };
  EXPECT_LT(build_factorisations(large.summary),
            0.6 * build_factorisations(fresh.result.summary));
  EXPECT_NEAR(large.mesh.vertex_count(), fresh.result.mesh.vertex_count(),
              0.15 * fresh.result.mesh.vertex_count());
}

TEST_F(AtlasExtend, AStoppedExtensionResumesToTheSameMesh) {
  AtlasOptions options = cap_options();
  options.checkpoint.resume_from = std::make_shared<const std::string>(small_->final_state);
  options.checkpoint.extend = true;
  const AtlasRun whole = cover(*setup_, cap_box(-0.5), options);
  ASSERT_TRUE(whole.result.summary.is_complete());

  // Stopped after 40 children of the extension; the stop's state holds the new domain, so it
  // is resumed as any other (no extend).
  auto polls = std::make_shared<int>(0);
  options.stop_requested = [polls] { return ++*polls > 40; };
  const AtlasRun stopped = cover(*setup_, cap_box(-0.5), options);
  ASSERT_EQ(stopped.result.summary.termination, CoveringTermination::Interrupted);
  AtlasOptions resumed = cap_options();
  resumed.checkpoint.resume_from = std::make_shared<const std::string>(stopped.final_state);
  const AtlasRun finished = cover(*setup_, cap_box(-0.5), resumed);
  ASSERT_TRUE(finished.result.summary.is_complete());
  testing::expect_identical_meshes(whole.result.mesh, finished.result.mesh,
                                   "the extension stopped and resumed");
}

TEST_F(AtlasExtend, ADomainThatDoesNotContainTheOldOneIsRefused) {
  for (double lowest_z : {0.4, 0.2 + 1e-9}) {
    AtlasOptions options = cap_options();
    options.checkpoint.resume_from = std::make_shared<const std::string>(small_->final_state);
    options.checkpoint.extend = true;
    try {
      cover_by_atlas(*setup_->problem, setup_->start, cap_box(lowest_z), options);
      ADD_FAILURE() << "z >= " << lowest_z << " was not refused";
    } catch (const InvalidArgument& error) {
      EXPECT_NE(std::string(error.what()).find("does not contain the checkpoint's"),
                std::string::npos)
          << error.what();
    }
  }
  // Without `extend`, a larger domain is another run's: refused as before.
  AtlasOptions options = cap_options();
  options.checkpoint.resume_from = std::make_shared<const std::string>(small_->final_state);
  EXPECT_THROW(cover_by_atlas(*setup_->problem, setup_->start, cap_box(-0.5), options),
               InvalidArgument);
}

TEST_F(AtlasExtend, AFinerToleranceKeepsTheChartsAndRefines) {
  AtlasOptions options = cap_options();
  options.chart_tolerance = options.tolerance;
  options.tolerance /= 4;
  options.checkpoint.resume_from = std::make_shared<const std::string>(small_->final_state);
  options.checkpoint.extend = true;
  const AtlasRun finer = cover(*setup_, cap_box(0.2), options);
  const CoveringResult& result = finer.result;
  ASSERT_TRUE(result.summary.is_complete()) << result.summary.message;
  EXPECT_EQ(result.summary.charts, small_->result.summary.charts) << "no chart is added";
  EXPECT_LE(result.summary.max_sampled_distance, options.tolerance);
  EXPECT_GT(small_->result.summary.max_sampled_distance, options.tolerance)
      << "the old mesh must not meet the finer tolerance already, or this tests nothing";
  EXPECT_GT(result.mesh.vertex_count(), small_->result.mesh.vertex_count());
  EXPECT_EQ(euler_characteristic(result.mesh), 1);
  // A chart tolerance finer than the tolerance is refused.
  AtlasOptions wasted = cap_options();
  wasted.chart_tolerance = wasted.tolerance / 2;
  EXPECT_THROW(wasted.validate(), InvalidArgument);
}

}  // namespace
}  // namespace tessera
