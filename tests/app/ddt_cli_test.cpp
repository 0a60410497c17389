// SPDX-License-Identifier: MIT
// `tessera ddt` as a user meets it.
#include <gtest/gtest.h>

#include <string>

#include "support/test_support.h"
#include "tessera/geometry/mesh_validation.h"
#include "tessera/io/mesh_io.h"

namespace tessera {
namespace {

bool contains(const std::string& text, const std::string& fragment) {
  return text.find(fragment) != std::string::npos;
}

TEST(CliDdt, PrintsTheDelaunayErrorOfTheReportFor33Points) {
  const std::string data = testing::source_path("examples/data/franke33.csv");
  // Malcolm's Table 1, 33 points, DELAUNAY, F2: 0.01604 (F2 does not depend on which diagonal
  // of the one cocircular quadrilateral is used).
  const auto result = testing::run_cli("ddt " + data + " --function F2 --criterion delaunay");
  EXPECT_EQ(result.exit_code, 0) << result.output;
  EXPECT_TRUE(contains(result.output, "mean 0.01604")) << result.output;
}

TEST(CliDdt, WritesAValidTriangulationWithTheValues) {
  const std::string data = testing::source_path("examples/data/franke100.csv");
  const std::string out = testing::temporary_directory("ddt") + "/abn.ply";
  const auto result = testing::run_cli("ddt " + data + " --function F1 --criterion abn --norm l2 -o " + out);
  ASSERT_EQ(result.exit_code, 0) << result.output;
  const TriangleMesh mesh = read_mesh(out);
  EXPECT_EQ(mesh.vertex_count(), 100);
  const MeshValidation validation = validate(mesh);
  EXPECT_TRUE(validation.is_valid()) << validation.report();
  EXPECT_EQ(validation.euler_characteristic, 1);  // a triangulated disk: the convex hull
}

TEST(CliDdt, AllCriteriaPrintsEveryRow) {
  const std::string data = testing::source_path("examples/data/franke33.csv");
  const auto result = testing::run_cli("ddt " + data + " --function F7 --all-criteria");
  ASSERT_EQ(result.exit_code, 0) << result.output;
  for (const char* row : {"delaunay", "mwt3d-2", "abn-1", "abn-2", "jnd-1", "jnd-2", "pf-1",
                          "pf-2", "pd-1", "pd-2", "equid-2"}) {
    EXPECT_TRUE(contains(result.output, row)) << row << "\n" << result.output;
  }
}

TEST(CliDdt, BadInputIsAUsageErrorThatSaysWhat) {
  const std::string data = testing::source_path("examples/data/franke33.csv");
  auto result = testing::run_cli("ddt " + data + " --function F3");
  EXPECT_EQ(result.exit_code, 2);
  EXPECT_TRUE(contains(result.output, "F3")) << result.output;
  result = testing::run_cli("ddt " + data);
  EXPECT_EQ(result.exit_code, 2);
  EXPECT_TRUE(contains(result.output, "no value column")) << result.output;
  result = testing::run_cli("ddt /nonexistent/points.csv --function F1");
  EXPECT_EQ(result.exit_code, 2);
  EXPECT_TRUE(contains(result.output, "points.csv")) << result.output;
  result = testing::run_cli("ddt " + data + " --function F1 --criterion bogus");
  EXPECT_EQ(result.exit_code, 2);
  EXPECT_TRUE(contains(result.output, "bogus")) << result.output;
}

}  // namespace
}  // namespace tessera
