// SPDX-License-Identifier: MIT
// Checkpoints of method `atlas` (atlas_checkpoint.h): a build stopped after k children, saved
// and continued gives the same mesh, bit for bit, as the build that was never stopped — from
// the stop's own checkpoint and from an earlier periodic one (what a kill -9 leaves) — on
// dense (n = 3) and sparse (large n) problems. A state of another problem, start or options,
// or a damaged one, is refused with a message that names what differs.
#include "tessera/methods/atlas/atlas.h"

#include <gtest/gtest.h>

#include <bit>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "support/test_support.h"
#include "tessera/core/error.h"
#include "tessera/problems/catalogue.h"

namespace tessera {
namespace {

AtlasOptions options_for(const ProblemSetup& setup) {
  AtlasOptions options;  // the command line's defaults
  options.step = 2.0 * setup.suggested_step;
  options.tolerance = 0.02 * setup.suggested_step;
  return options;
}

struct Checkpoints {
  std::vector<std::string> periodic;  // every `every`-th child
  std::string at_stop;
  CoveringResult result;
};

// Builds with a stop request after `stop_after` children (0: never) and a periodic checkpoint
// every `every` children, continuing `resume_from` if given.
Checkpoints build(const ProblemSetup& setup, int stop_after, int every,
                  std::shared_ptr<const std::string> resume_from = nullptr) {
  Checkpoints saved;
  AtlasOptions options = options_for(setup);
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
  saved.result = cover_by_atlas(*setup.problem, setup.start, setup.domain, options);
  return saved;
}

// The run never stopped, with checkpoints (saved nowhere): a run with checkpoints makes every
// factorisation afresh (FullPivotingScope), one without may round KLU's pivots differently.
CoveringResult uninterrupted(const ProblemSetup& setup) {
  AtlasOptions options = options_for(setup);
  options.checkpoint.is_due = [] { return false; };
  options.checkpoint.save = [](const std::string&) {};
  return cover_by_atlas(*setup.problem, setup.start, setup.domain, options);
}

void expect_resumes_identically(const std::string& specification, int stop_after, int every) {
  SCOPED_TRACE(specification);
  const ProblemSetup setup = make_catalogue_problem(specification);
  const CoveringResult whole = uninterrupted(setup);
  ASSERT_TRUE(whole.summary.is_complete()) << whole.summary.message;
  ASSERT_GT(whole.summary.charts, stop_after / 4) << "the stop must come during the build";

  const Checkpoints stopped = build(setup, stop_after, every);
  ASSERT_EQ(stopped.result.summary.termination, CoveringTermination::Interrupted);
  ASSERT_FALSE(stopped.at_stop.empty()) << "a stop saves the state";
  ASSERT_GE(stopped.periodic.size(), 2u) << "periodic checkpoints before the stop";

  // From the stop's checkpoint, and from an earlier periodic one (a kill -9 between two).
  const auto from = [&](const std::string& state) {
    return build(setup, 0, 0, std::make_shared<const std::string>(state)).result;
  };
  const CoveringResult resumed = from(stopped.at_stop);
  ASSERT_TRUE(resumed.summary.is_complete()) << resumed.summary.message;
  testing::expect_identical_meshes(whole.mesh, resumed.mesh, "resumed from the stop");
  ASSERT_TRUE(resumed.summary.resumed_from.has_value());
  EXPECT_GT(resumed.summary.resumed_from->charts, 1);
  EXPECT_LT(resumed.summary.resumed_from->charts, whole.summary.charts);
  EXPECT_EQ(resumed.summary.charts, whole.summary.charts);
  // The work before the checkpoint is counted: at least the uninterrupted run's, less the
  // repeated start projection.
  EXPECT_GE(resumed.summary.function_evaluations, whole.summary.function_evaluations);
  const std::string& earlier = stopped.periodic[stopped.periodic.size() / 2];
  testing::expect_identical_meshes(whole.mesh, from(earlier).mesh, "resumed from a periodic checkpoint");

  // Stopped again after resuming, and resumed once more.
  const Checkpoints twice =
      build(setup, stop_after / 2, 0, std::make_shared<const std::string>(stopped.at_stop));
  ASSERT_EQ(twice.result.summary.termination, CoveringTermination::Interrupted);
  ASSERT_FALSE(twice.at_stop.empty());
  testing::expect_identical_meshes(whole.mesh, from(twice.at_stop).mesh, "resumed twice");
}

TEST(AtlasCheckpoint, SphereResumesToTheSameMesh) { expect_resumes_identically("sphere", 150, 37); }

TEST(AtlasCheckpoint, TorusResumesToTheSameMesh) {
  expect_resumes_identically("torus:R=2,r=0.5", 300, 71);
}

// Sparse Jacobians (bordered LU): the kept factorisations are made again after the resume.
TEST(AtlasCheckpoint, BvpResumesToTheSameMesh) {
  expect_resumes_identically("bvp:points=200", 60, 13);
}

TEST(AtlasCheckpoint, Bratu2dResumesToTheSameMesh) {  // n = 146
  expect_resumes_identically("bratu2d:N=12", 60, 13);
}

// A state too large to write at a stop (it would delay the partial mesh) is not written there;
// the note says so and the last periodic checkpoint gives the same mesh.
TEST(AtlasCheckpoint, LargeStateIsNotWrittenAtTheStop) {
  const ProblemSetup setup = make_catalogue_problem("torus:R=2,r=0.5");
  AtlasOptions options = options_for(setup);
  auto polls = std::make_shared<int>(0);
  options.stop_requested = [polls] { return ++*polls > 200; };
  options.checkpoint.is_due = [polls] { return *polls % 50 == 0; };
  std::vector<std::string> saved;
  options.checkpoint.save = [&saved](std::string state) { saved.push_back(std::move(state)); };
  options.checkpoint.max_bytes_at_stop = 0;
  const CoveringResult stopped =
      cover_by_atlas(*setup.problem, setup.start, setup.domain, options);
  ASSERT_EQ(stopped.summary.termination, CoveringTermination::Interrupted);
  EXPECT_EQ(saved.size(), 4u) << "the periodic ones only (children 50, 100, 150, 200)";
  bool noted = false;
  for (const std::string& note : stopped.summary.notes) {
    noted = noted || note.find("no checkpoint was written at the stop") != std::string::npos;
  }
  EXPECT_TRUE(noted);
  ASSERT_FALSE(saved.empty());
  AtlasOptions resumed = options_for(setup);
  resumed.checkpoint.resume_from = std::make_shared<const std::string>(saved.back());
  testing::expect_identical_meshes(uninterrupted(setup).mesh,
                   cover_by_atlas(*setup.problem, setup.start, setup.domain, resumed).mesh,
                   "resumed from the last periodic checkpoint");
}

// The state of one run given to another: refused, the message naming what differs.
void expect_refused(const std::string& state, const ProblemSetup& setup, AtlasOptions options,
                    const std::string& named, const Eigen::VectorXd* start = nullptr) {
  options.checkpoint.resume_from = std::make_shared<const std::string>(state);
  try {
    cover_by_atlas(*setup.problem, start ? *start : setup.start, setup.domain, options);
    ADD_FAILURE() << "not refused; expected a message naming " << named;
  } catch (const InvalidArgument& error) {
    EXPECT_NE(std::string(error.what()).find(named), std::string::npos) << error.what();
  }
}

TEST(AtlasCheckpoint, AnotherProblemStartOrOptionsIsRefused) {
  const ProblemSetup setup = make_catalogue_problem("torus:R=2,r=0.5");
  const std::string state = build(setup, 100, 0).at_stop;
  ASSERT_FALSE(state.empty());
  // Another parameter of the same problem: its name may say nothing, F does.
  const ProblemSetup other = make_catalogue_problem("torus:R=2,r=0.6");
  expect_refused(state, other, options_for(setup), "differs from the checkpoint's");
  expect_refused(state, make_catalogue_problem("sphere"), options_for(setup), "made for problem");
  AtlasOptions coarser = options_for(setup);
  coarser.step *= 1.5;
  expect_refused(state, setup, coarser, "AtlasOptions::step");
  // (The start is projected onto M first: a start moved off M's normal lands elsewhere.)
  Eigen::VectorXd moved = setup.start;
  moved(0) += 0.05;
  moved(1) += 0.05;
  expect_refused(state, setup, options_for(setup), "start point", &moved);
}

TEST(AtlasCheckpoint, DamagedStateIsRefused) {
  const ProblemSetup setup = make_catalogue_problem("sphere");
  const std::string state = build(setup, 80, 0).at_stop;
  ASSERT_FALSE(state.empty());
  expect_refused(state.substr(0, state.size() / 2), setup, options_for(setup), "truncated");
  expect_refused(state + "x", setup, options_for(setup), "bytes after");
  std::string versioned = state;
  versioned[0] = 7;
  expect_refused(versioned, setup, options_for(setup), "format version 7");
}

}  // namespace
}  // namespace tessera
