// SPDX-License-Identifier: MIT
// Pictures (src/tessera/picture) held to geometry: a unit sphere seen orthographically covers
// π r² of its frame, a triangle shows the colour map's colour of its value, the nearer of two
// triangles hides the farther, curves behind the surface are dashed, SVG is the same drawing.
#include "tessera/picture/picture.h"

#include <gtest/gtest.h>

#include <algorithm>
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
  options.edges = PictureEdges::Off;
  options.axes = PictureAxes::Off;
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
  options.edges = PictureEdges::Off;
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

namespace tessera {
namespace {

// A grid of cells × cells squares over [0, a] × [0, b], two triangles each, at height
// c·(x/a)²·(y/b) (a curved sheet), with its heights as vertex values.
PictureScene sheet(int cells, double a, double b, double c) {
  PictureScene scene;
  scene.positions.resize(3, (cells + 1) * (cells + 1));
  for (int j = 0; j <= cells; ++j) {
    for (int i = 0; i <= cells; ++i) {
      const double x = a * i / cells, y = b * j / cells;
      scene.positions.col(j * (cells + 1) + i) =
          Eigen::Vector3d(x, y, c * (x / a) * (x / a) * (y / b) + 0.1 * c * (y / b));
    }
  }
  for (int j = 0; j < cells; ++j) {
    for (int i = 0; i < cells; ++i) {
      const int v = j * (cells + 1) + i;
      scene.triangles.push_back({v, v + 1, v + cells + 2});
      scene.triangles.push_back({v, v + cells + 2, v + cells + 1});
    }
  }
  scene.vertex_values = scene.positions.row(2).transpose();
  return scene;
}

std::string text_of(const std::string& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

bool intersect(const PictureLabel& a, const PictureLabel& b) {
  return a.x0 < b.x1 && b.x0 < a.x1 && a.y0 < b.y1 && b.y0 < a.y1;
}

// One triangle seen from above, unshaded, its corners valued 0, 0.5 and 1: a PNG interpolates
// the corners' colours linearly across it (cairo's mesh pattern of a triangle is barycentric),
// an SVG fills it with their mean.
TEST(Picture, GouraudShadingInterpolatesTheCornersColours) {
  PictureScene scene;
  scene.positions.resize(3, 3);
  scene.positions << 0, 1, 0,  //
      0, 0, 1,                 //
      0, 0, 0;
  scene.triangles = {{0, 1, 2}};
  scene.vertex_values = Eigen::Vector3d(0.0, 0.5, 1.0);
  PictureOptions options = plain_options(200);
  options.azimuth_degrees = -90;  // x to the right, y up
  options.elevation_degrees = 90;
  options.flat_shading = true;
  const PictureImage image = render_picture(scene, options);
  // The unit square around the triangle fills 92 % of 200 pixels about the centre (100, 100).
  auto at = [&](const Eigen::Vector3d& barycentric) {
    const Eigen::Vector2d p =
        barycentric(1) * Eigen::Vector2d(1, 0) + barycentric(2) * Eigen::Vector2d(0, 1);
    return image.at(static_cast<int>(100 + 184 * (p(0) - 0.5)),
                    static_cast<int>(100 - 184 * (p(1) - 0.5)));
  };
  for (const Eigen::Vector3d& barycentric :
       {Eigen::Vector3d(Eigen::Vector3d(1, 1, 1) / 3), Eigen::Vector3d(0.8, 0.1, 0.1),
        Eigen::Vector3d(0.1, 0.8, 0.1), Eigen::Vector3d(0.1, 0.1, 0.8),
        Eigen::Vector3d(0.45, 0.45, 0.1)}) {
    std::array<double, 3> expected = {0, 0, 0};
    for (int k = 0; k < 3; ++k) {
      const auto corner = viridis(0.5 * k);
      for (std::size_t c = 0; c < 3; ++c) {
        expected[c] += barycentric(k) * corner[c];
      }
    }
    // Tolerance: a pixel's centre lies within 0.7 pixels (0.004 of the triangle) of the
    // point asked for, which moves the colour by at most 1 of 255 here.
    const auto got = rgb_of(at(barycentric));
    for (std::size_t c = 0; c < 3; ++c) {
      EXPECT_NEAR(got[c], 255.0 * expected[c], 2.5) << barycentric.transpose() << ", channel " << c;
    }
  }
  // The SVG's triangle: one colour, the mean of the corners'.
  const std::string path = testing::temporary_directory("picture_gouraud") + "/t.svg";
  write_picture(path, scene, options);
  const std::string svg = text_of(path);
  const auto found = svg.find("color=\"#");
  ASSERT_NE(found, std::string::npos) << svg;
  const long hex = std::strtol(svg.substr(found + 8, 6).c_str(), nullptr, 16);
  const std::array<double, 3> mean = {(viridis(0)[0] + viridis(0.5)[0] + viridis(1)[0]) / 3,
                                      (viridis(0)[1] + viridis(0.5)[1] + viridis(1)[1]) / 3,
                                      (viridis(0)[2] + viridis(0.5)[2] + viridis(1)[2]) / 3};
  EXPECT_NEAR((hex >> 16) & 0xFF, 255 * mean[0], 1.0);
  EXPECT_NEAR((hex >> 8) & 0xFF, 255 * mean[1], 1.0);
  EXPECT_NEAR(hex & 0xFF, 255 * mean[2], 1.0);
}

// An SVG of 5000 triangles: every triangle a vector shape, in a few hundred kilobytes (cairo's
// own SVG of it was 1.6 MB: 330 bytes a triangle).
TEST(Picture, SvgOfFiveThousandTrianglesStaysSmall) {
  const PictureScene scene = sheet(50, 1.0, 1.0, 0.5);
  ASSERT_EQ(scene.triangles.size(), 5000u);
  const std::string dir = testing::temporary_directory("picture_svg_size");
  for (const PictureEdges edges : {PictureEdges::Off, PictureEdges::On}) {
    PictureOptions options;
    options.width = 600;
    options.height = 450;
    options.edges = edges;
    const std::string path = dir + (edges == PictureEdges::On ? "/edges.svg" : "/plain.svg");
    write_picture(path, scene, options);
    const std::string svg = text_of(path);
    // Bounds: 80 and 110 bytes a triangle (measured 59 and 75 with cairo 1.16).
    EXPECT_LT(svg.size(), edges == PictureEdges::On ? 550'000u : 400'000u);
    const std::string body = svg.substr(svg.find("</defs>"));
    EXPECT_GE(std::count(body.begin(), body.end(), 'M'), 5000);  // a subpath per triangle
    EXPECT_EQ(svg.find("<image"), std::string::npos);            // nothing rasterised
  }
}

// A continuation view (axes of unrelated units, scaled apart) gets ticked axes named by its
// coordinates; at several sizes and from several directions no label overlaps another or leaves
// the picture, and the tick labels are round numbers.
TEST(Picture, ContinuationViewsHaveTickedAxesNamedByTheirCoordinates) {
  PictureScene scene = sheet(12, 10.0, 0.3, 20.0);  // extents 10, 0.3, 22: scaled apart
  scene.axis_names = {"lambda", "epsilon", "max_u"};
  scene.value_label = "max_u";
  for (const auto& [width, height] :
       {std::pair{600, 450}, std::pair{320, 240}, std::pair{800, 600}}) {
    for (const auto& [azimuth, elevation] :
         {std::pair{-60.0, 30.0}, std::pair{210.0, 25.0}, std::pair{45.0, 60.0},
          std::pair{-90.0, 90.0}, std::pair{30.0, 5.0}}) {
      PictureOptions options;
      options.width = width;
      options.height = height;
      options.azimuth_degrees = azimuth;
      options.elevation_degrees = elevation;
      const PictureLayout layout = picture_layout(scene, options);
      const std::string where = std::to_string(width) + "x" + std::to_string(height) + " from (" +
                                std::to_string(azimuth) + ", " + std::to_string(elevation) + ")";
      EXPECT_EQ(layout.axes, PictureAxes::Ticked) << where;
      int named = 0;
      for (const PictureLabel& label : layout.labels) {
        EXPECT_GE(label.x0, 0.0) << label.text << " " << where;
        EXPECT_LE(label.x1, width) << label.text << " " << where;
        EXPECT_GE(label.y0, 0.0) << label.text << " " << where;
        EXPECT_LE(label.y1, height) << label.text << " " << where;
        named += label.text == "lambda" || label.text == "epsilon" || label.text == "max_u";
        char* end = nullptr;
        const double value = std::strtod(label.text.c_str(), &end);
        if (*end == '\0') {  // a number: a round one, in few digits
          EXPECT_LE(label.text.size(), 4u) << label.text << " " << where;
          EXPECT_NEAR(value * 100, std::round(value * 100), 1e-9) << label.text;
        }
      }
      // The seen axes' names and the colour bar's title (from straight above the third axis
      // is seen end-on and left out).
      EXPECT_EQ(named, elevation == 90.0 ? 3 : 4) << where;
      for (std::size_t i = 0; i < layout.labels.size(); ++i) {
        for (std::size_t j = i + 1; j < layout.labels.size(); ++j) {
          EXPECT_FALSE(intersect(layout.labels[i], layout.labels[j]))
              << layout.labels[i].text << " and " << layout.labels[j].text << " " << where;
        }
      }
    }
  }
  const std::string path = testing::temporary_directory("picture_axes") + "/view.svg";
  write_picture(path, scene, {});
  EXPECT_NE(text_of(path).find("<desc>axes: lambda, epsilon, max_u\ncolour: max_u</desc>"),
            std::string::npos);
}

// Geometry keeps the triad; its long names stay inside the picture (pleat_folds.png cut
// "lambda" to "lamb" at the right edge) and apart.
TEST(Picture, TheTriadsNamesStayInsideThePictureAndApart) {
  PictureScene scene = sheet(8, 1.0, 1.0, 0.5);
  scene.axis_names = {"lambda", "epsilon", "max_u"};
  for (const double azimuth : {-60.0, 0.0, 90.0, 150.0, 235.0}) {
    PictureOptions options;
    options.width = 400;
    options.height = 300;
    options.azimuth_degrees = azimuth;
    const PictureLayout layout = picture_layout(scene, options);
    ASSERT_EQ(layout.axes, PictureAxes::Triad);
    for (std::size_t i = 0; i < layout.labels.size(); ++i) {
      EXPECT_LE(layout.labels[i].x1, 400.0) << layout.labels[i].text << " at " << azimuth;
      for (std::size_t j = i + 1; j < layout.labels.size(); ++j) {
        EXPECT_FALSE(intersect(layout.labels[i], layout.labels[j]))
            << layout.labels[i].text << " and " << layout.labels[j].text << " at " << azimuth;
      }
    }
  }
}

// The colour bar is labelled at round values with few digits, not at the data's extremes
// (0.07047, 19.93 and 2.127e-06 before).
TEST(Picture, ColourBarLabelsAreRoundValues) {
  auto bar_labels = [](double low, double high) {
    PictureScene scene = sheet(4, 1.0, 1.0, 1.0);
    scene.vertex_values = Eigen::VectorXd::LinSpaced(scene.positions.cols(), low, high);
    scene.value_label = "value";
    PictureOptions options;
    options.axes = PictureAxes::Off;
    std::vector<std::string> texts;
    for (const PictureLabel& label : picture_layout(scene, options).labels) {
      if (label.text != "value") {
        texts.push_back(label.text);
      }
    }
    return texts;
  };
  // Every label a multiple of its step, the step 1, 2 or 5 × 10^k; at least four labels.
  for (const auto& [low, high] : {std::pair{0.07047, 19.93}, std::pair{0.02254, 0.9988},
                                  std::pair{-1.474, 1.468}, std::pair{0.0, 2.127e-6}}) {
    const auto labels = bar_labels(low, high);
    ASSERT_GE(labels.size(), 4u) << low << " " << high;
    const double step =
        std::strtod(labels[1].c_str(), nullptr) - std::strtod(labels[0].c_str(), nullptr);
    const double mantissa = step / std::pow(10.0, std::floor(std::log10(step) + 1e-9));
    EXPECT_TRUE(std::abs(mantissa - 1) < 1e-6 || std::abs(mantissa - 2) < 1e-6 ||
                std::abs(mantissa - 5) < 1e-6)
        << labels[0] << ", " << labels[1];
    for (const std::string& label : labels) {
      const double value = std::strtod(label.c_str(), nullptr);
      EXPECT_NEAR(value / step, std::round(value / step), 1e-6) << label;
      EXPECT_GE(value, low);
      EXPECT_LE(value, high);
      EXPECT_LE(label.size(), 6u) << label;  // "0.8", "15", "-0.5", "1.5e-6"
    }
  }
}

// Edges by density: every edge on a coarse mesh, none on a fine one (their lines would darken
// it), as asked when asked.
TEST(Picture, AutomaticEdgesAppearWhereTrianglesAreLargeOnTheScreen) {
  PictureOptions options;
  options.width = 400;
  options.height = 300;
  EXPECT_EQ(picture_layout(sheet(4, 1.0, 1.0, 0.5), options).edge_strength, 1.0);
  EXPECT_EQ(picture_layout(sheet(100, 1.0, 1.0, 0.5), options).edge_strength, 0.0);
  const double middle = picture_layout(sheet(25, 1.0, 1.0, 0.5), options).edge_strength;
  EXPECT_GT(middle, 0.0);
  EXPECT_LT(middle, 1.0);
  options.edges = PictureEdges::On;
  EXPECT_EQ(picture_layout(sheet(100, 1.0, 1.0, 0.5), options).edge_strength, 1.0);
  options.edges = PictureEdges::Off;
  EXPECT_EQ(picture_layout(sheet(4, 1.0, 1.0, 0.5), options).edge_strength, 0.0);
}

}  // namespace
}  // namespace tessera
