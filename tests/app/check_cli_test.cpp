// SPDX-License-Identifier: MIT
// `tessera check FILE --problem P` holds a mesh to geometric validity: a planted flipped
// triangle, doubled patch or vertex outside the domain makes it exit 1 and name the defect
// with its coordinates.
#include <gtest/gtest.h>

#include <cmath>
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

}  // namespace
}  // namespace tessera
