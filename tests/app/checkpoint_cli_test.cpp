// SPDX-License-Identifier: MIT
// `tessera mesh --checkpoint` and `tessera resume` as processes: runs killed with SIGKILL at
// pseudo-random moments (fixed seeds) after their first checkpoint, or stopped by SIGTERM, and
// resumed, write the same mesh file, byte for byte, as the run that was never stopped. Bad
// checkpoints are refused with a message and nothing is written (docs/checkpoints.md).
#include <gtest/gtest.h>

#include <fcntl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <random>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "support/test_support.h"
#include "tessera/io/checkpoint_file.h"

namespace tessera {
namespace {

namespace fs = std::filesystem;

void write_bytes(const std::string& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary) << bytes;
}

// A build of half a second (bvp, n = 202, sparse: 3200 charts) with checkpoints every 0.05 s;
// the report measures few samples, so that a run takes about a second.
const char* const kProblem = "bvp:points=200";
// The front's: the same problem, a build of 1.5 s with checkpoints (20 MB each) every 0.05 s
// (sparse: KLU, the border guides and the grid's fitted view are all in its state).
const char* const kFrontProblem = "bvp:points=200";

// The run of `method` (atlas: kProblem, front: kFrontProblem) with checkpoints to folder/run.tsc.
std::vector<std::string> mesh_words(const std::string& folder,
                                    const std::string& method = "atlas") {
  return {TESSERA_CLI,
          "mesh",
          method == "front" ? kFrontProblem : kProblem,
          "--method",
          method,
          "-o",
          folder + "/mesh.ply",
          "--report-samples",
          "50",
          "--checkpoint",
          folder + "/run.tsc",
          "--checkpoint-every",
          "0.05",
          "-q"};
}

// The run with checkpoints that is never stopped, made once per method: its mesh, and what
// its last checkpoint (at the end of the build) holds, the atlas's charts or the front's
// vertices; that checkpoint resumed gives the same mesh again. (A run without --checkpoint may
// differ from it by the rounding of KLU's pivots, which a checkpointed run makes afresh in every
// factorisation: docs/checkpoints.md.)
struct Reference {
  std::string mesh;
  int complete_build = 0;
};

Reference make_reference(const std::string& method) {
  const std::string folder = testing::temporary_directory("checkpoint_reference_" + method);
  const testing::CommandResult run = testing::run_cli(
      std::string("mesh ") + (method == "front" ? kFrontProblem : kProblem) + " --method " +
      method + " --report-samples 50 -q -o " + folder + "/mesh.ply --checkpoint " + folder +
      "/run.tsc --checkpoint-every 1000");
  EXPECT_EQ(run.exit_code, 0) << run.output;
  Reference reference{testing::read_file_bytes(folder + "/mesh.ply")};
  const testing::CommandResult again = testing::run_cli(
      "resume " + folder + "/run.tsc -q -o " + folder + "/again.ply --summary " + folder +
      "/again.json");
  EXPECT_EQ(again.exit_code, 0) << again.output;
  EXPECT_TRUE(testing::read_file_bytes(folder + "/again.ply") == reference.mesh);
  const nlohmann::json resumed =
      nlohmann::json::parse(testing::read_file_bytes(folder + "/again.json"))["run"]["resumed_from"];
  reference.complete_build = resumed[method == "front" ? "vertices" : "charts"].get<int>();
  return reference;
}

const Reference& reference(const std::string& method) {
  static const Reference atlas = make_reference("atlas");
  if (method == "atlas") {
    return atlas;
  }
  static const Reference front = make_reference("front");
  return front;
}

const std::string& reference_mesh(const std::string& method = "atlas") {
  return reference(method).mesh;
}

// Waits until `path` exists (or the process ended); false if it never came.
bool wait_for_file(const std::string& path, pid_t child) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  int status = 0;
  while (!fs::exists(path)) {
    if (waitpid(child, &status, WNOHANG) == child || std::chrono::steady_clock::now() > deadline) {
      return false;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  return true;
}

// Kills runs of `method` at moments drawn from each seed, resumes them and compares the meshes.
void expect_killed_runs_resume(const std::string& method, int most_milliseconds) {
  ASSERT_FALSE(reference_mesh(method).empty());
  int killed_in_build = 0;
  for (const unsigned seed : {1u, 2u, 3u, 4u}) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    const std::string folder =
        testing::temporary_directory("checkpoint_kill_" + method + std::to_string(seed));
    const pid_t child =
        testing::spawn(mesh_words(folder, method), folder + "/log.txt", folder + "/log.txt");
    ASSERT_TRUE(wait_for_file(folder + "/run.tsc", child)) << testing::read_file_bytes(folder + "/log.txt");
    // A pseudo-random moment after the first checkpoint, between checkpoints or in one.
    std::mt19937 random(seed);
    std::this_thread::sleep_for(
        std::chrono::milliseconds(std::uniform_int_distribution<int>(0, most_milliseconds)(random)));
    kill(child, SIGKILL);
    int status = 0;
    waitpid(child, &status, 0);
    ASSERT_TRUE(WIFSIGNALED(status)) << "the run ended before the kill";
    EXPECT_FALSE(fs::exists(folder + "/mesh.ply")) << "a killed build wrote no mesh";
    const testing::CommandResult resumed =
        testing::run_cli("resume " + folder + "/run.tsc -q --summary " + folder + "/summary.json");
    ASSERT_EQ(resumed.exit_code, 0) << resumed.output;
    EXPECT_TRUE(testing::read_file_bytes(folder + "/mesh.ply") == reference_mesh(method))
        << "the resumed run's mesh differs from the uninterrupted run's";
    const nlohmann::json run = nlohmann::json::parse(testing::read_file_bytes(folder + "/summary.json"))["run"];
    killed_in_build += run["resumed_from"][method == "front" ? "vertices" : "charts"].get<int>() <
                       reference(method).complete_build;
  }
  EXPECT_GE(killed_in_build, 3) << "most kills must come during the build for the test to mean it";
}

TEST(CliCheckpoint, KilledRunsResumeToTheSameMesh) { expect_killed_runs_resume("atlas", 350); }

TEST(CliCheckpoint, KilledFrontRunsResumeToTheSameMesh) {
  expect_killed_runs_resume("front", 900);
}

// Stops a run of `method` by SIGTERM `milliseconds` after its first checkpoint and resumes it.
void expect_sigterm_then_resume(const std::string& method, int milliseconds) {
  const std::string folder = testing::temporary_directory("checkpoint_sigterm_" + method);
  std::vector<std::string> words = mesh_words(folder, method);
  words.push_back("--summary");
  words.push_back(folder + "/summary.json");
  const pid_t child = testing::spawn(words, folder + "/log.txt", folder + "/log.txt");
  ASSERT_TRUE(wait_for_file(folder + "/run.tsc", child));
  std::this_thread::sleep_for(std::chrono::milliseconds(milliseconds));
  kill(child, SIGTERM);
  int status = 0;
  waitpid(child, &status, 0);
  ASSERT_TRUE(WIFEXITED(status)) << testing::read_file_bytes(folder + "/log.txt");
  ASSERT_EQ(WEXITSTATUS(status), 1) << "a stopped run ends as stopped early";
  const nlohmann::json stopped = nlohmann::json::parse(testing::read_file_bytes(folder + "/summary.json"));
  ASSERT_EQ(stopped["stop"]["stage"], "build") << stopped.dump(1);

  const testing::CommandResult resumed =
      testing::run_cli("resume " + folder + "/run.tsc -q --summary " + folder + "/resumed.json");
  ASSERT_EQ(resumed.exit_code, 0) << resumed.output;
  EXPECT_TRUE(testing::read_file_bytes(folder + "/mesh.ply") == reference_mesh(method));
  const nlohmann::json summary = nlohmann::json::parse(testing::read_file_bytes(folder + "/resumed.json"));
  ASSERT_TRUE(summary["run"].contains("resumed_from")) << summary["run"].dump(1);
  if (method == "atlas") {
    EXPECT_EQ(summary["run"]["resumed_from"]["charts"], stopped["run"]["atlas"]["charts"]);
  } else {  // (the stopped run's mesh is clipped: its vertices are not the build's)
    EXPECT_GT(summary["run"]["resumed_from"]["vertices"].get<int>(), 7);
    EXPECT_LT(summary["run"]["resumed_from"]["vertices"].get<int>(),
              reference(method).complete_build);
  }
  EXPECT_GT(summary["run"]["function_evaluations"].get<long>(),
            summary["run"]["resumed_from"]["function_evaluations"].get<long>());
  EXPECT_FALSE(summary.contains("stop"));
}

TEST(CliCheckpoint, SigtermThenResumeGivesTheSameMeshAndCountsTheWork) {
  expect_sigterm_then_resume("atlas", 150);
}

TEST(CliCheckpoint, SigtermThenResumeGivesTheSameFrontMesh) {
  expect_sigterm_then_resume("front", 500);
}

// A refused resume: exit 2, the message, and no mesh written at `-o`.
void expect_refused(const std::string& checkpoint, const std::string& message) {
  const std::string output = fs::path(checkpoint).parent_path().string() + "/refused.ply";
  const testing::CommandResult run = testing::run_cli("resume " + checkpoint + " -o " + output);
  EXPECT_EQ(run.exit_code, 2) << run.output;
  EXPECT_NE(run.output.find(message), std::string::npos) << run.output;
  EXPECT_FALSE(fs::exists(output)) << run.output;
}

TEST(CliCheckpoint, DamagedCheckpointsAreRefused) {
  const std::string folder = testing::temporary_directory("checkpoint_damaged");
  const testing::CommandResult run = testing::run_cli(
      "mesh sphere -q -o " + folder + "/mesh.ply --checkpoint " + folder + "/run.tsc");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  const std::string good = testing::read_file_bytes(folder + "/run.tsc");
  ASSERT_GT(good.size(), 100u);
  write_bytes(folder + "/truncated.tsc", good.substr(0, good.size() * 2 / 3));
  expect_refused(folder + "/truncated.tsc", "truncated");
  std::string flipped = good;
  flipped[flipped.size() / 2] ^= 0x10;
  write_bytes(folder + "/flipped.tsc", flipped);
  expect_refused(folder + "/flipped.tsc", "checksum");
  std::string magic = good;
  magic[0] = 'X';
  write_bytes(folder + "/magic.tsc", magic);
  expect_refused(folder + "/magic.tsc", "not a tessera checkpoint");
  std::string version = good;
  version[8] = 9;
  write_bytes(folder + "/version.tsc", version);
  expect_refused(folder + "/version.tsc", "format version 9");
  // The good one resumes (nothing to build: it was saved at the end of the build).
  const testing::CommandResult resumed =
      testing::run_cli("resume " + folder + "/run.tsc -q -o " + folder + "/again.ply");
  EXPECT_EQ(resumed.exit_code, 0) << resumed.output;
  EXPECT_TRUE(testing::read_file_bytes(folder + "/again.ply") == testing::read_file_bytes(folder + "/mesh.ply"));
}

TEST(CliCheckpoint, ChangedProblemFileIsRefused) {
  for (const std::string method : {"atlas", "front"}) {
    SCOPED_TRACE(method);
    const std::string folder = testing::temporary_directory("checkpoint_problem_file_" + method);
    const std::string problem = folder + "/sphere_cut.tsr";
    fs::copy_file(testing::source_path("examples/problems/sphere_cut.tsr"), problem);
    const testing::CommandResult run =
        testing::run_cli("mesh " + problem + " --method " + method + " -q -o " + folder +
                         "/mesh.ply --checkpoint " + folder + "/run.tsc");
    ASSERT_EQ(run.exit_code, 0) << run.output;
    std::ofstream(problem, std::ios::app) << "# changed\n";
    const std::string mesh = testing::read_file_bytes(folder + "/mesh.ply");
    expect_refused(folder + "/run.tsc", "changed since");
    EXPECT_TRUE(testing::read_file_bytes(folder + "/mesh.ply") == mesh) << "the original mesh is untouched";
  }
}

// The front's checkpoint: a damaged file is refused; a state of another problem (the problem
// file's parameter changed, and the file's fingerprint with it) too; the good one resumes.
TEST(CliCheckpoint, DamagedOrForeignFrontCheckpointsAreRefused) {
  const std::string folder = testing::temporary_directory("checkpoint_front_damaged");
  const testing::CommandResult run =
      testing::run_cli("mesh torus --method front -q -o " + folder + "/mesh.ply --checkpoint " +
                       folder + "/run.tsc");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  const std::string good = testing::read_file_bytes(folder + "/run.tsc");
  ASSERT_GT(good.size(), 1000u);
  write_bytes(folder + "/truncated.tsc", good.substr(0, good.size() / 2));
  expect_refused(folder + "/truncated.tsc", "truncated");
  std::string flipped = good;
  flipped[flipped.size() * 3 / 4] ^= 0x04;
  write_bytes(folder + "/flipped.tsc", flipped);
  expect_refused(folder + "/flipped.tsc", "checksum");
  // A well-formed file whose command line runs another torus than its state's: refused by F.
  const testing::CommandResult other = testing::run_cli(
      "mesh torus:r=0.45 --method front -q -o " + folder + "/other.ply --checkpoint " + folder +
      "/other.tsc");
  ASSERT_EQ(other.exit_code, 0) << other.output;
  CheckpointFile foreign = read_checkpoint_file(folder + "/other.tsc");
  const CheckpointFile original = read_checkpoint_file(folder + "/run.tsc");
  for (auto& [name, payload] : foreign.sections) {
    if (name == "front") {
      payload = original.section("front", "run.tsc");
    }
  }
  write_checkpoint_file(folder + "/foreign.tsc", foreign);
  expect_refused(folder + "/foreign.tsc", "differs from the checkpoint's");
  // A front's state under a command line of the atlas: refused by the method.
  CheckpointFile atlas = original;
  for (auto& [name, payload] : atlas.sections) {
    if (name == "method") {
      payload = "atlas";
    } else if (name == "front") {
      name = "atlas";
    }
  }
  write_checkpoint_file(folder + "/method.tsc", atlas);
  expect_refused(folder + "/method.tsc", "runs --method front");
  // `extend` is the atlas's.
  const testing::CommandResult extended = testing::run_cli(
      "extend " + folder + "/run.tsc --box -3,3,-3,3,-3,3 -o " + folder + "/extended.ply");
  EXPECT_EQ(extended.exit_code, 2) << extended.output;
  EXPECT_NE(extended.output.find("extend continues an atlas"), std::string::npos)
      << extended.output;
  EXPECT_FALSE(fs::exists(folder + "/extended.ply"));
  const testing::CommandResult resumed =
      testing::run_cli("resume " + folder + "/run.tsc -q -o " + folder + "/again.ply");
  EXPECT_EQ(resumed.exit_code, 0) << resumed.output;
  EXPECT_TRUE(testing::read_file_bytes(folder + "/again.ply") == testing::read_file_bytes(folder + "/mesh.ply"));
}

TEST(CliCheckpoint, OtherMethodsAreRefused) {
  const std::string folder = testing::temporary_directory("checkpoint_bezier");
  const testing::CommandResult run = testing::run_cli(
      "mesh sphere --method bezier -o " + folder + "/mesh.ply --checkpoint " + folder + "/run.tsc");
  EXPECT_EQ(run.exit_code, 2) << run.output;
  EXPECT_NE(run.output.find("checkpoints are supported for --method atlas and front"),
            std::string::npos)
      << run.output;
  EXPECT_FALSE(fs::exists(folder + "/mesh.ply"));
  EXPECT_FALSE(fs::exists(folder + "/run.tsc"));
}

}  // namespace
}  // namespace tessera
