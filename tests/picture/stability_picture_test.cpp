// SPDX-License-Identifier: MIT
// Categorical pictures (picture.h, picture_styles.h): the stability categories of unstable
// counts, a triangle of one category in its colour, a triangle whose corners differ split into
// its corners' parts, the legend in the colour bar's place (and named in the SVG), dashed and
// dotted curves that leave gaps where a solid one leaves none, markers in the shape and colour
// of their kind.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>

#include "support/test_support.h"
#include "tessera/core/error.h"
#include "tessera/picture/picture.h"

namespace tessera {
namespace {

std::array<int, 3> rgb_of(std::uint32_t pixel) {
  return {static_cast<int>((pixel >> 16) & 0xFF), static_cast<int>((pixel >> 8) & 0xFF),
          static_cast<int>(pixel & 0xFF)};
}

// Within 2 of 255 per channel: antialiasing does not reach the inside of a fill.
bool has_colour(std::uint32_t pixel, const std::array<double, 3>& rgb) {
  const auto got = rgb_of(pixel);
  for (std::size_t c = 0; c < 3; ++c) {
    if (std::abs(got[c] - 255.0 * rgb[c]) > 2.0) {
      return false;
    }
  }
  return true;
}

// Seen from above, unshaded, nothing but the surface (and what a test adds).
PictureOptions top_view(int size) {
  PictureOptions options;
  options.width = size;
  options.height = size;
  options.azimuth_degrees = -90;  // x to the right, y up
  options.elevation_degrees = 90;
  options.flat_shading = true;
  options.edges = PictureEdges::Off;
  options.axes = PictureAxes::Off;
  options.colour_bar = false;
  options.legend = false;
  return options;
}

// A strip [0, 4] × [0, 1] of 8 triangles over the vertices (i, 0), (i, 1), i = 0..4.
PictureScene strip() {
  PictureScene scene;
  scene.positions.resize(3, 10);
  for (int i = 0; i <= 4; ++i) {
    scene.positions.col(2 * i) = Eigen::Vector3d(i, 0, 0);
    scene.positions.col(2 * i + 1) = Eigen::Vector3d(i, 1, 0);
  }
  for (int i = 0; i < 4; ++i) {
    scene.triangles.push_back({2 * i, 2 * i + 2, 2 * i + 3});
    scene.triangles.push_back({2 * i, 2 * i + 3, 2 * i + 1});
  }
  return scene;
}

TEST(StabilityPicture, CategoriesOfUnstableCounts) {
  EXPECT_EQ(stability_category(0.0), 0);
  EXPECT_EQ(stability_category(1.0), 1);
  EXPECT_EQ(stability_category(2.0), 2);
  EXPECT_EQ(stability_category(7.0), 2);
  EXPECT_EQ(stability_category(-1.0), 3);  // the eigensolver failed
  EXPECT_EQ(stability_category(std::nan("")), 3);
  EXPECT_EQ(stability_category(INFINITY), 3);
  EXPECT_EQ(stability_category(0.5), 3);  // not a count
  const auto categories = stability_categories();
  ASSERT_EQ(categories.size(), 4u);
  EXPECT_EQ(categories[0].label, "stable");
  EXPECT_EQ(categories[3].label, "unknown");
  for (std::size_t a = 0; a < categories.size(); ++a) {
    for (std::size_t b = a + 1; b < categories.size(); ++b) {
      double distance = 0;
      for (std::size_t c = 0; c < 3; ++c) {
        distance += std::abs(categories[a].rgb[c] - categories[b].rgb[c]);
      }
      EXPECT_GT(distance, 0.3) << categories[a].label << " and " << categories[b].label;
    }
  }
}

// Stable on the left (x < 2), index 1 on the right: each half shows its colour, and the
// boundary runs through x = 2 (the vertices at x = 2 are stable, so the stable colour reaches
// half an edge beyond them, to x = 2.5).
TEST(StabilityPicture, RegionsShowTheirCategoryColours) {
  PictureScene scene = strip();
  std::vector<double> counts(10);
  for (int v = 0; v < 10; ++v) {
    counts[static_cast<std::size_t>(v)] = scene.positions(0, v) <= 2 ? 0.0 : 1.0;
  }
  colour_by_stability(scene, counts);
  const PictureImage image = render_picture(scene, top_view(400));
  const auto categories = stability_categories();
  // The strip [0, 4] fills 92 % of 400 pixels: x = 0 at 16, x = 4 at 384; y = 0.5 at 200.
  auto column = [](double x) { return static_cast<int>(std::lround(16 + 92 * x)); };
  EXPECT_TRUE(has_colour(image.at(column(1.0), 200), categories[0].rgb));
  EXPECT_TRUE(has_colour(image.at(column(2.3), 200), categories[0].rgb));
  EXPECT_TRUE(has_colour(image.at(column(2.7), 200), categories[1].rgb));
  EXPECT_TRUE(has_colour(image.at(column(3.5), 200), categories[1].rgb));
  EXPECT_FALSE(has_colour(image.at(column(3.5), 200), categories[0].rgb));
}

// One triangle with stable, index-1 and unknown corners: the part at each corner is in the
// corner's colour, so no category is lost to a vote.
TEST(StabilityPicture, ATriangleWhoseCornersDifferIsSplitBetweenThem) {
  PictureScene scene;
  scene.positions.resize(3, 3);
  scene.positions << 0, 1, 0,  //
      0, 0, 1,                 //
      0, 0, 0;
  scene.triangles = {{0, 1, 2}};
  colour_by_stability(scene, {0.0, 1.0, -1.0});
  const PictureImage image = render_picture(scene, top_view(300));
  const auto categories = stability_categories();
  // [0, 1]² fills 92 % of 300 pixels: x = 0 at 12, y = 0 at 288.
  auto pixel = [&](double x, double y) {
    return image.at(static_cast<int>(12 + 276 * x), static_cast<int>(288 - 276 * y));
  };
  EXPECT_TRUE(has_colour(pixel(0.1, 0.1), categories[0].rgb));
  EXPECT_TRUE(has_colour(pixel(0.8, 0.1), categories[1].rgb));
  EXPECT_TRUE(has_colour(pixel(0.1, 0.8), categories[3].rgb));
  // Under a majority vote (ties to the larger index) the triangle would be one colour.
  scene.triangle_categories = {2};
  scene.vertex_categories.clear();
  const PictureImage whole = render_picture(scene, top_view(300));
  EXPECT_TRUE(
      has_colour(whole.at(static_cast<int>(12 + 276 * 0.1), static_cast<int>(288 - 276 * 0.1)),
                 categories[2].rgb));
}

TEST(StabilityPicture, TheLegendTakesTheColourBarsPlaceAndIsNamedInTheSvg) {
  // All stable: orange, red and grey can come only from the legend, which lists every category.
  PictureScene scene = strip();
  colour_by_stability(scene, std::vector<double>(10, 0.0));
  scene.curves.push_back(
      styled_curve(Eigen::Matrix3Xd::Zero(3, 2), false, dark_curve_style(CurveKind::Hopf)));
  scene.curves.back().points.col(1) = Eigen::Vector3d(1, 1, 0);
  PictureOptions options = top_view(500);
  const auto categories = stability_categories();
  // The leftmost pixel of each colour, or -1.
  auto leftmost = [](const PictureImage& image, const std::array<double, 3>& rgb) {
    for (int x = 0; x < image.width; ++x) {
      for (int y = 0; y < image.height; ++y) {
        if (has_colour(image.at(x, y), rgb)) {
          return x;
        }
      }
    }
    return -1;
  };
  const PictureImage without = render_picture(scene, options);
  options.legend = true;
  const PictureImage with = render_picture(scene, options);
  for (std::size_t c = 1; c < categories.size(); ++c) {
    EXPECT_EQ(leftmost(without, categories[c].rgb), -1) << categories[c].label;
    EXPECT_GT(leftmost(with, categories[c].rgb), 0.6 * with.width) << categories[c].label;
  }
  const std::string dir = testing::temporary_directory("stability_picture_svg");
  options.title = "stability & Hopf";
  write_picture(dir + "/strip.svg", scene, options);
  std::ifstream in(dir + "/strip.svg");
  std::stringstream text;
  text << in.rdbuf();
  EXPECT_NE(text.str().find("<title>stability &amp; Hopf</title>"), std::string::npos);
  EXPECT_NE(text.str().find("<desc>legend: stable; index 1; index &gt;= 2; unknown; Hopf</desc>"),
            std::string::npos)
      << text.str().substr(0, 600);
}

// The number of runs of curve-coloured pixels along the row y = 100 of a horizontal curve.
int runs_along_curve(CurveDash dash) {
  PictureScene scene;  // a thin triangle at the left, so that the scene has a surface
  scene.positions.resize(3, 3);
  scene.positions << 0, 0.1, 0,  //
      0, 0, 1,                   //
      0, 0, 0;
  scene.triangles = {{0, 1, 2}};
  PictureCurve curve;
  curve.points.resize(3, 2);
  curve.points << 0, 1,  //
      0.5, 0.5,          //
      0, 0;
  curve.rgb = {0.1, 0.3, 0.85};
  curve.width = 3.0;
  curve.dash = dash;
  scene.curves.push_back(curve);
  const PictureImage image = render_picture(scene, top_view(200));
  int runs = 0;
  bool inside = false;
  for (int x = 0; x < image.width; ++x) {
    const bool coloured = has_colour(image.at(x, 100), curve.rgb);
    runs += coloured && !inside ? 1 : 0;
    inside = coloured;
  }
  return runs;
}

TEST(StabilityPicture, DashedAndDottedCurvesLeaveGaps) {
  EXPECT_EQ(runs_along_curve(CurveDash::Solid), 1);
  // 184 pixels of curve; dashes of 12 and gaps of 7.5 pixels: about 9 dashes.
  EXPECT_GE(runs_along_curve(CurveDash::Dashed), 8);
  // Dots every 9 pixels: about 20 (a dot of 3 pixels may fall short of the full colour).
  EXPECT_GE(runs_along_curve(CurveDash::Dotted), 12);
}

TEST(StabilityPicture, MarkersHaveTheColourOfTheirKindAtTheirPlace) {
  PictureScene scene;
  scene.positions.resize(3, 3);
  scene.positions << 0, 1, 0,  //
      0, 0, 1,                 //
      0, 0, 0;
  scene.triangles = {{0, 1, 2}};
  scene.markers.resize(3, 3);
  scene.markers << 0.2, 0.5, 0.8,  //
      0.8, 0.8, 0.8,               //
      0, 0, 0;
  scene.marker_kinds = {PointKind::Cusp, PointKind::BogdanovTakens, PointKind::ZeroHopf};
  const PictureImage image = render_picture(scene, top_view(300));
  auto at = [&](double x, double y) {
    return image.at(static_cast<int>(12 + 276 * x), static_cast<int>(288 - 276 * y));
  };
  EXPECT_TRUE(has_colour(at(0.2, 0.8), {1.0, 0.85, 0.1}));   // cusp: yellow triangle
  EXPECT_TRUE(has_colour(at(0.5, 0.8), {0.2, 0.8, 0.3}));    // Bogdanov–Takens: green square
  EXPECT_TRUE(has_colour(at(0.8, 0.8), {0.85, 0.35, 0.9}));  // zero-Hopf: violet diamond
  // A square's corner is inside, a triangle's upper corners are not: 3 pixels right and up of
  // the centre (the square's half side is 5, the triangle's half width there 2).
  EXPECT_TRUE(has_colour(
      image.at(static_cast<int>(12 + 276 * 0.5) + 3, static_cast<int>(288 - 276 * 0.8) - 3),
      {0.2, 0.8, 0.3}));
  EXPECT_FALSE(has_colour(
      image.at(static_cast<int>(12 + 276 * 0.2) + 3, static_cast<int>(288 - 276 * 0.8) - 3),
      {1.0, 0.85, 0.1}));
}

TEST(StabilityPicture, BadCategoriesAreRefused) {
  PictureScene scene = strip();
  EXPECT_THROW(colour_by_stability(scene, {0.0, 1.0}), InvalidArgument);
  colour_by_stability(scene, std::vector<double>(10, 0.0));
  scene.vertex_categories[3] = 7;
  EXPECT_THROW(render_picture(scene, top_view(100)), InvalidArgument);
  scene.vertex_categories[3] = 0;
  scene.triangle_values = Eigen::VectorXd::Zero(8);
  EXPECT_THROW(render_picture(scene, top_view(100)), InvalidArgument);
  scene.triangle_values.resize(0);
  scene.markers = Eigen::Matrix3Xd::Zero(3, 2);
  scene.marker_kinds = {PointKind::Cusp};
  EXPECT_THROW(render_picture(scene, top_view(100)), InvalidArgument);
}

}  // namespace
}  // namespace tessera
