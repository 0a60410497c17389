// SPDX-License-Identifier: MIT
// `tessera mesh --components all` and `--start` given more than once: the components in the
// summary and the report, and the refusals of bad input.
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "support/test_support.h"
#include "tessera/geometry/mesh_validation.h"
#include "tessera/io/mesh_io.h"

namespace tessera {
namespace {

using testing::CommandResult;
using testing::run_cli;

constexpr int kSuccess = 0;
constexpr int kUsageError = 2;

std::string work_path(const std::string& file_name) {
  static const std::string directory = testing::temporary_directory("components_cli");
  return directory + "/" + file_name;
}

bool contains(const std::string& text, const std::string& fragment) {
  return text.find(fragment) != std::string::npos;
}

nlohmann::json read_json(const std::string& path) {
  std::ifstream in(path);
  return nlohmann::json::parse(in);
}

TEST(CliComponents, AllFindsTheTorusAndTheSphereAndListsThem) {
  const std::string mesh = work_path("ts.ply");
  const std::string summary = work_path("ts.json");
  const CommandResult result = run_cli(
      "mesh torus_and_sphere --components all --component-seeds "
      "256 -o '" +
      mesh + "' --summary '" + summary + "'");
  ASSERT_EQ(result.exit_code, kSuccess) << result.output;
  EXPECT_TRUE(contains(result.output, "components     2 (256 seeds")) << result.output;
  EXPECT_TRUE(contains(result.output, "χ 0, closed, genus 1")) << result.output;
  EXPECT_TRUE(contains(result.output, "χ 2, closed, genus 0")) << result.output;
  const nlohmann::json json = read_json(summary);
  const nlohmann::json& components = json.at("run").at("components");
  ASSERT_EQ(components.size(), 2u);
  EXPECT_EQ(components[0].at("origin"), "start 1");
  EXPECT_EQ(components[0].at("euler_characteristic"), 0);
  EXPECT_EQ(components[1].at("euler_characteristic"), 2);
  EXPECT_EQ(components[1].at("start").size(), 3u);
  EXPECT_EQ(json.at("run").at("component_search").at("seeds"), 256);
  EXPECT_EQ(json.at("counts").at("components"), 2);
  EXPECT_EQ(json.at("topology").at("euler_characteristic"), 2);
  // The problem's known χ (the torus's) is not claimed for the union of both.
  EXPECT_FALSE(json.at("topology").contains("expected_euler_characteristic"));
  EXPECT_TRUE(json.at("valid").get<bool>());
  const MeshValidation validation = validate(read_mesh(mesh));
  EXPECT_TRUE(validation.is_valid()) << validation.report();
  EXPECT_EQ(validation.component_count, 2);
  EXPECT_EQ(components[0].at("vertices").get<int>() + components[1].at("vertices").get<int>(),
            validation.vertex_count);
}

TEST(CliComponents, SeveralStartsSayWhichComponentEachReached) {
  const std::string summary = work_path("starts.json");
  const CommandResult result = run_cli(
      "mesh two_spheres --method front --start 1,0,0.5 --start -1,0,0.6 --start "
      "1.2,0.4,0 -o '" +
      work_path("starts.ply") + "' --summary '" + summary + "'");
  ASSERT_EQ(result.exit_code, kSuccess) << result.output;
  EXPECT_TRUE(contains(result.output,
                       "start 1 → component 1; start 2 → component 2; start 3 → "
                       "component 1 (already covered)"))
      << result.output;
  const nlohmann::json starts = read_json(summary).at("run").at("starts");
  ASSERT_EQ(starts.size(), 3u);
  EXPECT_EQ(starts[2].at("component"), 1);
  EXPECT_FALSE(starts[2].at("started_component").get<bool>());
}

TEST(CliComponents, AllWithoutABoundedRegionIsAUsageError) {
  const CommandResult result =
      run_cli("mesh sphere --components all -o '" + work_path("no.ply") + "'");
  EXPECT_EQ(result.exit_code, kUsageError) << result.output;
  EXPECT_TRUE(contains(result.output, "--components all searches a bounded region"))
      << result.output;
  EXPECT_TRUE(contains(result.output, "--box")) << result.output;
  EXPECT_FALSE(std::ifstream(work_path("no.ply")).good());
}

TEST(CliComponents, SeedsWithoutTheSearchAreAUsageError) {
  const CommandResult result =
      run_cli("mesh two_spheres --component-seeds 10 -o '" + work_path("no2.ply") + "'");
  EXPECT_EQ(result.exit_code, kUsageError) << result.output;
  EXPECT_TRUE(contains(result.output, "needs --components all")) << result.output;
}

// With a user's box the search covers what lies in it: the box x ≥ 0 holds one sphere.
TEST(CliComponents, AllInAUserBoxCoversWhatLiesInIt) {
  const std::string summary = work_path("box.json");
  const CommandResult result =
      run_cli("mesh two_spheres --box 0,2,-1,1,-1,1 --components all --component-seeds 64 -o '" +
              work_path("box.ply") + "' --summary '" + summary + "'");
  ASSERT_EQ(result.exit_code, kSuccess) << result.output;
  EXPECT_EQ(read_json(summary).at("run").at("components").size(), 1u);
}

}  // namespace
}  // namespace tessera
