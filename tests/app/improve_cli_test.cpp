// SPDX-License-Identifier: MIT
// `tessera improve` as a user meets it.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>
#include <string>

#include "support/test_support.h"
#include "tessera/geometry/mesh_validation.h"
#include "tessera/io/mesh_io.h"

namespace tessera {
namespace {

bool contains(const std::string& text, const std::string& fragment) {
  return text.find(fragment) != std::string::npos;
}

TEST(CliImprove, EveryCriterionWritesAValidMeshAndASummary) {
  const std::string folder = testing::temporary_directory("improve");
  const std::string input = folder + "/sphere_cut.ply";
  auto result = testing::run_cli("mesh sphere_cut --step 0.3 -q -o " + input);
  ASSERT_EQ(result.exit_code, 0) << result.output;
  for (const std::string criterion : {"angle", "normal", "distance"}) {
    const std::string output = folder + "/" + criterion + ".ply";
    const std::string summary = folder + "/" + criterion + ".json";
    result = testing::run_cli("improve " + input + " --problem sphere_cut --criterion " +
                              criterion + " -o " + output + " --summary " + summary);
    ASSERT_EQ(result.exit_code, 0) << result.output;
    EXPECT_TRUE(contains(result.output, "before")) << result.output;
    EXPECT_TRUE(contains(result.output, "after")) << result.output;
    const MeshValidation validation = validate(read_mesh(output));
    EXPECT_TRUE(validation.is_valid()) << validation.report();
    EXPECT_EQ(validation.euler_characteristic, 1);  // a disk, as before
    const nlohmann::json json = nlohmann::json::parse(std::ifstream(summary));
    EXPECT_EQ(json["criterion"], criterion);
    EXPECT_TRUE(json["after"]["is_valid"].get<bool>());
    EXPECT_EQ(json["before"]["boundary_edge_count"], json["after"]["boundary_edge_count"]);
  }
}

// Issue 34: `mesh --improve` ran its swaps and smoothing without a trace in the report. The
// report now says what they did, and the summary holds the same numbers.
TEST(CliImprove, MeshImproveSaysWhatItDidInTheReportAndTheSummary) {
  const std::string folder = testing::temporary_directory("mesh_improve");
  const std::string summary = folder + "/cap.json";
  const auto result = testing::run_cli("mesh sphere_cut --step 0.3 --improve -o " + folder +
                                       "/cap.ply --summary " + summary);
  ASSERT_EQ(result.exit_code, 0) << result.output;
  EXPECT_TRUE(contains(result.output, "improve        edge swaps by the angle criterion: "))
      << result.output;
  EXPECT_TRUE(contains(result.output, "smoothing: ")) << result.output;
  EXPECT_TRUE(contains(result.output, "min angle ")) << result.output;
  const nlohmann::json json = nlohmann::json::parse(std::ifstream(summary));
  ASSERT_TRUE(json.contains("improvement")) << json.dump(2);
  const nlohmann::json& improvement = json["improvement"];
  EXPECT_EQ(improvement["criterion"], "angle");
  EXPECT_EQ(improvement["smoothing_passes"], 3);
  EXPECT_GT(improvement["swaps"].get<int>() + improvement["smoothing_moves"].get<int>(), 0);
  // The swaps never lower the smallest angle, and the smoothing refuses moves that would.
  EXPECT_GE(improvement["min_angle_degrees"]["after"].get<double>(),
            improvement["min_angle_degrees"]["before"].get<double>());
  EXPECT_TRUE(json["valid"].get<bool>());
  // Without --improve neither says anything about it.
  const auto plain = testing::run_cli("mesh sphere_cut --step 0.3 -o " + folder +
                                      "/plain.ply --summary " + folder + "/plain.json");
  ASSERT_EQ(plain.exit_code, 0) << plain.output;
  EXPECT_FALSE(contains(plain.output, "improve        ")) << plain.output;
  EXPECT_FALSE(
      nlohmann::json::parse(std::ifstream(folder + "/plain.json")).contains("improvement"));
}

TEST(CliImprove, SmoothingKeepsTheMeshValidAndOnM) {
  const std::string folder = testing::temporary_directory("improve_smooth");
  const std::string input = folder + "/sphere_cut.ply";
  auto result = testing::run_cli("mesh sphere_cut --step 0.3 -q -o " + input);
  ASSERT_EQ(result.exit_code, 0) << result.output;
  const std::string output = folder + "/smoothed.ply";
  result = testing::run_cli("improve " + input + " --problem sphere_cut --smooth 3 -o " + output);
  ASSERT_EQ(result.exit_code, 0) << result.output;
  EXPECT_TRUE(contains(result.output, "smoothing:")) << result.output;
  // `check` passes only if the mesh is valid, a disk, and its vertices are on M (1e-6).
  result = testing::run_cli("check " + output + " --problem sphere_cut");
  EXPECT_EQ(result.exit_code, 0) << result.output;
}

// The command line recorded in the file holds "--criterion", which an XML comment may not: every
// format the command offers must still be written (issue 34).
TEST(CliImprove, EveryOutputFormatIsWrittenWhateverTheRecordedCommandLine) {
  const std::string dir = testing::temporary_directory("cli_improve_formats");
  const std::string input = dir + "/in.ply";
  ASSERT_EQ(testing::run_cli("mesh sphere_cut --step 0.3 -q -o " + input).exit_code, 0);
  for (const std::string extension : {".vtu", ".vtk", ".ply", ".obj"}) {
    const std::string output = dir + "/out" + extension;
    const auto result = testing::run_cli("improve " + input +
                                         " --problem sphere_cut --criterion angle -o " + output);
    EXPECT_EQ(result.exit_code, 0) << extension << "\n" << result.output;
    EXPECT_TRUE(std::filesystem::exists(output)) << output;
  }
  std::ifstream vtu(dir + "/out.vtu");
  const std::string text((std::istreambuf_iterator<char>(vtu)), std::istreambuf_iterator<char>());
  EXPECT_NE(text.find("- -criterion angle"), std::string::npos);  // "--" in a comment, kept legible
}

TEST(CliImprove, BadInputIsAUsageError) {
  const std::string folder = testing::temporary_directory("improve_bad");
  auto result =
      testing::run_cli("improve /nonexistent/mesh.ply --problem sphere -o " + folder + "/out.ply");
  EXPECT_EQ(result.exit_code, 2) << result.output;
  result = testing::run_cli("improve x.ply --problem sphere --criterion bogus -o out.ply");
  EXPECT_EQ(result.exit_code, 2) << result.output;
}

}  // namespace
}  // namespace tessera
