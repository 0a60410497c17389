// SPDX-License-Identifier: MIT
// Pictures (src/tessera/picture) held to geometry: a unit sphere seen orthographically covers
// π r² of its frame, a triangle shows the colour map's colour of its value, the nearer of two
// triangles hides the farther, curves behind the surface are dashed, SVG is the same drawing.
#include "tessera/picture/picture.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "support/test_support.h"
#include "tessera/core/error.h"
#include "tessera/methods/covering_methods.h"
#include "tessera/problems/catalogue.h"

namespace tessera {
namespace {

constexpr std::uint32_t kWhite = 0xFFFFFFFFu;

std::array<int, 3> rgb_of(std::uint32_t pixel) {
  return {static_cast<int>((pixel >> 16) & 0xFF), static_cast<int>((pixel >> 8) & 0xFF),
          static_cast<int>(pixel & 0xFF)};
}

void expect_colour(std::uint32_t pixel, const std::array<double, 3>& rgb, const char* what) {
  const auto got = rgb_of(pixel);
  for (int c = 0; c < 3; ++c) {
    EXPECT_NEAR(got[static_cast<std::size_t>(c)], 255.0 * rgb[static_cast<std::size_t>(c)], 1.5)
        << what << ", channel " << c;
  }
}

PictureOptions plain_options(int size) {
  PictureOptions options;
  options.width = size;
  options.height = size;
  options.edges = false;
  options.axes = false;
  options.colour_bar = false;
  return options;
}

TEST(Picture, UnitSphereSeenOrthographicallyCoversPiRSquaredOfTheFrame) {
  const ProblemSetup setup = make_catalogue_problem("sphere");
  MethodSettings settings;
  settings.tolerance = 1e-3;
  const CoveringResult covering = cover(setup, covering_methods().front(), settings);
  ASSERT_TRUE(covering.summary.is_complete());
  PictureScene scene;
  scene.positions = covering.mesh.points();
  scene.triangles = covering.mesh.triangles();
  for (const auto& [azimuth, elevation] : {std::pair{-60.0, 30.0}, std::pair{10.0, -75.0}}) {
    PictureOptions options = plain_options(600);
    options.azimuth_degrees = azimuth;
    options.elevation_degrees = elevation;
    const PictureImage image = render_picture(scene, options);
    long covered = 0;
    int left = image.width, right = -1, top = image.height, bottom = -1;
    for (int y = 0; y < image.height; ++y) {
      for (int x = 0; x < image.width; ++x) {
        if (image.at(x, y) != kWhite) {
          ++covered;
          left = std::min(left, x), right = std::max(right, x);
          top = std::min(top, y), bottom = std::max(bottom, y);
        }
      }
    }
    // Zoom 1 fits the projected extent, a diameter of 2, into 92 % of the frame.
    const double radius = 0.92 * 600 / 2;
    EXPECT_NEAR(right - left + 1, 2 * radius, 3.0);
    EXPECT_NEAR(bottom - top + 1, 2 * radius, 3.0);
    const double disk = M_PI * radius * radius;
    EXPECT_NEAR(covered / disk, 1.0, 0.01) << "azimuth " << azimuth << ", elevation " << elevation;
  }
}

// Two triangles in the plane z = 0, seen from above without light falloff (they face the eye):
// each shows viridis of its value, scaled to the range of the values.
TEST(Picture, ATriangleShowsTheColourOfItsValue) {
  PictureScene scene;
  scene.positions.resize(3, 4);
  scene.positions << 0, 1, 1, 0,  //
      0, 0, 1, 1,                 //
      0, 0, 0, 0;
  scene.triangles = {{0, 1, 2}, {0, 2, 3}};
  scene.triangle_values = Eigen::Vector2d(3.0, 5.0);
  PictureOptions options = plain_options(200);
  options.azimuth_degrees = -90;  // x to the right, y up
  options.elevation_degrees = 90;
  const PictureImage image = render_picture(scene, options);
  // Frame: the unit square fills 92 % of 200 pixels around the centre (100, 100).
  expect_colour(image.at(100 + 40, 100 + 20), viridis(0.0), "lower right triangle, value 3");
  expect_colour(image.at(100 - 40, 100 - 20), viridis(1.0), "upper left triangle, value 5");
  expect_colour(image.at(3, 3), {1.0, 1.0, 1.0}, "background");
}

TEST(Picture, TheNearerTriangleHidesTheFartherWhateverTheirOrder) {
  for (const bool near_first : {true, false}) {
    PictureScene scene;
    scene.positions.resize(3, 6);
    scene.positions << 0, 1, 0, 0.2, 1.2, 0.2,  //
        0, 0, 1, 0.2, 0.2, 1.2,                 //
        0, 0, 0, 1, 1, 1;                       // the second triangle is nearer (z = 1)
    scene.triangles = near_first ? std::vector<Triangle>{{3, 4, 5}, {0, 1, 2}}
                                 : std::vector<Triangle>{{0, 1, 2}, {3, 4, 5}};
    scene.triangle_values = near_first ? Eigen::Vector2d(1.0, 0.0) : Eigen::Vector2d(0.0, 1.0);
    PictureOptions options = plain_options(240);
    options.azimuth_degrees = -90;
    options.elevation_degrees = 90;
    options.flat_shading = true;
    const PictureImage image = render_picture(scene, options);
    // The point (0.4, 0.4) lies in both; the frame maps [0, 1.2]² to 92 % of 240 pixels.
    const double scale = 0.92 * 240 / 1.2;
    const int x = static_cast<int>(120 + scale * (0.4 - 0.6));
    const int y = static_cast<int>(120 - scale * (0.4 - 0.6));
    expect_colour(image.at(x, y), viridis(1.0), near_first ? "near listed first" : "near listed last");
  }
}

// A curve drawn at the back of a sphere is dashed: fewer of its pixels are coloured than of the
// same curve in front.
TEST(Picture, CurvesBehindTheSurfaceAreDashed) {
  const ProblemSetup setup = make_catalogue_problem("sphere");
  const CoveringResult covering = cover(setup, covering_methods().front(), {});
  ASSERT_TRUE(covering.summary.is_complete());
  auto red_pixels = [&](double z) {
    PictureScene scene;
    scene.positions = covering.mesh.points();
    scene.triangles = covering.mesh.triangles();
    PictureCurve circle;  // a circle of radius 0.5 at height z, inside or on the sphere's side
    circle.points.resize(3, 64);
    for (int i = 0; i < 64; ++i) {
      const double angle = 2 * M_PI * i / 64;
      const double r = std::sqrt(1.0 - z * z);
      circle.points.col(i) = Eigen::Vector3d(r * std::cos(angle), r * std::sin(angle), z);
    }
    circle.is_closed = true;
    circle.rgb = {1.0, 0.0, 0.0};
    scene.curves.push_back(circle);
    PictureOptions options = plain_options(300);
    options.azimuth_degrees = 0;
    options.elevation_degrees = 89;  // from above: the circle at z < 0 is behind the sphere
    const PictureImage image = render_picture(scene, options);
    long count = 0;
    for (const std::uint32_t pixel : image.pixels) {
      const auto rgb = rgb_of(pixel);
      count += rgb[0] > 200 && rgb[1] < 60 && rgb[2] < 60;
    }
    return count;
  };
  const long front = red_pixels(0.6);
  const long back = red_pixels(-0.6);
  EXPECT_GT(front, 300);
  EXPECT_LT(back, 0.5 * front);
  EXPECT_GT(back, 0);
}

TEST(Picture, SvgIsTheSameDrawingAndBadInputIsRefused) {
  PictureScene scene;
  scene.positions = Eigen::Matrix3d::Identity();
  scene.triangles = {{0, 1, 2}};
  const std::string dir = testing::temporary_directory("picture_svg");
  write_picture(dir + "/t.svg", scene, {});
  std::ifstream in(dir + "/t.svg");
  std::stringstream text;
  text << in.rdbuf();
  EXPECT_EQ(text.str().rfind("<?xml", 0), 0u);
  EXPECT_NE(text.str().find("<path"), std::string::npos);
  EXPECT_NE(text.str().find("</svg>"), std::string::npos);
  write_picture(dir + "/t.PNG", scene, {});
  std::ifstream png(dir + "/t.PNG", std::ios::binary);
  char signature[8] = {};
  png.read(signature, 8);
  EXPECT_EQ(std::string(signature + 1, 3), "PNG");

  EXPECT_THROW(write_picture(dir + "/t.jpg", scene, {}), InvalidArgument);
  PictureScene empty;
  empty.positions.resize(3, 0);
  EXPECT_THROW(render_picture(empty, {}), InvalidArgument);
  PictureScene bad_index = scene;
  bad_index.triangles = {{0, 1, 3}};
  EXPECT_THROW(render_picture(bad_index, {}), InvalidArgument);
  PictureScene bad_values = scene;
  bad_values.triangle_values = Eigen::Vector2d(1, 2);
  EXPECT_THROW(render_picture(bad_values, {}), InvalidArgument);
  PictureOptions tiny;
  tiny.width = 4;
  EXPECT_THROW(render_picture(scene, tiny), InvalidArgument);
}

// The closed box [0, a] × [0, b] × [0, c] as 12 triangles.
PictureScene box_scene(double a, double b, double c) {
  PictureScene scene;
  scene.positions.resize(3, 8);
  for (int v = 0; v < 8; ++v) {
    scene.positions.col(v) = Eigen::Vector3d((v & 1) ? a : 0, (v & 2) ? b : 0, (v & 4) ? c : 0);
  }
  scene.triangles = {{0, 2, 1}, {1, 2, 3}, {4, 5, 6}, {5, 7, 6}, {0, 1, 4}, {1, 5, 4},
                     {2, 6, 3}, {3, 6, 7}, {0, 4, 2}, {2, 4, 6}, {1, 3, 5}, {3, 7, 5}};
  return scene;
}

// Width over height of the non-background pixels of the box seen from the front (first axis
// to the right, third up).
double silhouette_aspect(const PictureScene& scene, PictureAspect aspect) {
  PictureOptions options = plain_options(400);
  options.azimuth_degrees = -90;
  options.elevation_degrees = 0;
  options.aspect = aspect;
  const PictureImage image = render_picture(scene, options);
  int left = image.width, right = -1, top = image.height, bottom = -1;
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) {
      if (image.at(x, y) != kWhite) {
        left = std::min(left, x), right = std::max(right, x);
        top = std::min(top, y), bottom = std::max(bottom, y);
      }
    }
  }
  return (right - left + 1.0) / (bottom - top + 1.0);
}

// Geometry keeps its shape (a box of 5 × 5 × 1, like a torus of R = 2, r = 0.5, seen from the
// side is five times wider than high); axes whose extents differ by more than a factor 10 (a
// continuation view) are each scaled to the same length unless equal scales are asked for.
TEST(Picture, AutomaticAspectKeepsGeometryAndStretchesUnrelatedAxes) {
  // Tolerance: the silhouette's height is 368/5 ≈ 74 pixels, known to ±1 pixel of antialiasing.
  EXPECT_NEAR(silhouette_aspect(box_scene(5, 5, 1), PictureAspect::Automatic), 5.0, 0.15);
  EXPECT_NEAR(silhouette_aspect(box_scene(5, 5, 1), PictureAspect::Box), 1.0, 0.03);
  EXPECT_NEAR(silhouette_aspect(box_scene(20, 20, 1), PictureAspect::Automatic), 1.0, 0.03);
  EXPECT_NEAR(silhouette_aspect(box_scene(20, 20, 1), PictureAspect::Equal), 20.0, 1.5);
}

// The SVG is well-formed XML (parsed by Python's xml.etree) with at least one <path> per
// triangle: every triangle is a vector shape, not a raster.
TEST(Picture, SvgParsesAsXmlWithAPathPerTriangle) {
  PictureScene scene;
  constexpr int cells = 4;
  scene.positions.resize(3, (cells + 1) * (cells + 1));
  for (int j = 0; j <= cells; ++j) {
    for (int i = 0; i <= cells; ++i) {
      scene.positions.col(j * (cells + 1) + i) = Eigen::Vector3d(i, j, 0.1 * i * j);
    }
  }
  for (int j = 0; j < cells; ++j) {
    for (int i = 0; i < cells; ++i) {
      const int v = j * (cells + 1) + i;
      scene.triangles.push_back({v, v + 1, v + cells + 2});
      scene.triangles.push_back({v, v + cells + 2, v + cells + 1});
    }
  }
  PictureOptions options;
  options.edges = false;
  const std::string path = testing::temporary_directory("picture_svg_xml") + "/grid.svg";
  write_picture(path, scene, options);
  if (std::system("/usr/bin/python3 -c 'import xml.etree.ElementTree' >/dev/null 2>&1") != 0) {
    GTEST_SKIP() << "no /usr/bin/python3 to parse the SVG with";
  }
  // Prints the root's name, its width and the number of <path> elements.
  const std::string script =
      R"(import sys, xml.etree.ElementTree as E; r = E.parse(sys.argv[1]).getroot(); )"
      R"(print(r.tag.split('}')[-1], r.get('width'), sum(1 for e in r.iter() if e.tag.endswith('}path'))))";
  const std::string command = "/usr/bin/python3 -c \"" + script + "\" '" + path + "' 2>&1";
  std::string output;
  FILE* pipe = popen(command.c_str(), "r");
  ASSERT_NE(pipe, nullptr);
  char buffer[512];
  for (std::size_t count; (count = std::fread(buffer, 1, sizeof buffer, pipe)) > 0;) {
    output.append(buffer, count);
  }
  ASSERT_EQ(pclose(pipe), 0) << output;
  std::istringstream fields(output);
  std::string root, width;
  int paths = 0;
  fields >> root >> width >> paths;
  EXPECT_EQ(root, "svg") << output;
  EXPECT_EQ(width, "800pt") << output;  // cairo sizes SVG in points, one per pixel
  EXPECT_GE(paths, static_cast<int>(scene.triangles.size())) << output;
}

TEST(Picture, NonFiniteCurvesAndMarkersAreRefused) {
  PictureScene scene;
  scene.positions = Eigen::Matrix3d::Identity();
  scene.triangles = {{0, 1, 2}};
  PictureScene bad_curve = scene;
  PictureCurve curve;
  curve.points = Eigen::Matrix3Xd::Zero(3, 2);
  curve.points(1, 1) = NAN;
  bad_curve.curves.push_back(curve);
  EXPECT_THROW(render_picture(bad_curve, {}), InvalidArgument);
  PictureScene bad_marker = scene;
  bad_marker.markers = Eigen::Matrix3Xd::Constant(3, 1, INFINITY);
  EXPECT_THROW(render_picture(bad_marker, {}), InvalidArgument);
}

}  // namespace
}  // namespace tessera
