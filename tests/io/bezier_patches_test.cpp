// SPDX-License-Identifier: MIT
// The patch file of method `bezier` reads back exactly what was written, and malformed files
// are refused with a message naming the field.
#include "tessera/io/bezier_patches.h"

#include <gtest/gtest.h>

#include <fstream>

#include "support/test_support.h"
#include "tessera/core/error.h"

namespace tessera {
namespace {

BezierSurfaceFile one_patch_in_r4() {
  BezierSurfaceFile surface;
  Eigen::MatrixXd points(4, 3);
  points << 0, 1, 0, 0, 0, 1, 0.5, 0.25, -1, 1e-17, 3.25, 1.0 / 3.0;
  surface.mesh = TriangleMesh(points, {{0, 1, 2}});
  std::array<Eigen::MatrixXd, 3> bases;
  for (auto& T : bases) {
    T = Eigen::MatrixXd::Zero(4, 2);
    T(0, 0) = 1;
    T(1, 1) = 1;
  }
  surface.patches.push_back(CubicBezierPatch::interpolate_triangle_on_manifold(points, bases));
  surface.coordinate_names = {"x1", "x2", "Da", "B"};
  return surface;
}

TEST(BezierPatchesFile, RoundTripIsExact) {
  const std::string path = testing::temporary_directory("bezier_patches") + "/p.json";
  const BezierSurfaceFile written = one_patch_in_r4();
  write_bezier_patches(path, written);
  const BezierSurfaceFile read = read_bezier_patches(path);
  EXPECT_EQ(read.coordinate_names, written.coordinate_names);
  EXPECT_EQ(read.mesh.points(), written.mesh.points());
  EXPECT_EQ(read.mesh.triangles(), written.mesh.triangles());
  ASSERT_EQ(read.patches.size(), 1u);
  EXPECT_EQ(read.patches[0].control_points(), written.patches[0].control_points());
}

TEST(BezierPatchesFile, RefusesAFileOfAnotherFormat) {
  const std::string path = testing::temporary_directory("bezier_patches_bad") + "/p.json";
  std::ofstream(path) << R"({"format": "something else", "version": 1})";
  try {
    read_bezier_patches(path);
    FAIL() << "no exception";
  } catch (const InvalidArgument& error) {
    EXPECT_NE(std::string(error.what()).find("format"), std::string::npos) << error.what();
  }
}

TEST(BezierPatchesFile, RefusesAPatchCountThatDoesNotMatchTheTriangles) {
  BezierSurfaceFile surface = one_patch_in_r4();
  surface.patches.push_back(surface.patches[0]);
  EXPECT_THROW(write_bezier_patches(
                   testing::temporary_directory("bezier_patches_count") + "/p.json", surface),
               InvalidArgument);
}

}  // namespace
}  // namespace tessera
