// SPDX-License-Identifier: MIT
// The two-parameter bifurcation diagram (bifurcation_diagram.h): ticks at round values that
// cover the range, curves and points drawn inside the axes box where the layout puts them, the
// Hopf curve dashed, the legend named in the SVG, columns taken by name, bad input refused.
#include "tessera/picture/bifurcation_diagram.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "support/test_support.h"
#include "tessera/core/error.h"

namespace tessera {
namespace {

bool has_colour(std::uint32_t pixel, const std::array<double, 3>& rgb, double slack = 2.0) {
  const int got[3] = {static_cast<int>((pixel >> 16) & 0xFF), static_cast<int>((pixel >> 8) & 0xFF),
                      static_cast<int>(pixel & 0xFF)};
  for (std::size_t c = 0; c < 3; ++c) {
    if (std::abs(got[c] - 255.0 * rgb[c]) > slack) {
      return false;
    }
  }
  return true;
}

// A cusp-shaped pair of fold curves from (0, 0), a Hopf curve p2 = 1.5 from p1 = 0.5 to 2 with
// a Bogdanov–Takens point at its left end.
BifurcationDiagramScene cusp_and_hopf() {
  BifurcationDiagramScene scene;
  scene.parameter_names = {"Da", "B"};
  for (const double sign : {1.0, -1.0}) {
    DiagramCurve fold;
    fold.points.resize(2, 21);
    for (int i = 0; i <= 20; ++i) {
      const double t = i / 10.0;
      fold.points.col(i) = Eigen::Vector2d(t, sign * std::pow(t, 1.5) * 0.5);
    }
    scene.curves.push_back(fold);
  }
  DiagramCurve hopf;
  hopf.kind = CurveKind::Hopf;
  hopf.points.resize(2, 2);
  hopf.points << 0.5, 2.0,  //
      1.5, 1.5;
  scene.curves.push_back(hopf);
  scene.points.push_back({Eigen::Vector2d(0, 0), PointKind::Cusp});
  scene.points.push_back({Eigen::Vector2d(0.5, 1.5), PointKind::BogdanovTakens});
  return scene;
}

TEST(BifurcationDiagram, TicksAreRoundAndCoverTheRange) {
  const auto ticks = nice_ticks(0.0, 1.0, 6);
  ASSERT_EQ(ticks.size(), 6u);
  for (std::size_t i = 0; i < ticks.size(); ++i) {
    EXPECT_DOUBLE_EQ(ticks[i], 0.2 * static_cast<double>(i));
  }
  for (const auto& [low, high] : {std::pair{-0.73, 1.52}, std::pair{3.1e-4, 7.7e-4},
                                  std::pair{-1234.0, 98765.0}, std::pair{0.999, 1.001}}) {
    const auto values = nice_ticks(low, high, 5);
    ASSERT_GE(values.size(), 2u) << low << ", " << high;
    const double step = values[1] - values[0];
    const double mantissa = step / std::pow(10.0, std::floor(std::log10(step) + 1e-9));
    EXPECT_TRUE(std::abs(mantissa - 1) < 1e-6 || std::abs(mantissa - 2) < 1e-6 ||
                std::abs(mantissa - 5) < 1e-6)
        << "step " << step;
    EXPECT_GE(values.front(), low - 1e-12 * std::abs(low));
    EXPECT_LT(values.front() - step, low);  // the first multiple of the step in the range
    EXPECT_LE(values.back(), high + 1e-12 * std::abs(high));
    EXPECT_GT(values.back() + step, high);
    EXPECT_LE(values.size(), 11u);
  }
  EXPECT_EQ(nice_ticks(2.0, 2.0, 5), std::vector<double>{2.0});
}

TEST(BifurcationDiagram, CurvesAndPointsLieInsideTheAxesBoxWhereTheLayoutPutsThem) {
  const BifurcationDiagramScene scene = cusp_and_hopf();
  BifurcationDiagramOptions options;
  options.legend = false;
  const DiagramLayout layout = bifurcation_diagram_layout(scene, options);
  EXPECT_LT(layout.p1_range[0], 0.0);  // the margin
  EXPECT_GT(layout.p1_range[1], 2.0);
  const PictureImage image = render_bifurcation_diagram(scene, options);
  const CurveStyle fold = curve_style(CurveKind::Fold);
  const CurveStyle hopf = curve_style(CurveKind::Hopf);
  int fold_pixels = 0, hopf_pixels = 0;
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) {
      const bool is_fold = has_colour(image.at(x, y), fold.rgb, 8.0);
      const bool is_hopf = has_colour(image.at(x, y), hopf.rgb, 8.0);
      if (is_fold || is_hopf) {
        EXPECT_TRUE(x >= layout.left && x <= layout.right && y >= layout.top && y <= layout.bottom)
            << "curve pixel (" << x << ", " << y << ") outside the axes box";
      }
      fold_pixels += is_fold ? 1 : 0;
      hopf_pixels += is_hopf ? 1 : 0;
    }
  }
  EXPECT_GT(fold_pixels, 500);
  EXPECT_GT(hopf_pixels, 100);
  // The Hopf curve p2 = 1.5 is dashed: along its row, runs of its colour with gaps between.
  const Eigen::Vector2d start = layout.pixel({0.7, 1.5});
  const Eigen::Vector2d end = layout.pixel({2.0, 1.5});
  const int row = static_cast<int>(std::lround(start(1)));
  int runs = 0;
  bool inside = false;
  for (int x = static_cast<int>(start(0)); x < static_cast<int>(end(0)) - 2; ++x) {
    const bool coloured = has_colour(image.at(x, row), hopf.rgb, 8.0);
    runs += coloured && !inside ? 1 : 0;
    inside = coloured;
  }
  EXPECT_GE(runs, 10) << "a dashed Hopf curve of " << end(0) - start(0) << " pixels";
  // The Bogdanov–Takens square at its place (green), the cusp triangle at the origin (yellow).
  const Eigen::Vector2d bt = layout.pixel({0.5, 1.5});
  EXPECT_TRUE(has_colour(image.at(static_cast<int>(bt(0)) + 2, static_cast<int>(bt(1)) + 3),
                         {0.2, 0.8, 0.3}));
  const Eigen::Vector2d cusp = layout.pixel({0.0, 0.0});
  EXPECT_TRUE(has_colour(image.at(static_cast<int>(cusp(0)), static_cast<int>(cusp(1)) + 2),
                         {1.0, 0.85, 0.1}));
}

TEST(BifurcationDiagram, TheSvgNamesTheTitleAndTheLegend) {
  const std::string dir = testing::temporary_directory("bifurcation_diagram_svg");
  BifurcationDiagramOptions options;
  options.title = "CSTR in (Da, B)";
  BifurcationDiagramScene scene = cusp_and_hopf();
  DiagramCurve saddle;
  saddle.kind = CurveKind::NeutralSaddle;
  saddle.points = Eigen::Matrix2Xd::Zero(2, 2);
  saddle.points(0, 1) = 1.0;
  scene.curves.push_back(saddle);
  write_bifurcation_diagram(dir + "/d.svg", scene, options);
  write_bifurcation_diagram(dir + "/d.PNG", scene, options);
  std::ifstream in(dir + "/d.svg");
  std::stringstream text;
  text << in.rdbuf();
  EXPECT_NE(text.str().find("<title>CSTR in (Da, B)</title>"), std::string::npos);
  EXPECT_NE(text.str().find("<desc>axes: Da, B\nlegend: Hopf; fold; neutral saddle; cusp; "
                            "Bogdanov-Takens</desc>"),
            std::string::npos)
      << text.str().substr(0, 800);
  EXPECT_GT(std::filesystem::file_size(dir + "/d.PNG"), 1000u);
  EXPECT_THROW(write_bifurcation_diagram(dir + "/d.jpg", scene, options), InvalidArgument);
}

TEST(BifurcationDiagram, PolylinesGiveTheirNamedColumnsAndMarkedPoints) {
  Polyline line;
  line.points.resize(3, 3);
  line.points << 1, 2, 3,  // x1 (not drawn)
      0.1, 0.2, 0.3,       // Da
      5, 6, 7;             // B
  line.marked = {false, true, false};
  PolylineFileOptions file;
  file.names = {"x1", "Da", "B"};
  file.kind = "hopf";
  file.marker_name = "bogdanov_takens";
  BifurcationDiagramScene scene;
  add_to_diagram(scene, {line}, file, "Da", "B");
  ASSERT_EQ(scene.curves.size(), 1u);
  EXPECT_EQ(scene.curves[0].kind, CurveKind::Hopf);
  EXPECT_EQ(scene.curves[0].points.col(2), Eigen::Vector2d(0.3, 7));
  ASSERT_EQ(scene.points.size(), 1u);
  EXPECT_EQ(scene.points[0].kind, PointKind::BogdanovTakens);
  EXPECT_EQ(scene.points[0].point, Eigen::Vector2d(0.2, 6));
  try {
    add_to_diagram(scene, {line}, file, "Da", "beta");
    FAIL() << "no column beta";
  } catch (const InvalidArgument& error) {
    EXPECT_NE(
        std::string(error.what()).find("no column 'beta' among the curves' columns (x1, Da, B)"),
        std::string::npos)
        << error.what();
  }
}

TEST(BifurcationDiagram, BadInputIsRefused) {
  BifurcationDiagramOptions options;
  EXPECT_THROW(render_bifurcation_diagram({}, options), InvalidArgument);  // nothing to draw
  BifurcationDiagramScene scene = cusp_and_hopf();
  scene.points.push_back({Eigen::Vector2d(NAN, 0), PointKind::ZeroHopf});
  EXPECT_THROW(render_bifurcation_diagram(scene, options), InvalidArgument);
  options.width = 4;
  EXPECT_THROW(render_bifurcation_diagram(cusp_and_hopf(), options), InvalidArgument);
}

}  // namespace
}  // namespace tessera
