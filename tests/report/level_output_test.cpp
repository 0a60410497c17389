// SPDX-License-Identifier: MIT
// `tessera mesh --level` as the library gives it to the command (report/level_output): the file,
// the report and the summary, and the option's errors.
#include "tessera/report/level_output.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "support/test_support.h"
#include "tessera/core/error.h"
#include "tessera/methods/covering_methods.h"
#include "tessera/problems/catalogue.h"
#include "tessera/report/summary_json.h"

namespace tessera {
namespace {

TEST(LevelOutput, TheGreatCircleIsWrittenInTheViewAndReportedInTheSummary) {
  const ProblemSetup setup = make_catalogue_problem("sphere");
  const CoveringResult covering = cover(setup, covering_methods().front(), {});
  ASSERT_TRUE(covering.summary.is_complete()) << covering.summary.message;
  const LevelSet level = parse_level_option("z = 0", *setup.problem);
  const View view = parse_view("x, y, r = x^2 + y^2", *setup.problem);
  const std::string path = testing::temporary_directory("level_output") + "/sphere.level.json";
  const LevelOutput output =
      compute_level_curves(setup, covering.mesh, level, view, path, {"a comment"});

  ASSERT_EQ(output.curves_in_view.size(), 1u);
  const Polyline& circle = output.curves_in_view[0];
  EXPECT_TRUE(circle.is_closed);
  for (Eigen::Index i = 0; i < circle.points.cols(); ++i) {
    EXPECT_NEAR(circle.points(2, i), 1.0, 1e-9);  // r = x² + y² = 1 on the equator
    EXPECT_FALSE(circle.marked[static_cast<std::size_t>(i)]);
  }
  const LevelReport& report = output.report;
  EXPECT_EQ(report.functional, "z");
  EXPECT_EQ(report.value, 0.0);
  EXPECT_EQ(report.point_count, circle.points.cols());
  EXPECT_EQ(report.unrefined_count, 0);
  EXPECT_LE(report.max_residual, 1e-9);

  const nlohmann::json file = nlohmann::json::parse(std::ifstream(path));
  EXPECT_EQ(file["polylines"].size(), 1u);
  EXPECT_EQ(file["columns"][2], "r");

  MeshReport mesh_report;
  mesh_report.problem = "sphere";
  mesh_report.ambient_dimension = 3;
  mesh_report.level = report;
  const nlohmann::json summary = nlohmann::json::parse(to_json(mesh_report));
  EXPECT_EQ(summary["level"]["level"], "z = 0");
  EXPECT_EQ(summary["level"]["name"], "z");
  EXPECT_EQ(summary["level"]["file"], path);
  EXPECT_EQ(summary["level"]["curve_count"], 1);
  EXPECT_EQ(summary["level"]["point_count"], report.point_count);
  EXPECT_EQ(summary["level"]["unrefined_points"], 0);
  EXPECT_EQ(summary["level"]["curves"][0]["closed"], true);
  const std::string text = to_text(mesh_report);
  EXPECT_NE(text.find("level          1 curve(s) where z = 0"), std::string::npos) << text;
}

TEST(LevelOutput, TheDefaultFileIsBesideTheMeshAndBadOptionsNameTheOption) {
  EXPECT_EQ(default_level_file("out/bvp.ply"), "out/bvp.level.ply");
  EXPECT_EQ(default_level_file("bvp.vtu"), "bvp.level.vtu");
  EXPECT_EQ(default_level_file("bvp.obj"), "bvp.level.csv");
  const ProblemSetup setup = make_catalogue_problem("bvp:points=10");
  for (const std::string& bad :
       {"lambda", "lambda=", "lambda=x", "lambda=1e999", "max:v=1", "lambda,epsilon=1"}) {
    try {
      parse_level_option(bad, *setup.problem);
      ADD_FAILURE() << bad << " was accepted";
    } catch (const InvalidArgument& error) {
      const std::string message = error.what();
      EXPECT_EQ(message.rfind("--level " + bad + ": ", 0), 0u) << message;
    }
  }
  try {
    parse_level_option("max:v=1", *setup.problem);
  } catch (const InvalidArgument& error) {
    EXPECT_NE(std::string(error.what()).find("no block 'v' (blocks: u"), std::string::npos)
        << error.what();
  }
  const LevelSet amplitude = parse_level_option(" max:u = 2 ", *setup.problem);
  EXPECT_EQ(amplitude.functional.specification(), "max:u");
  EXPECT_EQ(amplitude.value, 2.0);
}

}  // namespace
}  // namespace tessera
