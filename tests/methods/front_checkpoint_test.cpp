// SPDX-License-Identifier: MIT
// Checkpoints of method `front` (front_checkpoint.h): a build stopped after k steps, saved and
// continued gives the same mesh, bit for bit, as the build that was never stopped — from the
// stop's own checkpoint and from earlier periodic ones (what a kill -9 leaves), for several k —
// on closed surfaces (sphere, torus), in a box (deferred steps, the sphere's caps outside it),
// on bratu2d's band (reopened vertices; sparse, n = 66: the grid's fitted view, the border
// guides) and bvp (n = 202), in both orders. A state of another problem or options, or a
// damaged one, is refused with a message that names what differs.
#include "tessera/methods/front/advancing_front.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <map>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "support/test_support.h"
#include "tessera/core/error.h"
#include "tessera/problems/problem_file.h"
#include "tessera/problems/catalogue.h"

namespace tessera {
namespace {

struct Case {
  std::string problem;  // a catalogue entry, or a problem file under the source tree
  double step = 0.0;    // 0: the problem's suggested step
  FrontOrder order = FrontOrder::SmallestGapFirst;
  double tolerance = 0.0;  // the command line's default for the front: no bound
};

ProblemSetup setup_of(const Case& c) {
  return c.problem.find('/') != std::string::npos
             ? load_problem_file(testing::source_path(c.problem))
             : make_catalogue_problem(c.problem);
}

FrontOptions options_for(const Case& c, const ProblemSetup& setup) {
  FrontOptions options;  // the command line's defaults
  options.step = c.step > 0 ? c.step : setup.suggested_step;
  options.tolerance = c.tolerance;
  options.order = c.order;
  return options;
}

struct Checkpoints {
  std::vector<std::string> periodic;  // every `every`-th step
  std::string at_stop;
  CoveringResult result;
};

// Builds with a stop request after `stop_after` steps (0: never) and a periodic checkpoint
// every `every` steps, continuing `resume_from` if given.
Checkpoints build(const Case& c, const ProblemSetup& setup, int stop_after, int every,
                  std::shared_ptr<const std::string> resume_from = nullptr) {
  Checkpoints saved;
  FrontOptions options = options_for(c, setup);
  auto polls = std::make_shared<int>(0);
  auto due = std::make_shared<int>(0);
  if (stop_after > 0) {
    options.stop_requested = [polls, stop_after] { return ++*polls > stop_after; };
  }
  options.checkpoint.is_due = [due, every] { return every > 0 && ++*due % every == 0; };
  options.checkpoint.save = [&saved, polls, stop_after](std::string state) {
    (stop_after > 0 && *polls > stop_after ? saved.at_stop : saved.periodic.emplace_back()) =
        std::move(state);
  };
  options.checkpoint.resume_from = std::move(resume_from);
  saved.result = triangulate_by_front(*setup.problem, setup.start, setup.domain, options);
  return saved;
}

// The run never stopped, with checkpoints (saved nowhere): a run with checkpoints makes every
// sparse factorisation afresh (FullPivotingScope), one without may round KLU's pivots otherwise.
CoveringResult uninterrupted(const Case& c, const ProblemSetup& setup) {
  FrontOptions options = options_for(c, setup);
  options.checkpoint.is_due = [] { return false; };
  options.checkpoint.save = [](const std::string&) {};
  return triangulate_by_front(*setup.problem, setup.start, setup.domain, options);
}

// Stops after each of `stops` steps; resumes from the stop's state and from a periodic one.
void expect_resumes_identically(const Case& c, const std::vector<int>& stops, int every) {
  SCOPED_TRACE(c.problem + " at step " + std::to_string(c.step) +
               (c.order == FrontOrder::Fifo ? ", FIFO" : ""));
  const ProblemSetup setup = setup_of(c);
  const CoveringResult whole = uninterrupted(c, setup);
  ASSERT_TRUE(whole.summary.is_complete()) << whole.summary.message;
  const auto from = [&](const std::string& state) {
    return build(c, setup, 0, 0, std::make_shared<const std::string>(state)).result;
  };
  for (const int stop_after : stops) {
    SCOPED_TRACE("stopped after " + std::to_string(stop_after) + " steps");
    const Checkpoints stopped = build(c, setup, stop_after, every);
    ASSERT_EQ(stopped.result.summary.termination, CoveringTermination::Interrupted)
        << "the stop must come during the build: " << stopped.result.summary.message;
    ASSERT_FALSE(stopped.at_stop.empty()) << "a stop saves the state";
    const CoveringResult resumed = from(stopped.at_stop);
    ASSERT_TRUE(resumed.summary.is_complete()) << resumed.summary.message;
    testing::expect_identical_meshes(whole.mesh, resumed.mesh, "resumed from the stop");
    EXPECT_EQ(resumed.summary.merges, whole.summary.merges);
    EXPECT_EQ(resumed.summary.front_connections, whole.summary.front_connections);
    EXPECT_EQ(resumed.summary.notes, whole.summary.notes);
    ASSERT_TRUE(resumed.summary.resumed_from.has_value());
    EXPECT_GT(resumed.summary.resumed_from->vertices, 7);
    EXPECT_EQ(resumed.summary.resumed_from->charts, 0);
    // The work before the checkpoint is counted: at least the uninterrupted run's.
    EXPECT_GE(resumed.summary.function_evaluations, whole.summary.function_evaluations);
    if (!stopped.periodic.empty()) {
      const std::string& earlier = stopped.periodic[stopped.periodic.size() / 2];
      testing::expect_identical_meshes(whole.mesh, from(earlier).mesh, "resumed from a periodic checkpoint");
    }
  }
  // Stopped again after resuming, and resumed once more.
  const Checkpoints first = build(c, setup, stops.front(), 0);
  ASSERT_FALSE(first.at_stop.empty());
  const Checkpoints twice =
      build(c, setup, stops.front(), 0, std::make_shared<const std::string>(first.at_stop));
  ASSERT_EQ(twice.result.summary.termination, CoveringTermination::Interrupted);
  ASSERT_FALSE(twice.at_stop.empty());
  testing::expect_identical_meshes(whole.mesh, from(twice.at_stop).mesh, "resumed twice");
  // The complete build's own checkpoint (what the end saves) gives the mesh again.
  const Checkpoints complete = build(c, setup, 0, 0);
  ASSERT_FALSE(complete.periodic.empty()) << "the end of the build saves";
  testing::expect_identical_meshes(whole.mesh, from(complete.periodic.back()).mesh, "resumed when complete");
}

TEST(FrontCheckpoint, SphereResumesToTheSameMesh) {
  expect_resumes_identically({"sphere"}, {1, 17, 60, 150}, 11);
}

TEST(FrontCheckpoint, SphereInFifoOrderResumesToTheSameMesh) {
  expect_resumes_identically({"sphere", 0.0, FrontOrder::Fifo}, {5, 80}, 7);
}

TEST(FrontCheckpoint, TorusResumesToTheSameMesh) {
  expect_resumes_identically({"torus"}, {3, 90, 400}, 37);
}

// The sphere in the box [-0.97, 0.97]³: steps that ran into the mesh are undone and deferred.
TEST(FrontCheckpoint, SphereInABoxWithDeferredStepsResumesToTheSameMesh) {
  expect_resumes_identically({"tests/stress/problems/sphere_box.tsr", 0.3}, {20, 45, 70}, 5);
}

// bratu2d's band narrower than the step: exterior vertices reopened (n = 66, sparse).
TEST(FrontCheckpoint, Bratu2dBandResumesToTheSameMesh) {
  expect_resumes_identically({"bratu2d:N=8", 0.4}, {10, 40, 90}, 9);
}

TEST(FrontCheckpoint, BvpResumesToTheSameMesh) {  // n = 202, sparse; refined to a bound
  expect_resumes_identically({"bvp:points=200", 0.0, FrontOrder::SmallestGapFirst, 0.01}, {25, 120},
                             23);
}

// A stop after every step of a whole run, each resumed: state that decides only now and then
// (a deferral count, a key's last bits, a tie in the order) is caught where a few stops miss
// it. Dense problems at n = 3, whose runs take milliseconds.
void expect_every_stop_resumes(const Case& c, int stride) {
  SCOPED_TRACE(c.problem + (c.order == FrontOrder::Fifo ? ", FIFO" : ""));
  const ProblemSetup setup = setup_of(c);
  const CoveringResult whole = uninterrupted(c, setup);
  ASSERT_TRUE(whole.summary.is_complete()) << whole.summary.message;
  int stops = 0;
  for (int stop_after = 1;; stop_after += stride) {
    const Checkpoints stopped = build(c, setup, stop_after, 0);
    if (stopped.at_stop.empty()) {
      break;  // the build ended before this step (a later stage may have seen the stop)
    }
    ASSERT_EQ(stopped.result.summary.termination, CoveringTermination::Interrupted);
    const CoveringResult resumed =
        build(c, setup, 0, 0, std::make_shared<const std::string>(stopped.at_stop)).result;
    ASSERT_EQ(resumed.mesh.triangle_count(), whole.mesh.triangle_count())
        << "stopped after " << stop_after << " steps";
    ASSERT_TRUE(resumed.mesh.triangles() == whole.mesh.triangles() &&
                resumed.mesh.points() == whole.mesh.points())
        << "stopped after " << stop_after << " steps: the resumed mesh differs";
    ++stops;
  }
  EXPECT_GT(stops, 20);
}

// The state a resumed build saves after its first step is the uninterrupted build's after the
// same step, byte for byte, but for the build time and the work counts (a resumed run projects
// its start again), 32 bytes together: whatever a resume failed to restore shows there, whether
// or not it changed the mesh of these runs. Every `stride`-th step.
void expect_resumed_states_continue(const Case& c, int stride) {
  SCOPED_TRACE(c.problem + (c.order == FrontOrder::Fifo ? ", FIFO" : ""));
  const ProblemSetup setup = setup_of(c);
  // The uninterrupted build's state after steps stride, 2·stride, …, and after the step past
  // each (the front's states are large at n = 202: only these are kept).
  std::map<int, std::string> states;
  {
    FrontOptions options = options_for(c, setup);
    auto steps = std::make_shared<int>(0);
    options.checkpoint.is_due = [steps] { return ++*steps > 0; };
    options.checkpoint.save = [&states, steps, stride](std::string state) {
      if (*steps % stride <= 1 && !states.contains(*steps)) {  // (not the end's save)
        states[*steps] = std::move(state);
      }
    };
    ASSERT_TRUE(triangulate_by_front(*setup.problem, setup.start, setup.domain, options)
                    .summary.is_complete());
  }
  int compared = 0;
  for (const auto& [step, state] : states) {
    if (step % stride != 0 || !states.contains(step + 1)) {
      continue;
    }
    const std::string& next = states.at(step + 1);
    FrontOptions options = options_for(c, setup);
    auto polls = std::make_shared<int>(0);
    options.stop_requested = [polls] { return ++*polls > 1; };
    std::string resumed_next;
    options.checkpoint.is_due = [] { return true; };
    options.checkpoint.save = [&resumed_next](std::string saved) {
      if (resumed_next.empty()) {
        resumed_next = std::move(saved);
      }
    };
    options.checkpoint.resume_from = std::make_shared<const std::string>(state);
    triangulate_by_front(*setup.problem, setup.start, setup.domain, options);
    ASSERT_EQ(resumed_next.size(), next.size()) << "after step " << step + 1;
    std::size_t first = next.size();
    std::size_t last = 0;
    for (std::size_t k = 0; k < next.size(); ++k) {
      if (next[k] != resumed_next[k]) {
        first = std::min(first, k);
        last = k;
      }
    }
    EXPECT_TRUE(first == next.size() || last - first < 32)
        << "after step " << step + 1 << ": bytes " << first << " to " << last
        << " of " << next.size() << " differ, more than the build time and the work counts";
    ++compared;
  }
  EXPECT_GT(compared, 10);
}

TEST(FrontCheckpoint, ResumedStatesContinueTheUninterruptedOnes) {
  expect_resumed_states_continue({"sphere"}, 1);
  expect_resumed_states_continue({"sphere", 0.0, FrontOrder::Fifo}, 1);
  expect_resumed_states_continue({"tests/stress/problems/sphere_box.tsr", 0.3}, 1);
  expect_resumed_states_continue({"tests/stress/problems/sphere_box.tsr", 0.15}, 1);
  expect_resumed_states_continue({"torus"}, 5);
  expect_resumed_states_continue({"bratu2d:N=8", 0.4}, 5);
}

TEST(FrontCheckpoint, ResumedStatesOfBvpContinueTheUninterruptedOnes) {  // n = 202, sparse
  expect_resumed_states_continue({"bvp:points=200"}, 250);
}

TEST(FrontCheckpoint, EveryStopOfTheSphereResumesToTheSameMesh) {
  expect_every_stop_resumes({"sphere"}, 1);
  expect_every_stop_resumes({"sphere", 0.0, FrontOrder::Fifo}, 1);
}

TEST(FrontCheckpoint, EveryStopOfTheSphereInABoxResumesToTheSameMesh) {  // deferred steps
  expect_every_stop_resumes({"tests/stress/problems/sphere_box.tsr", 0.3}, 1);
  expect_every_stop_resumes({"tests/stress/problems/sphere_box.tsr", 0.15}, 2);
}

TEST(FrontCheckpoint, EveryFifteenthStopOfTheTorusResumesToTheSameMesh) {
  expect_every_stop_resumes({"torus"}, 15);
}

// Without checkpoints the dense problems' factorisations are the same: the mesh is too.
TEST(FrontCheckpoint, CheckpointsLeaveADenseRunUnchanged) {
  const Case c{"torus"};
  const ProblemSetup setup = setup_of(c);
  const FrontOptions plain = options_for(c, setup);
  testing::expect_identical_meshes(triangulate_by_front(*setup.problem, setup.start, setup.domain, plain).mesh,
                   uninterrupted(c, setup).mesh, "with and without checkpoints");
}

// A state too large to write at a stop is not written there; the note says so, and the last
// periodic checkpoint gives the same mesh.
TEST(FrontCheckpoint, LargeStateIsNotWrittenAtTheStop) {
  const Case c{"torus"};
  const ProblemSetup setup = setup_of(c);
  FrontOptions options = options_for(c, setup);
  auto polls = std::make_shared<int>(0);
  options.stop_requested = [polls] { return ++*polls > 200; };
  options.checkpoint.is_due = [polls] { return *polls % 50 == 0; };
  std::vector<std::string> saved;
  options.checkpoint.save = [&saved](std::string state) { saved.push_back(std::move(state)); };
  options.checkpoint.max_bytes_at_stop = 0;
  const CoveringResult stopped =
      triangulate_by_front(*setup.problem, setup.start, setup.domain, options);
  ASSERT_EQ(stopped.summary.termination, CoveringTermination::Interrupted);
  EXPECT_EQ(saved.size(), 4u) << "the periodic ones only (steps 50, 100, 150, 200)";
  bool noted = false;
  for (const std::string& note : stopped.summary.notes) {
    noted = noted || note.find("no checkpoint was written at the stop") != std::string::npos;
  }
  EXPECT_TRUE(noted);
  ASSERT_FALSE(saved.empty());
  FrontOptions resumed = options_for(c, setup);
  resumed.checkpoint.resume_from = std::make_shared<const std::string>(saved.back());
  testing::expect_identical_meshes(uninterrupted(c, setup).mesh,
                   triangulate_by_front(*setup.problem, setup.start, setup.domain, resumed).mesh,
                   "resumed from the last periodic checkpoint");
}

// The state of one run given to another: refused, the message naming what differs.
void expect_refused(const std::string& state, const ProblemSetup& setup, FrontOptions options,
                    const std::string& named) {
  options.checkpoint.resume_from = std::make_shared<const std::string>(state);
  try {
    triangulate_by_front(*setup.problem, setup.start, setup.domain, options);
    ADD_FAILURE() << "not refused; expected a message naming " << named;
  } catch (const InvalidArgument& error) {
    EXPECT_NE(std::string(error.what()).find(named), std::string::npos) << error.what();
  }
}

TEST(FrontCheckpoint, AnotherProblemOrOptionsIsRefused) {
  const Case c{"torus:R=2,r=0.5"};
  const ProblemSetup setup = setup_of(c);
  const std::string state = build(c, setup, 100, 0).at_stop;
  ASSERT_FALSE(state.empty());
  // Another parameter of the same problem: its name may say nothing, F does.
  const ProblemSetup other = make_catalogue_problem("torus:R=2,r=0.6");
  expect_refused(state, other, options_for(c, setup), "differs from the checkpoint's");
  expect_refused(state, make_catalogue_problem("sphere"), options_for(c, setup),
                 "made for problem");
  FrontOptions wider = options_for(c, setup);
  wider.min_gap_angle = 0.7;
  expect_refused(state, setup, wider, "FrontOptions::min_gap_angle");
  FrontOptions fifo = options_for(c, setup);
  fifo.order = FrontOrder::Fifo;
  expect_refused(state, setup, fifo, "FrontOptions::order");
}

TEST(FrontCheckpoint, DamagedStateIsRefused) {
  const Case c{"sphere"};
  const ProblemSetup setup = setup_of(c);
  const std::string state = build(c, setup, 80, 0).at_stop;
  ASSERT_FALSE(state.empty());
  expect_refused(state.substr(0, state.size() / 2), setup, options_for(c, setup), "truncated");
  expect_refused(state.substr(0, state.size() - 3), setup, options_for(c, setup), "truncated");
  expect_refused(state + "x", setup, options_for(c, setup), "bytes after");
  std::string versioned = state;
  versioned[0] = 7;
  expect_refused(versioned, setup, options_for(c, setup), "format version 7");
}

}  // namespace
}  // namespace tessera
