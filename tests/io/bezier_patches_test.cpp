// SPDX-License-Identifier: MIT
// The patch file of method `bezier` reads back exactly what was written, and malformed files
// are refused with a message naming the field.
#include "tessera/io/bezier_patches.h"

#include <gtest/gtest.h>

#include <fstream>
#include <functional>
#include <nlohmann/json.hpp>

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

// Issue 34: a missing or mistyped field gave nlohmann's own message, e.g. "[json.exception.
// type_error.302] type must be array, but is null". Every field is checked first, and the
// message names the file and the field.
TEST(BezierPatchesFile, MalformedFilesNameTheFileAndTheFieldNotNlohmann) {
  const std::string dir = testing::temporary_directory("bezier_patches_malformed");
  const std::string good_path = dir + "/good.json";
  write_bezier_patches(good_path, one_patch_in_r4());
  const nlohmann::json good = nlohmann::json::parse(std::ifstream(good_path));
  struct Case {
    std::string name;
    std::function<void(nlohmann::json&)> change;
    std::string expected;
  };
  const std::vector<Case> cases = {
      {"no_names", [](auto& j) { j.erase("coordinate_names"); },
       "the field 'coordinate_names' is missing"},
      {"names_numbers",
       [](auto& j) {
         j["coordinate_names"] = {1, 2, 3, 4};
       },
       "'coordinate_names' must be an array of 4 names"},
      {"format_number", [](auto& j) { j["format"] = 5; }, "the field 'format' is 5"},
      {"version_text", [](auto& j) { j["version"] = "one"; }, "version \"one\" is not supported"},
      {"no_dimension", [](auto& j) { j.erase("dimension"); }, "'dimension' is missing"},
      {"no_vertices", [](auto& j) { j.erase("vertices"); }, "'vertices' is missing"},
      {"triangle_of_four",
       [](auto& j) {
         j["triangles"][0] = {0, 1, 2, 0};
       },
       "triangles[0] must be an array of 3 vertex indices"},
      {"triangle_of_reals",
       [](auto& j) {
         j["triangles"][0] = {0, 1, 1.5};
       },
       "triangles[0] must be an array of 3 vertex indices"},
      {"vertex_text", [](auto& j) { j["vertices"][1][2] = "z"; }, "vertices[1][2] is not a number"},
      {"no_control_points", [](auto& j) { j.erase("control_points"); },
       "'control_points' is missing"},
      {"an_array", [](auto& j) { j = nlohmann::json::array(); }, "expected a JSON object"},
  };
  for (const auto& bad : cases) {
    SCOPED_TRACE(bad.name);
    nlohmann::json changed = good;
    bad.change(changed);
    const std::string path = dir + "/" + bad.name + ".json";
    std::ofstream(path) << changed.dump();
    try {
      read_bezier_patches(path);
      ADD_FAILURE() << "no exception";
    } catch (const InvalidArgument& error) {
      const std::string message = error.what();
      EXPECT_NE(message.find("Bezier patches '" + path + "'"), std::string::npos) << message;
      EXPECT_NE(message.find(bad.expected), std::string::npos) << message;
      EXPECT_EQ(message.find("json.exception"), std::string::npos) << message;
    }
  }
  for (const std::string text : {"{\"format\": ", "[1e999]"}) {
    const std::string path = dir + "/syntax.json";
    std::ofstream(path) << text;
    try {
      read_bezier_patches(path);
      ADD_FAILURE() << "no exception for " << text;
    } catch (const InvalidArgument& error) {
      EXPECT_EQ(std::string(error.what()).find("json.exception"), std::string::npos)
          << error.what();
    }
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
