// SPDX-License-Identifier: MIT
// `tessera render` and `tessera mesh --picture` as a user meets them: pictures of a mesh file, of
// a planar DDT triangulation from above, of a run with its fold curves, and bad options refused
// with a message naming them (exit 2) before anything is drawn or computed.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "support/test_support.h"
#include "tessera/io/mesh_io.h"
#include "tessera/io/polylines.h"
#include "tessera/picture/picture.h"

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

// Issue 34: `render --help` said the automatic aspect keeps equal scales up to 4x while the code
// drew with 10; the help now quotes the constant the drawing uses.
TEST(RenderCli, HelpQuotesTheAspectRatioTheCodeUses) {
  const auto help = run_cli("render --help");
  ASSERT_EQ(help.exit_code, 0) << help.output;
  std::ostringstream ratio;
  ratio << "differ by more than " << kMaxEqualAspectRatio << "x";
  EXPECT_TRUE(contains(help.output, ratio.str())) << help.output;
  EXPECT_FALSE(contains(help.output, "more than 4x")) << help.output;
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
                       "distance, stability, x, lambda, mu"))
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
           Case{"render " + mesh + " --curves " + dir + "/s.ply",
                "not a polylines file of tessera"},
           Case{"render " + dir + "/missing.ply -o " + dir + "/s.png", "missing.ply"},
           Case{"render " + dir + "/empty.ply -o " + dir + "/s.png", "no triangles"},
           Case{"render " + mesh + " --curves " + dir + "/nan.csv", "drawn coordinates (its first three columns) are not numbers"},
           Case{"render " + mesh + " --aspect squashed", "--aspect"},
           Case{"render " + mesh + " --axes boxed", "--axes"},
           Case{"render " + mesh + " --edges some", "--edges"},
           Case{"mesh sphere -o " + dir + "/t.ply --picture " + dir + "/t.gif", ".png or .svg"},
       }) {
    const auto result = run_cli(bad.arguments);
    EXPECT_EQ(result.exit_code, kUsageError) << bad.arguments << "\n" << result.output;
    EXPECT_TRUE(contains(result.output, bad.message)) << bad.arguments << "\n" << result.output;
  }
  EXPECT_FALSE(std::filesystem::exists(dir + "/s.png"));
  EXPECT_FALSE(std::filesystem::exists(dir + "/t.ply"));
}

std::string text_of(const std::string& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// A planar grid over (Da, B) ∈ [0, 1]² with the stability data of `tessera mesh --stability`:
// stable for Da < 0.4, index 1 up to 0.7, index 2 beyond; unknown (−1, NaN) in one corner.
TriangleMesh stability_grid(std::vector<VertexScalars>& data) {
  constexpr int n = 8;
  Eigen::MatrixXd points(3, (n + 1) * (n + 1));
  std::vector<Triangle> triangles;
  std::vector<double> count, real_part, certain;
  for (int j = 0; j <= n; ++j) {
    for (int i = 0; i <= n; ++i) {
      const double da = static_cast<double>(i) / n, b = static_cast<double>(j) / n;
      points.col(j * (n + 1) + i) = Eigen::Vector3d(da, b, 0.1 * da * b);
      const bool is_unknown = i == n && j == n;
      count.push_back(is_unknown ? -1.0 : da < 0.4 ? 0.0 : da < 0.7 ? 1.0 : 2.0);
      real_part.push_back(is_unknown ? std::nan("") : da - 0.4);
      certain.push_back(is_unknown ? 0.0 : 1.0);
    }
  }
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      const int v = j * (n + 1) + i;
      triangles.push_back({v, v + 1, v + n + 2});
      triangles.push_back({v, v + n + 2, v + n + 1});
    }
  }
  data = {
      {"unstable_count", count}, {"leading_real_part", real_part}, {"stability_certain", certain}};
  return TriangleMesh(points, triangles);
}

TEST(RenderCli, ColoursAMeshByStabilityFromEveryFormat) {
  const std::string dir = testing::temporary_directory("render_cli_stability");
  std::vector<VertexScalars> data;
  const TriangleMesh mesh = stability_grid(data);
  for (const std::string extension : {".ply", ".vtk", ".vtu"}) {
    const std::string path = dir + "/grid" + extension;
    write_mesh(path, mesh,
               {.binary = false, .coordinate_names = {"Da", "B", "x1"}, .vertex_scalars = data});
    // The readers give the data back by name, NaN included.
    std::vector<VertexScalars> read_back;
    const TriangleMesh read = read_mesh(path, read_back);
    ASSERT_EQ(read.vertex_count(), mesh.vertex_count()) << extension;
    ASSERT_EQ(read_back.size(), 3u) << extension;
    EXPECT_EQ(read_back[0].name, "unstable_count") << extension;
    EXPECT_EQ(read_back[0].values, data[0].values) << extension;
    EXPECT_TRUE(std::isnan(read_back[1].values.back())) << extension;
    EXPECT_EQ(read_back[2].name, "stability_certain") << extension;

    const auto result = run_cli("render " + path + " --colour stability --top -o " + dir +
                                "/grid.svg --title 'stability of " + extension + "'");
    ASSERT_EQ(result.exit_code, 0) << extension << "\n" << result.output;
    const std::string svg = text_of(dir + "/grid.svg");
    // The axes named as the file names its columns, the legend's entries: text in the SVG.
    EXPECT_TRUE(contains(svg,
                         "<desc>axes: Da, B, x1\nlegend: stable; index 1; index &gt;= 2; "
                         "unknown</desc>"))
        << extension;
    // Another array of the file, by name: a colour bar, not a legend.
    const auto by_name =
        run_cli("render " + path + " --colour leading_real_part -o " + dir + "/real.png");
    ASSERT_EQ(by_name.exit_code, 0) << extension << "\n" << by_name.output;
    EXPECT_TRUE(is_png(dir + "/real.png"));
  }
  // A mesh without the data: the message names the file and the command that writes it.
  write_mesh(dir + "/plain.ply", mesh);
  const auto missing =
      run_cli("render " + dir + "/plain.ply --colour stability -o " + dir + "/plain.png");
  EXPECT_EQ(missing.exit_code, kUsageError);
  EXPECT_TRUE(contains(missing.output, "plain.ply has no vertex data 'unstable_count'") &&
              contains(missing.output, "--stability"))
      << missing.output;
  EXPECT_FALSE(std::filesystem::exists(dir + "/plain.png"));
}

// A continuation view, (lambda, epsilon, max_u) of unrelated extents as `tessera mesh` writes
// bvp's: ticked axes named by the file's columns (docs/images/bvp_folds.png said x, y, z), the
// camera chosen unless angles are given; --axes and --edges as asked.
TEST(RenderCli, ContinuationViewsNameTheirAxesByTheFilesColumns) {
  const std::string dir = testing::temporary_directory("render_cli_axes");
  constexpr int cells = 8;
  Eigen::MatrixXd points(3, (cells + 1) * (cells + 1));
  std::vector<Triangle> triangles;
  for (int j = 0; j <= cells; ++j) {
    for (int i = 0; i <= cells; ++i) {
      const double s = -1.3 + 2.6 * i / cells;  // an S-shaped sheet: folds along epsilon
      points.col(j * (cells + 1) + i) =
          Eigen::Vector3d(3.5 + 2 * (s * s * s - s), 0.3 * j / cells, 10 + 8 * s);
    }
  }
  for (int j = 0; j < cells; ++j) {
    for (int i = 0; i < cells; ++i) {
      const int v = j * (cells + 1) + i;
      triangles.push_back({v, v + 1, v + cells + 2});
      triangles.push_back({v, v + cells + 2, v + cells + 1});
    }
  }
  write_mesh(dir + "/view.ply", TriangleMesh(points, triangles),
             {.coordinate_names = {"lambda", "epsilon", "max_u"}});
  for (const std::string options : {"", " --azimuth 210 --elevation 25", " --axes triad --edges on",
                                    " --axes off --edges off"}) {
    const auto result = run_cli("render " + dir + "/view.ply -o " + dir + "/view.svg" + options);
    ASSERT_EQ(result.exit_code, 0) << options << "\n" << result.output;
    const std::string svg = text_of(dir + "/view.svg");
    const bool has_axes = options.find("--axes off") == std::string::npos;
    EXPECT_EQ(contains(svg, "<desc>axes: lambda, epsilon, max_u\ncolour: max_u</desc>"), has_axes)
        << options << "\n"
        << svg.substr(0, 600);
  }
  const auto png = run_cli("render " + dir + "/view.ply -o " + dir + "/view.png --size 320x240");
  ASSERT_EQ(png.exit_code, 0) << png.output;
  EXPECT_TRUE(is_png(dir + "/view.png"));
}

// Fold curves (JSON, cusps) and Hopf curves (CSV with an omega column and Bogdanov–Takens
// points) as the mesh command writes them, over a mesh and as a bifurcation diagram.
TEST(RenderCli, DrawsCurvesByKindAndTheBifurcationDiagram) {
  const std::string dir = testing::temporary_directory("render_cli_diagram");
  std::vector<VertexScalars> data;
  const TriangleMesh grid = stability_grid(data);
  write_mesh(dir + "/grid.vtu", grid,
             {.coordinate_names = {"Da", "B", "x1"}, .vertex_scalars = data});
  Polyline fold;
  fold.points.resize(3, 3);
  fold.points << 0.4, 0.4, 0.4,  //
      0.0, 0.5, 1.0,             //
      0.0, 0.02, 0.04;
  fold.marked = {false, true, false};
  write_polylines(dir + "/grid.folds.json", {fold}, {.names = {"Da", "B", "x1"}, .kind = "fold"});
  Polyline hopf;
  hopf.points.resize(4, 3);
  hopf.points << 0.7, 0.7, 0.7,  //
      0.2, 0.5, 0.8,             //
      0.01, 0.03, 0.05,          //
      1.0, 1.2, 1.5;             // omega
  hopf.marked = {true, false, false};
  write_polylines(
      dir + "/grid.hopf.csv", {hopf},
      {.names = {"Da", "B", "x1", "omega"}, .marker_name = "bogdanov_takens", .kind = "hopf"});
  EXPECT_TRUE(contains(text_of(dir + "/grid.hopf.csv"), "# kind: hopf\n"));
  // Old fold files: no kind, no marker.
  std::ofstream(dir + "/old.json")
      << R"({"polylines": [{"points": [[0.4, 0.1, 0], [0.4, 0.9, 0]]}]})";

  const auto surface = run_cli("render " + dir + "/grid.vtu --colour stability --curves " + dir +
                               "/grid.folds.json --curves " + dir + "/grid.hopf.csv --curves " +
                               dir + "/old.json -o " + dir + "/surface.svg");
  ASSERT_EQ(surface.exit_code, 0) << surface.output;
  EXPECT_TRUE(contains(text_of(dir + "/surface.svg"),
                       "\nlegend: stable; index 1; index &gt;= 2; unknown; fold; Hopf; cusp; "
                       "Bogdanov-Takens</desc>"));

  const auto diagram =
      run_cli("render --diagram Da,B --curves " + dir + "/grid.folds.json --curves " + dir +
              "/grid.hopf.csv -o " + dir + "/diagram.svg --title 'two-parameter diagram'");
  ASSERT_EQ(diagram.exit_code, 0) << diagram.output;
  const std::string svg = text_of(dir + "/diagram.svg");
  EXPECT_TRUE(contains(svg, "<title>two-parameter diagram</title>"));
  EXPECT_TRUE(contains(svg, "<desc>axes: Da, B\nlegend: Hopf; fold; cusp; Bogdanov-Takens</desc>"))
      << svg.substr(0, 500);
  const auto png = run_cli("render --diagram B,omega --curves " + dir + "/grid.hopf.csv -o " + dir +
                           "/omega.png");
  ASSERT_EQ(png.exit_code, 0) << png.output;
  EXPECT_TRUE(is_png(dir + "/omega.png"));

  std::ofstream(dir + "/broken.json") << R"({"polylines": [{"points": [[0, 1], [2, )";
  std::ofstream(dir + "/ragged.json") << R"({"polylines": [{"points": [[0, 1], [2, 3, 4]]}]})";
  struct Case {
    std::string arguments;
    std::string message;
  };
  const std::string curves =
      " --curves " + dir + "/grid.folds.json --curves " + dir + "/grid.hopf.csv";
  for (const Case& bad : {
           Case{"render --diagram Da,omega" + curves + " -o " + dir + "/d.png",
                "grid.folds.json: no column 'omega' among the curves' columns (Da, B, x1)"},
           Case{"render --diagram Da" + curves + " -o " + dir + "/d.png", "two column names"},
           Case{"render --diagram Da,B -o " + dir + "/d.png", "needs --curves"},
           Case{"render " + dir + "/grid.vtu --diagram Da,B" + curves + " -o " + dir + "/d.png",
                "leave out the mesh"},
           Case{"render -o " + dir + "/d.png", "needs a mesh file"},
           Case{"render " + dir + "/grid.vtu --curves " + dir + "/broken.json -o " + dir + "/d.png",
                "broken.json': not valid JSON"},
           Case{"render " + dir + "/grid.vtu --curves " + dir + "/ragged.json -o " + dir + "/d.png",
                "polyline 0, point 1 has 3 coordinates, expected 2"},
       }) {
    const auto result = run_cli(bad.arguments);
    EXPECT_EQ(result.exit_code, kUsageError) << bad.arguments << "\n" << result.output;
    EXPECT_TRUE(contains(result.output, bad.message)) << bad.arguments << "\n" << result.output;
    EXPECT_FALSE(contains(result.output, "json.exception")) << result.output;
  }
  EXPECT_FALSE(std::filesystem::exists(dir + "/d.png"));
}

}  // namespace
}  // namespace tessera
