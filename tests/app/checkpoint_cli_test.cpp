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

namespace tessera {
namespace {

namespace fs = std::filesystem;

void write_bytes(const std::string& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary) << bytes;
}

// A build of half a second (bvp, n = 202, sparse: 3200 charts) with checkpoints every 0.05 s;
// the report measures few samples, so that a run takes about a second.
const char* const kProblem = "bvp:points=200";

std::vector<std::string> mesh_words(const std::string& folder) {
  return {TESSERA_CLI,
          "mesh",
          kProblem,
          "--method",
          "atlas",
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

// The mesh of the run with checkpoints that is never stopped, made once. (A run without
// --checkpoint may differ from it by the rounding of KLU's pivots, which a checkpointed run
// makes afresh in every factorisation: docs/checkpoints.md.)
const std::string& reference_mesh() {
  static const std::string bytes = [] {
    const std::string folder = testing::temporary_directory("checkpoint_reference");
    const testing::CommandResult run = testing::run_cli(
        std::string("mesh ") + kProblem + " --method atlas --report-samples 50 -q -o " + folder +
        "/mesh.ply --checkpoint " + folder + "/run.tsc --checkpoint-every 1000");
    EXPECT_EQ(run.exit_code, 0) << run.output;
    return testing::read_file_bytes(folder + "/mesh.ply");
  }();
  return bytes;
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

TEST(CliCheckpoint, KilledRunsResumeToTheSameMesh) {
  ASSERT_FALSE(reference_mesh().empty());
  int killed_in_build = 0;
  for (const unsigned seed : {1u, 2u, 3u, 4u}) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    const std::string folder =
        testing::temporary_directory("checkpoint_kill_" + std::to_string(seed));
    const pid_t child = testing::spawn(mesh_words(folder), folder + "/log.txt", folder + "/log.txt");
    ASSERT_TRUE(wait_for_file(folder + "/run.tsc", child)) << testing::read_file_bytes(folder + "/log.txt");
    // A pseudo-random moment after the first checkpoint, between checkpoints or in one.
    std::mt19937 random(seed);
    std::this_thread::sleep_for(
        std::chrono::milliseconds(std::uniform_int_distribution<int>(0, 350)(random)));
    kill(child, SIGKILL);
    int status = 0;
    waitpid(child, &status, 0);
    ASSERT_TRUE(WIFSIGNALED(status)) << "the run ended before the kill";
    EXPECT_FALSE(fs::exists(folder + "/mesh.ply")) << "a killed build wrote no mesh";
    const testing::CommandResult resumed =
        testing::run_cli("resume " + folder + "/run.tsc -q --summary " + folder + "/summary.json");
    ASSERT_EQ(resumed.exit_code, 0) << resumed.output;
    EXPECT_TRUE(testing::read_file_bytes(folder + "/mesh.ply") == reference_mesh())
        << "the resumed run's mesh differs from the uninterrupted run's";
    const nlohmann::json run = nlohmann::json::parse(testing::read_file_bytes(folder + "/summary.json"))["run"];
    killed_in_build += run["resumed_from"]["charts"].get<int>() < run["atlas"]["charts"].get<int>();
  }
  EXPECT_GE(killed_in_build, 3) << "most kills must come during the build for the test to mean it";
}

TEST(CliCheckpoint, SigtermThenResumeGivesTheSameMeshAndCountsTheWork) {
  const std::string folder = testing::temporary_directory("checkpoint_sigterm");
  std::vector<std::string> words = mesh_words(folder);
  words.push_back("--summary");
  words.push_back(folder + "/summary.json");
  const pid_t child = testing::spawn(words, folder + "/log.txt", folder + "/log.txt");
  ASSERT_TRUE(wait_for_file(folder + "/run.tsc", child));
  std::this_thread::sleep_for(std::chrono::milliseconds(150));
  kill(child, SIGTERM);
  int status = 0;
  waitpid(child, &status, 0);
  ASSERT_TRUE(WIFEXITED(status)) << testing::read_file_bytes(folder + "/log.txt");
  ASSERT_EQ(WEXITSTATUS(status), 1) << "a stopped run ends as stopped early";
  const nlohmann::json stopped = nlohmann::json::parse(testing::read_file_bytes(folder + "/summary.json"));
  ASSERT_EQ(stopped["stop"]["stage"], "build") << stopped.dump(1);
  const int charts_at_stop = stopped["run"]["atlas"]["charts"];

  const testing::CommandResult resumed =
      testing::run_cli("resume " + folder + "/run.tsc -q --summary " + folder + "/resumed.json");
  ASSERT_EQ(resumed.exit_code, 0) << resumed.output;
  EXPECT_TRUE(testing::read_file_bytes(folder + "/mesh.ply") == reference_mesh());
  const nlohmann::json summary = nlohmann::json::parse(testing::read_file_bytes(folder + "/resumed.json"));
  ASSERT_TRUE(summary["run"].contains("resumed_from")) << summary["run"].dump(1);
  EXPECT_EQ(summary["run"]["resumed_from"]["charts"], charts_at_stop);
  EXPECT_GT(summary["run"]["function_evaluations"].get<long>(),
            summary["run"]["resumed_from"]["function_evaluations"].get<long>());
  EXPECT_FALSE(summary.contains("stop"));
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
  const std::string folder = testing::temporary_directory("checkpoint_problem_file");
  const std::string problem = folder + "/sphere_cut.tsr";
  fs::copy_file(testing::source_path("examples/problems/sphere_cut.tsr"), problem);
  const testing::CommandResult run = testing::run_cli(
      "mesh " + problem + " -q -o " + folder + "/mesh.ply --checkpoint " + folder + "/run.tsc");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  std::ofstream(problem, std::ios::app) << "# changed\n";
  const std::string mesh = testing::read_file_bytes(folder + "/mesh.ply");
  expect_refused(folder + "/run.tsc", "changed since");
  EXPECT_TRUE(testing::read_file_bytes(folder + "/mesh.ply") == mesh) << "the original mesh is untouched";
}

TEST(CliCheckpoint, OtherMethodsAreRefused) {
  const std::string folder = testing::temporary_directory("checkpoint_front");
  for (const char* method : {"front", "bezier"}) {
    const testing::CommandResult run =
        testing::run_cli(std::string("mesh sphere --method ") + method + " -o " + folder +
                         "/mesh.ply --checkpoint " + folder + "/run.tsc");
    EXPECT_EQ(run.exit_code, 2) << run.output;
    EXPECT_NE(run.output.find("checkpoints are supported for --method atlas"), std::string::npos)
        << run.output;
    EXPECT_FALSE(fs::exists(folder + "/mesh.ply"));
    EXPECT_FALSE(fs::exists(folder + "/run.tsc"));
  }
}

}  // namespace
}  // namespace tessera
