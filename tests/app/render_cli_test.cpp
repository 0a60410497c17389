// SPDX-License-Identifier: MIT
// `tessera render` and `tessera mesh --picture` as a user meets them: pictures of a mesh file, of
// a planar DDT triangulation from above, of a run with its fold curves, and bad options refused
// with a message naming them (exit 2) before anything is drawn or computed.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "support/test_support.h"

namespace tessera {
namespace {

using testing::run_cli;

constexpr int kUsageError = 2;

bool is_png(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  char signature[8] = {};
  in.read(signature, 8);
  return in && std::string(signature + 1, 3) == "PNG";
}

bool contains(const std::string& text, const std::string& fragment) {
  return text.find(fragment) != std::string::npos;
}

TEST(RenderCli, DrawsAMeshFileADdtTriangulationAndARunWithItsFolds) {
  const std::string dir = testing::temporary_directory("render_cli");
  ASSERT_EQ(run_cli("mesh torus --tolerance 0.01 -q -o " + dir + "/torus.vtu").exit_code, 0);
  for (const std::string colour : {"height", "min-angle", "curvature", "x", "none"}) {
    const auto result = run_cli("render " + dir + "/torus.vtu -o " + dir + "/torus.png --colour " +
                                colour + " --azimuth 20 --elevation 50 --perspective");
    ASSERT_EQ(result.exit_code, 0) << colour << "\n" << result.output;
    EXPECT_TRUE(is_png(dir + "/torus.png"));
  }
  const auto distance = run_cli("render " + dir + "/torus.vtu -o " + dir + "/torus.svg --problem " +
                                "torus --colour distance --size 400x300 --edges off");
  ASSERT_EQ(distance.exit_code, 0) << distance.output;
  EXPECT_TRUE(std::filesystem::file_size(dir + "/torus.svg") > 1000);

  // A file keeps its problem's coordinate names (x, lambda, mu): a column is a colour by name.
  ASSERT_EQ(run_cli("mesh whitney_pleat --tolerance 0.01 -q -o " + dir + "/named.vtu").exit_code,
            0);
  const auto named =
      run_cli("render " + dir + "/named.vtu --colour lambda -o " + dir + "/named.svg");
  ASSERT_EQ(named.exit_code, 0) << named.output;
  const auto unnamed = run_cli("render " + dir + "/named.vtu --colour y -o " + dir + "/named.svg");
  EXPECT_EQ(unnamed.exit_code, 2);
  EXPECT_TRUE(contains(unnamed.output,
                       "known: height, none, min-angle, area, curvature, "
                       "distance, x, lambda, mu"))
      << unnamed.output;

  ASSERT_EQ(run_cli("ddt " + testing::source_path("examples/data/franke33.csv") +
                    " --function F2 -o " + dir + "/ddt.ply").exit_code, 0);
  const auto ddt = run_cli("render " + dir + "/ddt.ply --top --colour z -o " + dir + "/ddt.png");
  ASSERT_EQ(ddt.exit_code, 0) << ddt.output;
  EXPECT_TRUE(is_png(dir + "/ddt.png"));

  const auto run = run_cli("mesh whitney_pleat --tolerance 0.01 --folds lambda,mu -q -o " + dir +
                           "/pleat.ply --folds-output " + dir + "/pleat.json --picture " + dir +
                           "/pleat.png");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  EXPECT_TRUE(is_png(dir + "/pleat.png"));
  const auto again = run_cli("render " + dir + "/pleat.ply --curves " + dir + "/pleat.json -o " +
                             dir + "/pleat2.png");
  ASSERT_EQ(again.exit_code, 0) << again.output;
}

TEST(RenderCli, BadOptionsAreRefusedBeforeDrawing) {
  const std::string dir = testing::temporary_directory("render_cli_bad");
  ASSERT_EQ(run_cli("mesh sphere --tolerance 0.02 -q -o " + dir + "/s.ply").exit_code, 0);
  struct Case {
    std::string arguments;
    std::string message;
  };
  const std::string mesh = dir + "/s.ply -o " + dir + "/s.png";
  // A mesh file with vertices and no triangles, and fold curves with a coordinate "nan".
  std::ofstream(dir + "/empty.ply") << "ply\nformat ascii 1.0\nelement vertex 3\n"
                                       "property double x\nproperty double y\nproperty double z\n"
                                       "end_header\n0 0 0\n1 0 0\n0 1 0\n";
  std::ofstream(dir + "/nan.csv") << "curve,point,x,y,z,cusp\n0,0,0,0,0,0\n0,1,nan,1,0,0\n";
  for (const Case& bad : {
           Case{"render " + mesh + " --colour curly", "unknown quantity"},
           Case{"render " + mesh + " --colour distance", "--problem"},
           Case{"render " + dir + "/s.ply -o " + dir + "/s.jpg", ".png or .svg"},
           Case{"render " + mesh + " --size 800", "WIDTHxHEIGHT"},
           Case{"render " + mesh + " --view x,y", "needs --problem"},
           Case{"render " + mesh + " --curves " + dir + "/s.ply", ".json or .csv"},
           Case{"render " + dir + "/missing.ply -o " + dir + "/s.png", "missing.ply"},
           Case{"render " + dir + "/empty.ply -o " + dir + "/s.png", "no triangles"},
           Case{"render " + mesh + " --curves " + dir + "/nan.csv", "line 3: not a finite number"},
           Case{"render " + mesh + " --aspect squashed", "--aspect"},
           Case{"mesh sphere -o " + dir + "/t.ply --picture " + dir + "/t.gif", ".png or .svg"},
       }) {
    const auto result = run_cli(bad.arguments);
    EXPECT_EQ(result.exit_code, kUsageError) << bad.arguments << "\n" << result.output;
    EXPECT_TRUE(contains(result.output, bad.message)) << bad.arguments << "\n" << result.output;
  }
  EXPECT_FALSE(std::filesystem::exists(dir + "/s.png"));
  EXPECT_FALSE(std::filesystem::exists(dir + "/t.ply"));
}

}  // namespace
}  // namespace tessera
