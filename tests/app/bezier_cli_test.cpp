// SPDX-License-Identifier: MIT
// `tessera mesh --method bezier` as a user meets it: the mesh, the patch file and --refine.
#include <gtest/gtest.h>

#include <string>

#include "support/test_support.h"
#include "tessera/geometry/mesh_validation.h"
#include "tessera/io/bezier_patches.h"
#include "tessera/io/mesh_io.h"

namespace tessera {
namespace {

using testing::run_cli;

TEST(CliBezier, WritesTheMeshThePatchesAndTheRefinedSurface) {
  const std::string dir = testing::temporary_directory("cli_bezier");
  const auto flat =
      run_cli("mesh torus --method bezier --patches " + dir + "/t.json -o " + dir + "/t.ply");
  ASSERT_EQ(flat.exit_code, 0) << flat.output;
  EXPECT_NE(flat.output.find("bezier"), std::string::npos) << flat.output;
  const TriangleMesh mesh = read_mesh(dir + "/t.ply");
  const BezierSurfaceFile patches = read_bezier_patches(dir + "/t.json");
  EXPECT_EQ(patches.mesh.triangle_count(), mesh.triangle_count());
  EXPECT_EQ(patches.patches.size(), static_cast<std::size_t>(mesh.triangle_count()));

  const auto refined = run_cli("mesh torus --method bezier --refine 3 -o " + dir + "/t3.ply");
  ASSERT_EQ(refined.exit_code, 0) << refined.output;
  const TriangleMesh fine = read_mesh(dir + "/t3.ply");
  EXPECT_EQ(fine.triangle_count(), 9 * mesh.triangle_count());
  const MeshValidation validation = validate(fine);
  EXPECT_TRUE(validation.is_valid()) << validation.report();
  EXPECT_EQ(validation.euler_characteristic, 0);
}

TEST(CliBezier, ToleranceGivesMoreTriangles) {
  const std::string dir = testing::temporary_directory("cli_bezier_tolerance");
  ASSERT_EQ(
      run_cli("mesh sphere --method bezier --tolerance 0.02 -q -o " + dir + "/a.ply").exit_code, 0);
  ASSERT_EQ(
      run_cli("mesh sphere --method bezier --tolerance 0.01 -q -o " + dir + "/b.ply").exit_code, 0);
  EXPECT_GT(read_mesh(dir + "/b.ply").triangle_count(),
            1.5 * read_mesh(dir + "/a.ply").triangle_count());
}

TEST(CliBezier, RefineNeedsTheBezierMethod) {
  const std::string dir = testing::temporary_directory("cli_bezier_usage");
  const auto result = run_cli("mesh sphere --method front --refine 2 -o " + dir + "/s.ply");
  EXPECT_EQ(result.exit_code, 2) << result.output;
  EXPECT_NE(result.output.find("--method bezier"), std::string::npos) << result.output;
}

}  // namespace
}  // namespace tessera
