// SPDX-License-Identifier: MIT
// `tessera mesh --folds` as a user meets it: the pleat's fold and cusp in the summary and in a
// polyline file of every format, the curves of a large problem in its view, and bad options
// refused before any computation with a message that names them.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "support/test_support.h"

namespace tessera {
namespace {

using testing::run_cli;

constexpr int kUsageError = 2;

std::string read_text(const std::string& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

bool contains(const std::string& text, const std::string& fragment) {
  return text.find(fragment) != std::string::npos;
}

TEST(FoldsCli, PleatFoldAndCuspAreInTheSummaryAndTheFileOnTheExactCurve) {
  const std::string dir = testing::temporary_directory("folds_cli_pleat");
  const auto result = run_cli("mesh whitney_pleat --tolerance 0.01 --folds lambda,mu -o " + dir +
                              "/pleat.vtk --summary " + dir + "/pleat.json");
  ASSERT_EQ(result.exit_code, 0) << result.output;
  EXPECT_TRUE(contains(result.output, "1 cusp(s)")) << result.output;
  EXPECT_TRUE(contains(result.output, dir + "/pleat.folds.vtk")) << result.output;
  const auto summary = nlohmann::json::parse(read_text(dir + "/pleat.json"));
  const auto& folds = summary.at("folds");
  EXPECT_EQ(folds.at("plane"), "lambda, mu");
  EXPECT_EQ(folds.at("file"), dir + "/pleat.folds.vtk");
  EXPECT_EQ(folds.at("unrefined_points"), 0);
  ASSERT_EQ(folds.at("cusps").size(), 1u);
  EXPECT_LT(std::abs(folds.at("cusps")[0].at("plane").at("lambda").get<double>()), 1e-8);
  EXPECT_LT(std::abs(folds.at("cusps")[0].at("point").at("x").get<double>()), 1e-8);
  ASSERT_EQ(folds.at("curves").size(), 1u);
  const auto& points = folds.at("curves")[0].at("points");
  EXPECT_EQ(static_cast<int>(points.size()), folds.at("point_count").get<int>());
  for (const auto& point : points) {  // columns x, lambda, mu
    const double x = point[0], lambda = point[1], mu = point[2];
    EXPECT_NEAR(lambda, 3 * x * x, 1e-8);
    EXPECT_NEAR(mu, -2 * x * x * x, 1e-8);
  }
  const std::string vtk = read_text(dir + "/pleat.folds.vtk");
  // An unstructured grid (meshio reads no POLYDATA) of segments (meshio reads no poly lines).
  EXPECT_TRUE(contains(vtk, "DATASET UNSTRUCTURED_GRID")) << vtk.substr(0, 300);
  EXPECT_TRUE(contains(vtk, "CELLS " + std::to_string(points.size() - 1) + " " +
                                std::to_string(3 * (points.size() - 1))));
  EXPECT_TRUE(contains(vtk, "CELL_TYPES " + std::to_string(points.size() - 1)));
  EXPECT_TRUE(contains(vtk, "SCALARS cusp int 1"));
}

TEST(FoldsCli, EveryPolylineFormatHoldsTheSamePointsInTheView) {
  const std::string dir = testing::temporary_directory("folds_cli_formats");
  // n = 22: written in the view lambda, epsilon, max:u; the folds in the same view.
  for (const std::string extension : {"vtk", "vtu", "ply", "json", "csv"}) {
    const std::string folds_file = dir + "/bvp.folds." + extension;
    const auto result = run_cli("mesh bvp:points=20 --tolerance 0.05 --view lambda,epsilon,max:u "
                                "--folds lambda,epsilon -q -o " + dir + "/bvp.ply --folds-output " +
                                folds_file + " --summary " + dir + "/bvp.json");
    ASSERT_EQ(result.exit_code, 0) << result.output;
    const auto summary = nlohmann::json::parse(read_text(dir + "/bvp.json")).at("folds");
    const int count = summary.at("point_count");
    EXPECT_GT(count, 10);
    EXPECT_EQ(summary.at("columns"), nlohmann::json({"lambda", "epsilon", "max_u"}));
    const std::string text = read_text(folds_file);
    if (extension == "json") {
      const auto document = nlohmann::json::parse(text);
      EXPECT_EQ(document.at("columns"), summary.at("columns"));
      EXPECT_EQ(document.at("polylines")[0].at("points"), summary.at("curves")[0].at("points"));
      EXPECT_EQ(document.at("polylines")[0].at("marked").size(), 1u);  // the cusp
    } else if (extension == "csv") {
      EXPECT_TRUE(contains(text, "curve,point,lambda,epsilon,max_u,cusp\n"));
      std::istringstream lines(text);
      int rows = 0;
      for (std::string line; std::getline(lines, line);) {
        rows += line.empty() || line[0] == '#' ? 0 : 1;
      }
      EXPECT_EQ(rows, count + 1);  // and the header
    } else if (extension == "ply") {
      EXPECT_TRUE(contains(text, "element vertex " + std::to_string(count) + "\n"));
      EXPECT_TRUE(contains(text, "element edge " + std::to_string(count - 1) + "\n"));
    } else if (extension == "vtu") {
      EXPECT_TRUE(contains(text, "NumberOfPoints=\"" + std::to_string(count) + "\""));
      EXPECT_TRUE(contains(text, "Name=\"max_u\""));
    } else {
      EXPECT_TRUE(contains(text, "POINTS " + std::to_string(count) + " double"));
    }
  }
}

TEST(FoldsCli, BadFoldOptionsAreRefusedBeforeTheComputation) {
  const std::string dir = testing::temporary_directory("folds_cli_bad");
  const std::string mesh = " -o " + dir + "/m.ply";
  struct Case {
    std::string arguments;
    std::string message;
  };
  for (const Case& bad : {
           Case{"mesh whitney_pleat --folds lambda" + mesh, "two functionals"},
           Case{"mesh whitney_pleat --folds lambda,nu" + mesh, "'nu'"},
           Case{"mesh bvp:points=20 --folds lambda,max:u" + mesh, "not differentiable"},
           Case{"mesh whitney_pleat --folds lambda,mu --folds-output " + dir + "/f.obj" + mesh,
                "unknown extension"},
           Case{"mesh whitney_pleat --folds-output " + dir + "/f.vtk" + mesh, "needs --folds"},
       }) {
    const auto result = run_cli(bad.arguments);
    EXPECT_EQ(result.exit_code, kUsageError) << bad.arguments << "\n" << result.output;
    EXPECT_TRUE(contains(result.output, bad.message)) << bad.arguments << "\n" << result.output;
    EXPECT_FALSE(std::filesystem::exists(dir + "/m.ply")) << bad.arguments;
  }
}

}  // namespace
}  // namespace tessera
