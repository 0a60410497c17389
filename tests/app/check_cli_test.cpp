// SPDX-License-Identifier: MIT
// `tessera check FILE --problem P` holds a mesh to geometric validity: a planted flipped
// triangle, doubled patch or vertex outside the domain makes it exit 1 and name the defect
// with its coordinates. Without --problem it takes the problem the file records.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "geometry/mesh_examples.h"
#include "support/test_support.h"
#include "tessera/core/describe.h"
#include "tessera/io/mesh_io.h"

namespace tessera {
namespace {

using testing::CommandResult;
using testing::run_cli;

constexpr int kSuccess = 0;
constexpr int kComputationFailed = 1;
constexpr int kUsageError = 2;

std::string work_path(const std::string& file_name) {
  static const std::string directory = testing::temporary_directory("check_cli");
  return directory + "/" + file_name;
}

bool contains(const std::string& text, const std::string& fragment) {
  return text.find(fragment) != std::string::npos;
}

TEST(CliCheckGeometry, AcceptsAGoodMeshOfTheSphere) {
  const std::string path = work_path("good.ply");
  write_mesh(path, examples::icosphere(3));
  const CommandResult result = run_cli("check '" + path + "' --problem sphere --json");
  ASSERT_EQ(result.exit_code, kSuccess) << result.output;
  const auto report = nlohmann::json::parse(result.output);
  EXPECT_TRUE(report.at("valid").get<bool>());
  EXPECT_TRUE(report.at("geometry").at("checked").get<bool>());
  EXPECT_EQ(report.at("geometry").at("flipped_triangles").at("count").get<int>(), 0);
  EXPECT_EQ(report.at("geometry").at("overlapping_triangles").at("count").get<int>(), 0);
  EXPECT_EQ(report.at("geometry").at("vertices_outside_domain").at("count").get<int>(), 0);
}

TEST(CliCheckGeometry, FailsOnAFlippedTriangleAndNamesItWithCoordinates) {
  TriangleMesh mesh = examples::icosphere(3);
  const int t = 100;
  const Triangle tri = mesh.triangle(t);
  mesh.mutable_point(tri[0]) =
      (mesh.point(tri[1]) + mesh.point(tri[2]) - mesh.point(tri[0])).normalized();
  const std::string path = work_path("broken.ply");
  write_mesh(path, mesh);

  const CommandResult result = run_cli("check '" + path + "' --problem sphere");
  EXPECT_EQ(result.exit_code, kComputationFailed) << result.output;
  EXPECT_TRUE(contains(result.output, "flipped triangle")) << result.output;
  const Eigen::VectorXd centroid =
      (mesh.point(tri[0]) + mesh.point(tri[1]) + mesh.point(tri[2])) / 3.0;
  EXPECT_TRUE(contains(result.output, "triangle " + std::to_string(t) + " (vertices ") &&
              contains(result.output, "near " + describe_point(centroid)))
      << result.output;
  EXPECT_TRUE(contains(result.output, "check failed")) << result.output;
}

TEST(CliCheckGeometry, JsonListsTheDefectsOfADoubledMesh) {
  // The sphere meshed twice, the copy turned by 0.01 rad: every part of M is covered twice.
  const TriangleMesh sphere = examples::icosphere(2);
  TriangleMesh turned = sphere;
  for (int v = 0; v < turned.vertex_count(); ++v) {
    const Eigen::Vector3d x = sphere.point(v);
    turned.mutable_point(v) = Eigen::Vector3d(std::cos(0.01) * x(0) - std::sin(0.01) * x(1),
                                              std::sin(0.01) * x(0) + std::cos(0.01) * x(1), x(2));
  }
  const std::string path = work_path("doubled.ply");
  write_mesh(path, examples::disjoint_union(sphere, turned));
  const CommandResult result = run_cli("check '" + path + "' --problem sphere --json");
  EXPECT_EQ(result.exit_code, kComputationFailed) << result.output;
  // stdout holds the JSON document (its top-level brace closes the first unindented line);
  // stderr, interleaved after it, names the defects.
  const auto report = nlohmann::json::parse(result.output.substr(0, result.output.find("\n}") + 2));
  EXPECT_FALSE(report.at("valid").get<bool>());
  const auto& overlaps = report.at("geometry").at("overlapping_triangles");
  EXPECT_GE(overlaps.at("count").get<int>(), sphere.triangle_count());
  EXPECT_EQ(overlaps.at("pairs").size(), 100u) << "lists are truncated in JSON, counts are not";
  EXPECT_TRUE(contains(result.output, "both cover M near (")) << result.output;
}

// Issue 34: `tessera check mesh.ply` demanded --problem where the file's comment names it.
TEST(CliCheckRecordedProblem, TakesTheProblemFromTheCommentOfEveryFormat) {
  for (const std::string extension : {".ply", ".vtk", ".vtu"}) {
    SCOPED_TRACE(extension);
    const std::string path = work_path("recorded" + extension);
    ASSERT_EQ(run_cli("mesh torus:R=2,r=0.5 -t 0.02 -q -o '" + path + "'").exit_code, kSuccess);
    const CommandResult check = run_cli("check '" + path + "'");
    EXPECT_EQ(check.exit_code, kSuccess) << check.output;
    EXPECT_TRUE(contains(check.output, "problem: torus:R=2,r=0.5 (from the file's comment)"))
        << check.output;
    EXPECT_TRUE(contains(check.output, "area")) << check.output;  // the report
    // `improve` records it too (in .vtu as an XML comment, which may not hold "--").
    const std::string improved = work_path("improved" + extension);
    ASSERT_EQ(
        run_cli("improve '" + path + "' --problem torus:R=2,r=0.5 -o '" + improved + "'").exit_code,
        kSuccess);
    const CommandResult check_improved = run_cli("check '" + improved + "'");
    EXPECT_EQ(check_improved.exit_code, kSuccess) << check_improved.output;
    EXPECT_TRUE(contains(check_improved.output, "problem: torus:R=2,r=0.5 (from the file's"))
        << check_improved.output;
  }
  // --json: stdout is the JSON report alone, the note goes to stderr.
  const std::string json = work_path("recorded.json");
  const CommandResult check =
      testing::run_shell("{ " + std::string(TESSERA_CLI) + " check '" + work_path("recorded.vtk") +
                         "' --json > '" + json + "'; }");
  EXPECT_EQ(check.exit_code, kSuccess) << check.output;
  EXPECT_TRUE(contains(check.output, "problem: torus:R=2,r=0.5 (from the file's comment)"));
  std::ifstream in(json);
  EXPECT_NO_THROW(nlohmann::json::parse(in));
}

TEST(CliCheckRecordedProblem, AMeshClippedToABoxIsCheckedInIt) {
  const std::string path = work_path("cap.vtu");
  ASSERT_EQ(run_cli("mesh sphere --box -1,1,-1,1,-0.8,1 -q -o '" + path + "'").exit_code, kSuccess);
  const CommandResult check = run_cli("check '" + path + "'");
  EXPECT_EQ(check.exit_code, kSuccess) << check.output;  // not "Euler characteristic 1, but 2"
  EXPECT_TRUE(
      contains(check.output, "problem: sphere, box -1,1,-1,1,-0.8,1 (from the file's comment)"))
      << check.output;
}

TEST(CliCheckRecordedProblem, RefusesAProblemFileThatHasChangedOrIsGone) {
  const std::string problem = work_path("cut.tsr");
  std::filesystem::copy_file(testing::source_path("examples/problems/sphere_cut.tsr"), problem,
                             std::filesystem::copy_options::overwrite_existing);
  const std::string path = work_path("cut.ply");
  ASSERT_EQ(run_cli("mesh '" + problem + "' -q -o '" + path + "'").exit_code, kSuccess);
  EXPECT_EQ(run_cli("check '" + path + "'").exit_code, kSuccess);
  std::ofstream(problem, std::ios::app) << "# edited after the mesh was written\n";
  CommandResult check = run_cli("check '" + path + "'");
  EXPECT_EQ(check.exit_code, kUsageError) << check.output;
  EXPECT_TRUE(contains(check.output, "has changed since the mesh was written")) << check.output;
  EXPECT_TRUE(contains(check.output, "give the problem with --problem")) << check.output;
  // Given explicitly, the file as it is now is taken.
  EXPECT_EQ(run_cli("check '" + path + "' --problem '" + problem + "'").exit_code, kSuccess);
  std::filesystem::remove(problem);
  check = run_cli("check '" + path + "'");
  EXPECT_EQ(check.exit_code, kUsageError) << check.output;
  EXPECT_TRUE(contains(check.output, "'" + problem + "' no longer exists")) << check.output;
}

TEST(CliCheckRecordedProblem, AFileWithoutARecordNeedsTheProblem) {
  const std::string path = work_path("plain.obj");
  ASSERT_EQ(run_cli("mesh sphere -q -o '" + path + "'").exit_code, kSuccess);
  const CommandResult check = run_cli("check '" + path + "'");
  EXPECT_EQ(check.exit_code, kUsageError) << check.output;
  EXPECT_TRUE(contains(check.output, "give the problem with --problem: the file records none"))
      << check.output;
}

}  // namespace
}  // namespace tessera
