// SPDX-License-Identifier: MIT
// The stop hook (MethodSettings::stop_requested, CoveringOptions::stop_requested), which the
// bindings' Ctrl-C sets: every method polls it while it builds, stops at the first `true` with
// termination Interrupted, and the skeleton still clips, refines and validates the partial
// mesh, so what comes back is a valid piece of M, smaller than the whole.
#include <gtest/gtest.h>

#include <algorithm>

#include <cstdio>
#include <nlohmann/json.hpp>
#include <string>

#include "tessera/core/parallel_for.h"
#include "tessera/geometry/mesh_validation.h"
#include "tessera/methods/covering_methods.h"
#include "tessera/problems/catalogue.h"
#include "tessera/report/summary_json.h"

namespace tessera {
namespace {

struct InterruptCase {
  std::string method;
  std::string problem;
  int polls_before_stop;  ///< stop_requested returns false this many times, then true
};

std::string name_of(const ::testing::TestParamInfo<InterruptCase>& info) {
  return info.param.method + "_" + info.param.problem;
}

class StopHook : public ::testing::TestWithParam<InterruptCase> {};

// A hook that never says stop and counts how often it is asked.
StopRequest counting_polls(int& polls) {
  return [&polls] {
    ++polls;
    return false;
  };
}

// Records in `polls_at_refine` how often the hook had been asked when the refinement began:
// the polls of the build, the clipping and the swaps (the final checks poll too, after it).
ProgressCallback note_polls_at_refine(const int& polls, int& polls_at_refine) {
  polls_at_refine = -1;
  return [&polls, &polls_at_refine](const CoveringProgress& progress) {
    if (progress.stage == "refine" && polls_at_refine < 0) {
      polls_at_refine = polls;
    }
  };
}

// A run without a stop, counting the polls: all of them, and those before the refinement
// began (the build's, the clipping's and the swaps'; the tolerance check and the final checks
// poll after them).
struct CountedRun {
  CoveringResult result;
  int whole_polls = 0;
  int build_polls = 0;
};
CountedRun run_counting_polls(const ProblemSetup& setup, const CoveringMethod& method,
                              MethodSettings settings) {
  CountedRun run;
  settings.stop_requested = counting_polls(run.whole_polls);
  settings.progress = note_polls_at_refine(run.whole_polls, run.build_polls);
  run.result = cover(setup, method, settings);
  return run;
}

TEST_P(StopHook, StopsWithAValidPartialMesh) {
  const InterruptCase& param = GetParam();
  const ProblemSetup setup = make_catalogue_problem(param.problem);
  const CoveringMethod& method = find_covering_method(param.method);

  // The whole run, for comparison; a hook that never says stop changes nothing.
  MethodSettings settings;
  int polls_of_whole_run = 0;
  settings.stop_requested = counting_polls(polls_of_whole_run);
  const CoveringResult whole = cover(setup, method, settings);
  ASSERT_TRUE(whole.summary.is_complete()) << whole.summary.message;
  // The hook is polled about once per vertex (or chart), so stopping after k polls leaves a
  // run well short of the whole.
  ASSERT_GT(polls_of_whole_run, 2 * param.polls_before_stop)
      << "the method polled stop_requested only " << polls_of_whole_run << " times";

  int polls = 0;
  settings.stop_requested = [&polls, &param] { return ++polls > param.polls_before_stop; };
  const CoveringResult partial = cover(setup, method, settings);

  EXPECT_EQ(partial.summary.termination, CoveringTermination::Interrupted)
      << to_string(partial.summary.termination) << ": " << partial.summary.message;
  EXPECT_FALSE(partial.summary.is_complete());
  EXPECT_NE(partial.summary.message.find("interrupted"), std::string::npos)
      << partial.summary.message;
  // The first `true` stops the build: it is not asked again.
  EXPECT_EQ(polls, param.polls_before_stop + 1);

  std::printf("%s on %s: stopped after %d of %d polls with %d of %d vertices (%s)\n",
              param.method.c_str(), param.problem.c_str(), param.polls_before_stop,
              polls_of_whole_run, partial.summary.vertex_count, whole.summary.vertex_count,
              partial.summary.message.c_str());

  // Non-empty, smaller than the whole, and valid as a mesh of M (geometric validation).
  EXPECT_GT(partial.mesh.triangle_count(), 0);
  EXPECT_GT(partial.summary.vertex_count, 0);
  EXPECT_LT(partial.summary.vertex_count, whole.summary.vertex_count);
  EXPECT_LT(partial.mesh.vertex_count(), whole.mesh.vertex_count());
  const MeshValidation validation = validate(partial.mesh, *setup.problem, setup.domain);
  EXPECT_TRUE(validation.is_valid()) << validation.report();
  EXPECT_TRUE(validation.is_geometry_checked);
  EXPECT_EQ(partial.summary.removed_triangles, 0);
  // A stop skips the tolerance's bisection (minutes at large n) and says so.
  if (partial.summary.tolerance > 0) {
    EXPECT_EQ(partial.summary.max_sampled_distance, -1.0);
    const auto& notes = partial.summary.notes;
    EXPECT_TRUE(std::any_of(notes.begin(), notes.end(), [](const std::string& note) {
      return note.find("was not enforced") != std::string::npos;
    }));
  }
  // A partial covering of a closed surface has a boundary.
  EXPECT_FALSE(validation.is_closed());

  // The run report names the termination (docs/summary-json.md).
  EXPECT_STREQ(to_string(partial.summary.termination), "interrupted");
  MeshReport report;
  report.problem = param.problem;
  report.ambient_dimension = setup.problem->ambient_dimension();
  report.run = partial.summary;
  report.validation = validation;
  const nlohmann::json json = nlohmann::json::parse(to_json(report));
  EXPECT_EQ(json["run"]["termination"], "interrupted");
  EXPECT_EQ(json["run"]["completed"], false);
  EXPECT_EQ(json["run"]["message"], partial.summary.message);
  EXPECT_NE(to_text(report).find("interrupted"), std::string::npos) << to_text(report);
}

INSTANTIATE_TEST_SUITE_P(Methods, StopHook,
                         ::testing::Values(InterruptCase{"atlas", "torus", 40},
                                           InterruptCase{"front", "torus", 40},
                                           InterruptCase{"bezier", "torus", 40}),
                         name_of);

// A stop after the build, during the tolerance check (minutes of chord steps at n = 10⁵): the
// check ends between two triangles, the mesh is the whole build's, valid, and the summary says
// the tolerance holds on part of it only. The front's build does not depend on the tolerance,
// so a run without one counts the build's polls.
TEST(StopRequest, StopDuringTheToleranceCheckKeepsTheBuiltMeshValid) {
  // One thread: the request is polled before every triangle (on several, before every block of
  // anchor groups), so that the count of polls below is exact.
  const ThreadCountScope one(1);
  const ProblemSetup setup = make_catalogue_problem("torus");
  const CoveringMethod& front = find_covering_method("front");
  MethodSettings settings;
  const CountedRun counted = run_counting_polls(setup, front, settings);
  const CoveringResult& built = counted.result;
  const int build_polls = counted.build_polls;
  ASSERT_TRUE(built.summary.is_complete()) << built.summary.message;
  ASSERT_GT(build_polls, 0);

  settings.tolerance = 2e-4;  // far below the front's own accuracy: many triangles to split
  int polls = 0;
  const int stop_after = build_polls + 50;  // 50 triangles checked, then stop
  settings.stop_requested = [&polls, stop_after] { return ++polls > stop_after; };
  const CoveringResult stopped = cover(setup, front, settings);
  EXPECT_EQ(stopped.summary.termination, CoveringTermination::Interrupted)
      << stopped.summary.message;
  EXPECT_NE(stopped.summary.message.find("tolerance check"), std::string::npos)
      << stopped.summary.message;
  EXPECT_EQ(polls, stop_after + 1);                       // not asked again after the first `true`
  EXPECT_EQ(stopped.summary.max_sampled_distance, -1.0);  // no bound for the whole mesh
  const auto& notes = stopped.summary.notes;
  EXPECT_TRUE(std::any_of(notes.begin(), notes.end(), [](const std::string& note) {
    return note.find("enforced on part of the mesh only") != std::string::npos;
  }));
  // The stop came in the first round's checks, before any split: the build's mesh, validated.
  EXPECT_EQ(stopped.summary.refined_edges, 0);
  EXPECT_EQ(stopped.mesh.vertex_count(), built.mesh.vertex_count());
  const MeshValidation validation = validate(stopped.mesh, *setup.problem, setup.domain);
  EXPECT_TRUE(validation.is_valid()) << validation.report();
  EXPECT_TRUE(validation.is_closed());

  // Without the stop the same settings bisect: the check did run and would have changed it.
  settings.stop_requested = nullptr;
  const CoveringResult refined = cover(setup, front, settings);
  EXPECT_GT(refined.summary.refined_edges, 0);
}

// The same on threads: the request, polled on the calling thread before every block of anchor
// groups, stops the check at its first poll, before any split.
TEST(StopRequest, StopDuringTheToleranceCheckOnThreadsKeepsTheBuiltMeshValid) {
  const ThreadCountScope two(2);
  const ProblemSetup setup = make_catalogue_problem("torus");
  const CoveringMethod& front = find_covering_method("front");
  MethodSettings settings;
  const CountedRun counted = run_counting_polls(setup, front, settings);
  const CoveringResult& built = counted.result;
  const int build_polls = counted.build_polls;
  ASSERT_TRUE(built.summary.is_complete()) << built.summary.message;
  ASSERT_GT(build_polls, 0);
  settings.tolerance = 2e-4;
  int polls = 0;
  const int stop_after = build_polls;  // the check's first poll says stop
  settings.stop_requested = [&polls, stop_after] { return ++polls > stop_after; };
  const CoveringResult stopped = cover(setup, front, settings);
  EXPECT_EQ(stopped.summary.termination, CoveringTermination::Interrupted)
      << stopped.summary.message;
  EXPECT_EQ(polls, stop_after + 1);
  EXPECT_EQ(stopped.summary.refined_edges, 0);
  EXPECT_EQ(stopped.mesh.vertex_count(), built.mesh.vertex_count());
  const MeshValidation validation = validate(stopped.mesh, *setup.problem, setup.domain);
  EXPECT_TRUE(validation.is_valid()) << validation.report();
}

// A stop during clipping (at n = 10⁵ each projection onto a face costs a factorisation; the
// clipping of bratu2d:N=316 took minutes): no more projections, the triangles outside the faces
// not yet clipped are removed, and the mesh is valid, inside the domain and says why its
// boundary is ragged.
TEST(StopRequest, StopDuringClippingLeavesAValidMeshInsideTheDomain) {
  const ProblemSetup setup = make_catalogue_problem("sphere_cut");
  const CoveringMethod& atlas = find_covering_method("atlas");
  MethodSettings settings;
  settings.tolerance = 0;  // the tolerance check polls too; without it only build and clip do
  const CountedRun counted = run_counting_polls(setup, atlas, settings);
  const CoveringResult& whole = counted.result;
  const int build_polls = counted.build_polls;
  ASSERT_TRUE(whole.summary.is_complete()) << whole.summary.message;
  ASSERT_GT(whole.summary.clipped_half_spaces, 0);
  ASSERT_GT(build_polls, 0);

  // build_polls counts the polls of the build, the clipping and the swaps after it, in that
  // order (the final checks' come after). A stop after k polls lands past the build exactly
  // when k is at least the build's count: found by bisection.
  const auto stop_after = [&](int k, int& polls) {
    polls = 0;
    settings.stop_requested = [&polls, k] { return ++polls > k; };
    return cover(setup, atlas, settings);
  };
  const auto says = [](const CoveringResult& result, const char* where) {
    return result.summary.message.find(where) != std::string::npos;
  };
  int polls = 0;
  int low = 0;                 // stops in the build
  int high = build_polls - 1;  // stops after it
  ASSERT_FALSE(says(stop_after(low, polls), "clipping"));
  while (high - low > 1) {
    const int middle = (low + high) / 2;
    const CoveringResult stopped = stop_after(middle, polls);
    (says(stopped, "clipping") || says(stopped, "improving") ? high : low) = middle;
  }
  // The first poll after the build is the clipping's, before its first projection.
  const int stop = high;
  const CoveringResult stopped = stop_after(stop, polls);
  EXPECT_EQ(stopped.summary.termination, CoveringTermination::Interrupted);
  EXPECT_TRUE(says(stopped, "clipping")) << stopped.summary.message;
  EXPECT_EQ(polls, stop + 1);  // not asked again after the first `true`
  const MeshValidation validation = validate(stopped.mesh, *setup.problem, setup.domain);
  EXPECT_TRUE(validation.is_valid()) << validation.report();
  EXPECT_EQ(validation.vertex_outside_domain_count, 0);
  EXPECT_FALSE(validation.is_closed());
  // Only the band across the face is lost, not the cap.
  EXPECT_GT(stopped.mesh.triangle_count(), whole.mesh.triangle_count() * 8 / 10);
  EXPECT_LT(stopped.mesh.triangle_count(), whole.mesh.triangle_count());
}

// A stop during the final geometric check (a factorisation per vertex or two, a second each at
// n = 10⁵): after the grace (CoveringOptions::check_seconds_after_stop) the check is cut short,
// the mesh, whole and valid, is returned at once, and the run is Interrupted and says what was
// not judged, in its message and in the validation it returns. With a grace the check
// finishes: the run completed, validated in full.
TEST(StopRequest, StopDuringTheFinalCheckCutsItShortAfterTheGrace) {
  const ThreadCountScope one(1);  // blocks of 512 vertices: the polls below are this count's
  const ProblemSetup setup = make_catalogue_problem("torus");
  const CoveringMethod& front = find_covering_method("front");
  MethodSettings settings;
  const CountedRun counted = run_counting_polls(setup, front, settings);
  const CoveringResult& whole = counted.result;
  const int build_polls = counted.build_polls;
  ASSERT_TRUE(whole.summary.is_complete()) << whole.summary.message;
  ASSERT_TRUE(whole.validation.has_value());
  // The check polls between blocks of vertices and of pairs of triangles, not per vertex: a
  // block is milliseconds at n = 3.
  ASSERT_GT(counted.whole_polls, build_polls + 3) << "the final check polls the stop request";

  // The stop comes after the build (no tolerance: no refinement polls), at the check's second
  // poll: the orientation check has judged its first block of vertices only.
  const int stop_after = build_polls + 1;
  settings.check_seconds_after_stop = 0.0;
  int polls = 0;
  settings.stop_requested = [&polls, stop_after] { return ++polls > stop_after; };
  const CoveringResult stopped = cover(setup, front, settings);
  EXPECT_EQ(stopped.summary.termination, CoveringTermination::Interrupted)
      << stopped.summary.message;
  EXPECT_NE(stopped.summary.message.find("final check"), std::string::npos)
      << stopped.summary.message;
  EXPECT_EQ(polls, stop_after + 1);  // not asked again after the first `true`
  EXPECT_EQ(stopped.mesh.vertex_count(), whole.mesh.vertex_count());
  EXPECT_EQ(stopped.mesh.triangle_count(), whole.mesh.triangle_count());
  ASSERT_TRUE(stopped.validation.has_value());
  EXPECT_TRUE(stopped.validation->is_valid()) << stopped.validation->report();
  ASSERT_TRUE(stopped.validation->is_cut_short());
  EXPECT_NE(stopped.validation->checks_cut_short.front().find("not judged"), std::string::npos)
      << stopped.validation->checks_cut_short.front();
  // What was not judged is still valid: the whole check of the same mesh finds nothing.
  const MeshValidation full = validate(stopped.mesh, *setup.problem, setup.domain);
  EXPECT_TRUE(full.is_valid()) << full.report();
  EXPECT_FALSE(full.is_cut_short());

  // A grace longer than the check: it finishes, and the run is complete.
  settings.check_seconds_after_stop = 60.0;
  polls = 0;
  const CoveringResult finished = cover(setup, front, settings);
  EXPECT_TRUE(finished.summary.is_complete()) << finished.summary.message;
  ASSERT_TRUE(finished.validation.has_value());
  EXPECT_FALSE(finished.validation->is_cut_short());
}

// After a stop in the build, the check gets the grace from its start; with none it judges
// nothing on M, and the run (Interrupted already) notes it.
TEST(StopRequest, StopInTheBuildWithoutGraceLeavesTheCheckOnMUndone) {
  const ProblemSetup setup = make_catalogue_problem("torus");
  MethodSettings settings;
  settings.check_seconds_after_stop = 0.0;
  int polls = 0;
  settings.stop_requested = [&polls] { return ++polls > 40; };
  const CoveringResult stopped = cover(setup, find_covering_method("front"), settings);
  EXPECT_EQ(stopped.summary.termination, CoveringTermination::Interrupted);
  EXPECT_EQ(polls, 41);
  ASSERT_TRUE(stopped.validation.has_value());
  ASSERT_TRUE(stopped.validation->is_cut_short());
  const auto& notes = stopped.summary.notes;
  EXPECT_TRUE(std::any_of(notes.begin(), notes.end(), [](const std::string& note) {
    return note.find("final check, which was cut short") != std::string::npos;
  }));
  const MeshValidation full = validate(stopped.mesh, *setup.problem, setup.domain);
  EXPECT_TRUE(full.is_valid()) << full.report();
}

// A hook that says stop at once still leaves a summary and a valid (possibly tiny) mesh.
TEST(StopRequest, StopAtTheFirstPollIsAnOutcomeForEveryMethod) {
  const ProblemSetup setup = make_catalogue_problem("sphere");
  for (const CoveringMethod& method : covering_methods()) {
    SCOPED_TRACE(method.name);
    MethodSettings settings;
    settings.stop_requested = [] { return true; };
    const CoveringResult result = cover(setup, method, settings);
    EXPECT_EQ(result.summary.termination, CoveringTermination::Interrupted)
        << result.summary.message;
    EXPECT_NE(result.summary.message.find("interrupted"), std::string::npos)
        << result.summary.message;
    const MeshValidation validation = validate(result.mesh, *setup.problem, setup.domain);
    EXPECT_TRUE(validation.is_valid()) << validation.report();
  }
}

}  // namespace
}  // namespace tessera
