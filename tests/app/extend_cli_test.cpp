// SPDX-License-Identifier: MIT
// `tessera extend` as a process (docs/checkpoints.md): a cap of the unit sphere meshed in the
// box z ≥ 0.2 with --checkpoint, extended to z ≥ −0.5 and to a finer tolerance. The extended
// run's checkpoint holds the extended command line: resuming it gives the extended mesh again.
// A box that does not contain the run's, a tolerance that is not finer, or neither: refused
// with exit 2, nothing written.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <numbers>
#include <string>

#include "support/test_support.h"

namespace tessera {
namespace {

namespace fs = std::filesystem;

nlohmann::json read_json(const std::string& path) {
  return nlohmann::json::parse(testing::read_file_bytes(path));
}

// The small cap's run, made once per test (each test has its own folder).
std::string mesh_small_cap(const std::string& name) {
  const std::string folder = testing::temporary_directory(name);
  const testing::CommandResult run = testing::run_cli(
      "mesh sphere --start 0,0,1 --box -2,2,-2,2,0.2,2 -q -o " + folder + "/small.ply --summary " +
      folder + "/small.json --checkpoint " + folder + "/run.tsc");
  EXPECT_EQ(run.exit_code, 0) << run.output;
  return folder;
}

TEST(CliExtend, ALargerBoxCoversTheLargerCap) {
  const std::string folder = mesh_small_cap("extend_box");
  const testing::CommandResult extended =
      testing::run_cli("extend " + folder + "/run.tsc --box -2,2,-2,2,-0.5,2 -q -o " + folder +
                       "/large.ply --summary " + folder + "/large.json");
  ASSERT_EQ(extended.exit_code, 0) << extended.output;
  const nlohmann::json small = read_json(folder + "/small.json");
  const nlohmann::json large = read_json(folder + "/large.json");
  EXPECT_TRUE(large["valid"].get<bool>()) << large["defects"].dump(1);
  EXPECT_EQ(large["topology"]["euler_characteristic"], 1);
  EXPECT_TRUE(large["run"]["completed"].get<bool>()) << large["run"]["message"];
  EXPECT_EQ(large["run"]["resumed_from"]["charts"], small["run"]["atlas"]["charts"]);
  EXPECT_GT(large["run"]["atlas"]["charts"].get<int>(), small["run"]["atlas"]["charts"].get<int>());
  EXPECT_NEAR(large["shape"]["area"].get<double>(), 2 * std::numbers::pi * 1.5, 0.1);
  // The checkpoint now holds the extended run: resumed, it writes the extended mesh again.
  const testing::CommandResult resumed =
      testing::run_cli("resume " + folder + "/run.tsc -q -o " + folder + "/again.ply");
  ASSERT_EQ(resumed.exit_code, 0) << resumed.output;
  EXPECT_TRUE(testing::read_file_bytes(folder + "/again.ply") == testing::read_file_bytes(folder + "/large.ply"));
}

TEST(CliExtend, AFinerToleranceRefinesTheSameCharts) {
  const std::string folder = mesh_small_cap("extend_tolerance");
  const testing::CommandResult extended = testing::run_cli(
      "extend " + folder + "/run.tsc --tolerance 0.0015 --checkpoint " + folder +
      "/fine.tsc -q -o " + folder + "/fine.ply --summary " + folder + "/fine.json");
  ASSERT_EQ(extended.exit_code, 0) << extended.output;
  const nlohmann::json small = read_json(folder + "/small.json");
  const nlohmann::json fine = read_json(folder + "/fine.json");
  EXPECT_TRUE(fine["valid"].get<bool>());
  EXPECT_EQ(fine["run"]["atlas"]["charts"], small["run"]["atlas"]["charts"]);
  EXPECT_EQ(fine["run"]["tolerance"].get<double>(), 0.0015);
  EXPECT_LE(fine["run"]["max_sampled_distance"].get<double>(), 0.0015);
  EXPECT_GT(small["run"]["max_sampled_distance"].get<double>(), 0.0015);
  EXPECT_GT(fine["counts"]["vertices"].get<int>(), small["counts"]["vertices"].get<int>());
  // --checkpoint kept the original; the new one resumes to the finer mesh.
  EXPECT_TRUE(fs::exists(folder + "/run.tsc"));
  const testing::CommandResult resumed =
      testing::run_cli("resume " + folder + "/fine.tsc -q -o " + folder + "/again.ply");
  ASSERT_EQ(resumed.exit_code, 0) << resumed.output;
  EXPECT_TRUE(testing::read_file_bytes(folder + "/again.ply") == testing::read_file_bytes(folder + "/fine.ply"));
}

// A refused extension: exit 2, the message, no mesh at -o and the checkpoint unchanged.
void expect_refused(const std::string& folder, const std::string& options,
                    const std::string& message) {
  const std::string checkpoint = testing::read_file_bytes(folder + "/run.tsc");
  const testing::CommandResult run =
      testing::run_cli("extend " + folder + "/run.tsc " + options + " -o " + folder + "/no.ply");
  EXPECT_EQ(run.exit_code, 2) << run.output;
  EXPECT_NE(run.output.find(message), std::string::npos) << run.output;
  EXPECT_FALSE(fs::exists(folder + "/no.ply")) << options;
  EXPECT_TRUE(testing::read_file_bytes(folder + "/run.tsc") == checkpoint) << options;
}

TEST(CliExtend, BadExtensionsAreRefused) {
  const std::string folder = mesh_small_cap("extend_refused");
  expect_refused(folder, "--box -2,2,-2,2,0.4,2", "does not contain the checkpoint's");
  expect_refused(folder, "--box -1,1,-2,2,0.2,2", "does not contain the checkpoint's");
  expect_refused(folder, "--tolerance 0.01", "is not finer than the run's");
  expect_refused(folder, "", "give a larger --box, a finer --tolerance");
}

}  // namespace
}  // namespace tessera
