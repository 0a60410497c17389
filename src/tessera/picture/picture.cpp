// SPDX-License-Identifier: MIT
#include "tessera/picture/picture.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <numeric>

#include "tessera/core/error.h"
#include "tessera/geometry/mesh_topology.h"
#include "tessera/geometry/planar.h"
#include "tessera/io/file_names.h"
#include "tessera/picture/detail/cairo_drawing.h"

namespace tessera {

namespace {

using picture_detail::LegendEntry;

constexpr double kPi = 3.14159265358979323846;
constexpr int kColourBarWidth = 110;  // pixels kept on the right for the bar and its labels
constexpr int kTitleHeight = 24;

void check_scene(const PictureScene& scene, const PictureOptions& options) {
  TESSERA_CHECK(!scene.triangles.empty(), "a picture needs at least one triangle, the mesh has none");
  const auto vertex_count = scene.positions.cols();
  for (const Triangle& triangle : scene.triangles) {
    for (const int v : triangle) {
      TESSERA_CHECK(v >= 0 && v < vertex_count, "picture: a triangle uses vertex "
                                                    << v << ", the scene has " << vertex_count);
    }
  }
  TESSERA_CHECK(scene.positions.allFinite(), "picture: a vertex position is not finite");
  for (std::size_t c = 0; c < scene.curves.size(); ++c) {
    TESSERA_CHECK(scene.curves[c].points.allFinite(),
                  "picture: curve " << c << " has a point that is not finite");
  }
  TESSERA_CHECK(scene.markers.allFinite(), "picture: a marker is not finite");
  TESSERA_CHECK(scene.marker_kinds.empty() ||
                    scene.marker_kinds.size() == static_cast<std::size_t>(scene.markers.cols()),
                "picture: " << scene.marker_kinds.size() << " marker kinds for "
                            << scene.markers.cols() << " markers");
  const bool has_categories =
      !scene.vertex_categories.empty() || !scene.triangle_categories.empty();
  TESSERA_CHECK(scene.vertex_categories.empty() || scene.triangle_categories.empty(),
                "picture: categories per vertex and per triangle at once; give one");
  TESSERA_CHECK(!has_categories || scene.triangle_values.size() == 0,
                "picture: values and categories at once; colour by one");
  TESSERA_CHECK(scene.vertex_categories.empty() ||
                    scene.vertex_categories.size() == static_cast<std::size_t>(vertex_count),
                "picture: " << scene.vertex_categories.size() << " vertex categories for "
                            << vertex_count << " vertices");
  TESSERA_CHECK(scene.triangle_categories.empty() ||
                    scene.triangle_categories.size() == scene.triangles.size(),
                "picture: " << scene.triangle_categories.size() << " triangle categories for "
                            << scene.triangles.size() << " triangles");
  for (const auto* categories : {&scene.vertex_categories, &scene.triangle_categories}) {
    for (const int category : *categories) {
      TESSERA_CHECK(category >= 0 && category < static_cast<int>(scene.categories.size()),
                    "picture: category " << category << " of " << scene.categories.size()
                                         << " (PictureScene::categories)");
    }
  }
  TESSERA_CHECK(scene.triangle_values.size() == 0 ||
                    scene.triangle_values.size() == static_cast<Eigen::Index>(scene.triangles.size()),
                "picture: " << scene.triangle_values.size() << " values for "
                            << scene.triangles.size() << " triangles");
  TESSERA_CHECK(options.width >= 16 && options.width <= 20000 && options.height >= 16 &&
                    options.height <= 20000,
                "picture size " << options.width << "x" << options.height
                                << " must be between 16 and 20000 pixels each way");
  TESSERA_CHECK(std::isfinite(options.zoom) && options.zoom > 0,
                "picture zoom " << options.zoom << " must be finite and > 0");
  TESSERA_CHECK(std::isfinite(options.azimuth_degrees) && std::isfinite(options.elevation_degrees),
                "picture: azimuth and elevation must be finite");
}

// The map from scene coordinates to pixels (and depth): the aspect's scaling, the camera's
// rotation (and perspective) and the fit to the frame.
class Camera {
 public:
  Camera(const PictureScene& scene, const PictureOptions& options, double frame_x0,
         double frame_y0, double frame_width, double frame_height)
      : perspective_(options.perspective) {
    const Eigen::Vector3d lower = scene.positions.rowwise().minCoeff();
    const Eigen::Vector3d upper = scene.positions.rowwise().maxCoeff();
    centre_ = 0.5 * (lower + upper);
    const Eigen::Vector3d extent = upper - lower;
    const double largest = std::max(extent.maxCoeff(), 1e-300);
    double smallest = largest;
    for (int k = 0; k < 3; ++k) {
      if (extent(k) > 1e-12 * largest) {
        smallest = std::min(smallest, extent(k));
      }
    }
    const bool is_box =
        options.aspect == PictureAspect::Box ||
        (options.aspect == PictureAspect::Automatic && largest > kMaxEqualAspectRatio * smallest);
    for (int k = 0; k < 3; ++k) {
      scale_(k) = is_box && extent(k) > 1e-12 * largest ? 1.0 / extent(k) : 1.0 / largest;
    }
    const double a = options.azimuth_degrees * kPi / 180.0;
    const double e = options.elevation_degrees * kPi / 180.0;
    toward_eye_ = Eigen::Vector3d(std::cos(e) * std::cos(a), std::cos(e) * std::sin(a), std::sin(e));
    right_ = Eigen::Vector3d(-std::sin(a), std::cos(a), 0.0);
    up_ = toward_eye_.cross(right_);
    // Fit: the projected extent of everything drawn fills 92 % of the frame at zoom 1.
    Eigen::Vector2d low(INFINITY, INFINITY), high(-INFINITY, -INFINITY);
    auto include = [&](const Eigen::Vector3d& p) {
      const Eigen::Vector3d s = screen(p);
      low = low.cwiseMin(s.head<2>());
      high = high.cwiseMax(s.head<2>());
    };
    for (Eigen::Index v = 0; v < scene.positions.cols(); ++v) {
      include(scene.positions.col(v));
    }
    for (const auto& curve : scene.curves) {
      for (Eigen::Index i = 0; i < curve.points.cols(); ++i) {
        include(curve.points.col(i));
      }
    }
    const Eigen::Vector2d range = (high - low).cwiseMax(1e-12);
    pixels_per_unit_ = options.zoom * 0.92 *
                       std::min(frame_width / range(0), frame_height / range(1));
    middle_ = 0.5 * (low + high);
    frame_centre_ = Eigen::Vector2d(frame_x0 + 0.5 * frame_width, frame_y0 + 0.5 * frame_height);
  }

  // (right, up, depth toward the eye) of a scene point, before the fit to the frame.
  Eigen::Vector3d screen(const Eigen::Vector3d& p) const {
    const Eigen::Vector3d q = scale_.cwiseProduct(p - centre_);
    Eigen::Vector3d s(q.dot(right_), q.dot(up_), q.dot(toward_eye_));
    if (perspective_) {
      // The eye at 2.5 units (the normalised scene is within √3/2 of its centre).
      constexpr double eye = 2.5;
      const double factor = eye / (eye - s(2));
      s(0) *= factor;
      s(1) *= factor;
    }
    return s;
  }
  // Pixel coordinates (x right, y down).
  Eigen::Vector2d pixel(const Eigen::Vector3d& p) const {
    const Eigen::Vector3d s = screen(p);
    return {frame_centre_(0) + pixels_per_unit_ * (s(0) - middle_(0)),
            frame_centre_(1) - pixels_per_unit_ * (s(1) - middle_(1))};
  }
  double depth(const Eigen::Vector3d& p) const { return screen(p)(2); }
  // The unit normal of a triangle in the scaled space (what the eye sees).
  double facing(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c) const {
    const Eigen::Vector3d qa = scale_.cwiseProduct(a), qb = scale_.cwiseProduct(b),
                          qc = scale_.cwiseProduct(c);
    const Eigen::Vector3d normal = (qb - qa).cross(qc - qa);
    const double norm = normal.norm();
    return norm > 0 ? std::abs(normal.dot(toward_eye_)) / norm : 0.0;
  }
  // Screen directions of the three axes (for the triad).
  Eigen::Vector2d axis_direction(int k) const {
    Eigen::Vector3d e = Eigen::Vector3d::Zero();
    e(k) = 1.0;
    return {e.dot(right_), e.dot(up_)};
  }

 private:
  bool perspective_;
  Eigen::Vector3d centre_;
  Eigen::Vector3d scale_;
  Eigen::Vector3d toward_eye_, right_, up_;
  Eigen::Vector2d middle_;
  Eigen::Vector2d frame_centre_;
  double pixels_per_unit_ = 1.0;
};

// The triangles on the screen, bucketed by a grid of cells, to ask whether a point is covered
// by a triangle nearer to the eye.
class ScreenIndex {
 public:
  ScreenIndex(const PictureScene& scene, const Camera& camera, int width, int height)
      : scene_(scene), camera_(camera), width_(width), height_(height), cells_(kCells * kCells) {
    for (std::size_t t = 0; t < scene.triangles.size(); ++t) {
      Eigen::Vector2d low(INFINITY, INFINITY), high(-INFINITY, -INFINITY);
      for (const int v : scene.triangles[t]) {
        const Eigen::Vector2d p = camera.pixel(scene.positions.col(v));
        low = low.cwiseMin(p);
        high = high.cwiseMax(p);
      }
      const int x0 = cell_x(low(0)), x1 = cell_x(high(0)), y0 = cell_y(low(1)), y1 = cell_y(high(1));
      for (int y = y0; y <= y1; ++y) {
        for (int x = x0; x <= x1; ++x) {
          cells_[static_cast<std::size_t>(y * kCells + x)].push_back(static_cast<int>(t));
        }
      }
    }
  }

  bool is_covered(const Eigen::Vector3d& point) const {
    const Eigen::Vector2d p = camera_.pixel(point);
    const double depth = camera_.depth(point);
    constexpr double margin = 0.01;  // of the normalised scene (size about 1)
    for (const int t : cells_[static_cast<std::size_t>(cell_y(p(1)) * kCells + cell_x(p(0)))]) {
      const auto& [a, b, c] = scene_.triangles[static_cast<std::size_t>(t)];
      const Eigen::Vector2d pa = camera_.pixel(scene_.positions.col(a));
      const Eigen::Vector2d pb = camera_.pixel(scene_.positions.col(b));
      const Eigen::Vector2d pc = camera_.pixel(scene_.positions.col(c));
      const double area = cross(pb - pa, pc - pa);
      if (std::abs(area) < 1e-12) {
        continue;
      }
      const double u = cross(pb - p, pc - p) / area;
      const double v = cross(pc - p, pa - p) / area;
      const double w = 1.0 - u - v;
      if (u < 0 || v < 0 || w < 0) {
        continue;
      }
      const double triangle_depth = u * camera_.depth(scene_.positions.col(a)) +
                                    v * camera_.depth(scene_.positions.col(b)) +
                                    w * camera_.depth(scene_.positions.col(c));
      if (triangle_depth > depth + margin) {
        return true;
      }
    }
    return false;
  }

 private:
  static constexpr int kCells = 64;
  int cell_x(double x) const {
    return std::clamp(static_cast<int>(x / width_ * kCells), 0, kCells - 1);
  }
  int cell_y(double y) const {
    return std::clamp(static_cast<int>(y / height_ * kCells), 0, kCells - 1);
  }
  const PictureScene& scene_;
  const Camera& camera_;
  double width_, height_;
  std::vector<std::vector<int>> cells_;
};

void stroke_curve(cairo_t* cr, const PictureCurve& curve, bool is_seen) {
  cairo_set_source_rgb(cr, curve.rgb[0], curve.rgb[1], curve.rgb[2]);
  if (is_seen) {
    cairo_set_line_width(cr, curve.width);
    picture_detail::set_dash(cr, curve.dash, curve.width);
  } else {
    const double dash[] = {4.0, 3.0};
    cairo_set_line_width(cr, 0.6 * curve.width);
    cairo_set_dash(cr, dash, 2, 0.0);
    cairo_set_line_cap(cr, CAIRO_LINE_CAP_BUTT);
  }
  cairo_stroke(cr);
  picture_detail::set_dash(cr, CurveDash::Solid, curve.width);
}

bool has_categories(const PictureScene& scene) {
  return !scene.vertex_categories.empty() || !scene.triangle_categories.empty();
}

// The legend's entries: the categories (of a categorical scene), the labelled curves, the kinds
// of markers.
std::vector<LegendEntry> legend_entries(const PictureScene& scene) {
  std::vector<LegendEntry> entries;
  if (has_categories(scene)) {
    for (const auto& category : scene.categories) {
      entries.push_back({LegendEntry::Sample::Swatch, category.label, category.rgb});
    }
  }
  std::vector<CurveStyle> styles;
  for (const auto& curve : scene.curves) {
    styles.push_back({curve.rgb, curve.width, curve.dash, curve.label});
  }
  picture_detail::append_curve_entries(styles, entries);
  if (!scene.marker_kinds.empty()) {
    picture_detail::append_point_entries(scene.marker_kinds, entries);
  }
  return entries;
}

// A colour bar label. The inner ticks are low + i·(high − low)/4; where the range straddles 0
// one of them is 0 up to rounding and would print as "-1.216e-05", so an inner tick below a
// thousandth of the range prints as 0. The end ticks are the data's extremes, printed as they are.
std::string label_of(double value, double range, bool is_inner) {
  if (is_inner && std::abs(value) < 1e-3 * range) {
    value = 0.0;
  }
  char text[32];
  std::snprintf(text, sizeof text, "%.4g", value);
  return text;
}

void draw(cairo_t* cr, const PictureScene& scene, const PictureOptions& options) {
  const bool has_values = scene.triangle_values.size() > 0;
  const bool has_bar = has_values && options.colour_bar;
  const bool is_categorical = has_categories(scene);
  const std::vector<LegendEntry> legend =
      options.legend ? legend_entries(scene) : std::vector<LegendEntry>();
  cairo_select_font_face(cr, "sans-serif", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
  cairo_set_font_size(cr, 12.0);
  // The right panel: the colour bar, or the legend of a categorical scene in its place.
  const bool has_side_legend = is_categorical && !legend.empty();
  const double panel_width =
      has_bar ? kColourBarWidth
      : has_side_legend
          ? std::min(0.4 * options.width, picture_detail::legend_width(cr, legend) + 12.0)
          : 0.0;
  const double frame_width = options.width - panel_width;
  const double top = options.title.empty() ? 0.0 : kTitleHeight;
  const Camera camera(scene, options, 0.0, top, frame_width, options.height - top);

  cairo_set_source_rgb(cr, options.background_rgb[0], options.background_rgb[1],
                       options.background_rgb[2]);
  cairo_paint(cr);

  double low = 0.0, high = 1.0;
  if (has_values) {
    low = INFINITY;
    high = -INFINITY;
    for (Eigen::Index t = 0; t < scene.triangle_values.size(); ++t) {
      const double value = scene.triangle_values(t);
      if (std::isfinite(value)) {
        low = std::min(low, value);
        high = std::max(high, value);
      }
    }
    if (!(low <= high)) {
      low = 0.0, high = 1.0;
    }
  }
  // The category of corner k of triangle t, or -1 without categories.
  auto category_of = [&](std::size_t t, int k) -> int {
    if (!scene.triangle_categories.empty()) {
      return scene.triangle_categories[t];
    }
    if (!scene.vertex_categories.empty()) {
      return scene.vertex_categories[static_cast<std::size_t>(
          scene.triangles[t][static_cast<std::size_t>(k)])];
    }
    return -1;
  };
  auto colour_of = [&](std::size_t t) -> std::array<double, 3> {
    if (is_categorical) {
      return scene.categories[static_cast<std::size_t>(category_of(t, 0))].rgb;
    }
    if (!has_values) {
      return options.surface_rgb;
    }
    const double value = scene.triangle_values(static_cast<Eigen::Index>(t));
    if (!std::isfinite(value)) {
      return {0.5, 0.5, 0.5};
    }
    return viridis(high > low ? (value - low) / (high - low) : 0.5);
  };

  // Painter's algorithm: far triangles first, by the depth of the centroid. Correct where
  // triangles do not interpenetrate and are small against the distance between sheets, which
  // holds for the fine meshes of smooth surfaces; cyclic overlaps are not split.
  std::vector<int> order(scene.triangles.size());
  std::iota(order.begin(), order.end(), 0);
  std::vector<double> depth(scene.triangles.size());
  for (std::size_t t = 0; t < scene.triangles.size(); ++t) {
    const auto& [a, b, c] = scene.triangles[t];
    depth[t] = camera.depth((scene.positions.col(a) + scene.positions.col(b) +
                             scene.positions.col(c)) / 3.0);
  }
  std::stable_sort(order.begin(), order.end(), [&](int s, int t) {
    return depth[static_cast<std::size_t>(s)] < depth[static_cast<std::size_t>(t)];
  });
  cairo_set_line_join(cr, CAIRO_LINE_JOIN_ROUND);
  for (const int t : order) {
    const auto& [a, b, c] = scene.triangles[static_cast<std::size_t>(t)];
    const Eigen::Vector2d pa = camera.pixel(scene.positions.col(a));
    const Eigen::Vector2d pb = camera.pixel(scene.positions.col(b));
    const Eigen::Vector2d pc = camera.pixel(scene.positions.col(c));
    cairo_move_to(cr, pa(0), pa(1));
    cairo_line_to(cr, pb(0), pb(1));
    cairo_line_to(cr, pc(0), pc(1));
    cairo_close_path(cr);
    // Lambert shading, two-sided, light at the eye; the ambient part keeps grazing faces visible.
    const double light = options.flat_shading ? 1.0 : 0.35 + 0.65 * camera.facing(scene.positions.col(a), scene.positions.col(b),
                                                     scene.positions.col(c));
    auto rgb = colour_of(static_cast<std::size_t>(t));
    const int c0 = category_of(static_cast<std::size_t>(t), 0);
    const int c1 = category_of(static_cast<std::size_t>(t), 1);
    const int c2 = category_of(static_cast<std::size_t>(t), 2);
    if (c0 != c1 || c1 != c2) {
      // Corners of different categories: the part of each corner (the corner, the midpoints of
      // its two edges, the centroid) in its colour, each stroked thinly in its own colour to
      // close the seams between parts; the edge below is stroked in the parts' mean shade.
      cairo_new_path(cr);
      const Eigen::Vector2d corners[3] = {pa, pb, pc};
      const Eigen::Vector2d centroid = (pa + pb + pc) / 3.0;
      std::array<double, 3> mean = {0.0, 0.0, 0.0};
      for (int k = 0; k < 3; ++k) {
        const Eigen::Vector2d& corner = corners[k];
        const Eigen::Vector2d next = 0.5 * (corner + corners[(k + 1) % 3]);
        const Eigen::Vector2d previous = 0.5 * (corner + corners[(k + 2) % 3]);
        cairo_move_to(cr, corner(0), corner(1));
        cairo_line_to(cr, next(0), next(1));
        cairo_line_to(cr, centroid(0), centroid(1));
        cairo_line_to(cr, previous(0), previous(1));
        cairo_close_path(cr);
        const auto& part =
            scene.categories[static_cast<std::size_t>(category_of(static_cast<std::size_t>(t), k))]
                .rgb;
        cairo_set_source_rgb(cr, light * part[0], light * part[1], light * part[2]);
        cairo_fill_preserve(cr);
        cairo_set_line_width(cr, 0.8);
        cairo_stroke(cr);
        for (int c = 0; c < 3; ++c) {
          mean[static_cast<std::size_t>(c)] += part[static_cast<std::size_t>(c)] / 3.0;
        }
      }
      rgb = mean;
      cairo_move_to(cr, pa(0), pa(1));
      cairo_line_to(cr, pb(0), pb(1));
      cairo_line_to(cr, pc(0), pc(1));
      cairo_close_path(cr);
      if (!options.edges) {
        cairo_new_path(cr);
        continue;
      }
    } else {
      cairo_set_source_rgb(cr, light * rgb[0], light * rgb[1], light * rgb[2]);
      cairo_fill_preserve(cr);
    }
    // Antialiased fills of neighbours leave a faint seam along shared edges; a thin stroke in
    // the fill colour closes it (or, with edges on, the edge itself in a darker shade). Not
    // CAIRO_ANTIALIAS_NONE: jagged silhouettes in PNG, and SVG viewers antialias anyway.
    if (options.edges) {
      cairo_set_source_rgb(cr, 0.45 * light * rgb[0], 0.45 * light * rgb[1], 0.45 * light * rgb[2]);
      cairo_set_line_width(cr, 0.5);
    } else {
      cairo_set_line_width(cr, 0.8);
    }
    cairo_stroke(cr);
  }

  // Curves over the surface, drawn last: solid where they are seen, dashed where a triangle
  // nearer to the eye covers them (a curve on the surface is level with its own triangles, so
  // only triangles nearer by more than 1 % of the scene's size count).
  const ScreenIndex index(scene, camera, options.width, options.height);
  for (const PictureCurve& curve : scene.curves) {
    const Eigen::Index m = curve.points.cols();
    const Eigen::Index segments = curve.is_closed ? m : m - 1;
    int previous = -1;  // visibility of the path being built: 1 seen, 0 hidden
    for (Eigen::Index i = 0; i < segments; ++i) {
      const Eigen::Vector3d a = curve.points.col(i);
      const Eigen::Vector3d b = curve.points.col((i + 1) % m);
      const int seen = index.is_covered(0.5 * (a + b)) ? 0 : 1;
      const Eigen::Vector2d pa = camera.pixel(a);
      const Eigen::Vector2d pb = camera.pixel(b);
      if (seen != previous) {
        if (previous >= 0) {
          stroke_curve(cr, curve, previous == 1);
        }
        cairo_move_to(cr, pa(0), pa(1));
        previous = seen;
      }
      cairo_line_to(cr, pb(0), pb(1));
    }
    if (previous >= 0) {
      stroke_curve(cr, curve, previous == 1);
    }
  }
  for (Eigen::Index i = 0; i < scene.markers.cols(); ++i) {
    const Eigen::Vector2d p = camera.pixel(scene.markers.col(i));
    picture_detail::draw_marker(cr,
                                scene.marker_kinds.empty()
                                    ? PointKind::Generic
                                    : scene.marker_kinds[static_cast<std::size_t>(i)],
                                p(0), p(1));
  }

  cairo_set_source_rgb(cr, 0.1, 0.1, 0.1);
  if (!options.title.empty()) {
    cairo_move_to(cr, 8.0, 17.0);
    cairo_show_text(cr, options.title.c_str());
  }
  if (options.axes) {
    // A triad at the lower left: each axis's screen direction, 28 pixels long, named.
    // Beneath the colour bar where there is one (the surface fills the frame), else at the
    // lower left.
    const Eigen::Vector2d origin(panel_width > 0 ? options.width - panel_width / 2.0 : 45.0,
                                 options.height - 45.0);
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector2d direction = camera.axis_direction(k);
      const Eigen::Vector2d end(origin(0) + 28.0 * direction(0), origin(1) - 28.0 * direction(1));
      cairo_move_to(cr, origin(0), origin(1));
      cairo_line_to(cr, end(0), end(1));
      cairo_set_line_width(cr, 1.2);
      cairo_stroke(cr);
      // The name beyond the axis's end, so that the three names stay apart, moved left where
      // it would leave the frame (long names such as "lambda" under the colour bar).
      const char* name = scene.axis_names[static_cast<std::size_t>(k)].c_str();
      cairo_text_extents_t extents;
      cairo_text_extents(cr, name, &extents);
      const double x = std::clamp(origin(0) + 36.0 * direction(0) - 4.0, 2.0,
                                  std::max(2.0, options.width - 3.0 - extents.x_advance));
      cairo_move_to(cr, x, origin(1) - 36.0 * direction(1) + 4.0);
      cairo_show_text(cr, name);
    }
  }
  if (has_bar) {
    // The colour bar: 64 bands from the smallest value (bottom) to the largest.
    const double x0 = options.width - kColourBarWidth + 16.0;
    const double y0 = top + 30.0;
    const double bar_height = options.height - top - (options.axes ? 130.0 : 60.0);
    constexpr int bands = 64;
    for (int i = 0; i < bands; ++i) {
      const auto rgb = viridis((i + 0.5) / bands);
      cairo_set_source_rgb(cr, rgb[0], rgb[1], rgb[2]);
      cairo_rectangle(cr, x0, y0 + bar_height * (1.0 - (i + 1.0) / bands), 18.0,
                      bar_height / bands + 0.5);
      cairo_fill(cr);
    }
    cairo_set_source_rgb(cr, 0.1, 0.1, 0.1);
    for (int i = 0; i <= 4; ++i) {
      const double y = y0 + bar_height * (1.0 - i / 4.0);
      cairo_move_to(cr, x0 + 22.0, y + 4.0);
      const double value = i == 4 ? high : low + (high - low) * i / 4.0;
      cairo_show_text(cr, label_of(value, high - low, i > 0 && i < 4).c_str());
    }
    cairo_move_to(cr, x0 - 8.0, y0 - 12.0);
    cairo_show_text(cr, scene.value_label.c_str());
  }
  if (has_side_legend) {
    if (!scene.value_label.empty()) {
      cairo_set_source_rgb(cr, 0.1, 0.1, 0.1);
      cairo_move_to(cr, frame_width + 6.0, top + 18.0);
      cairo_show_text(cr, scene.value_label.c_str());
    }
    picture_detail::draw_legend(cr, legend, frame_width, top + 26.0, false);
  } else if (!legend.empty()) {
    picture_detail::draw_legend(cr, legend, 6.0, top + 6.0, true);
  }
}

}  // namespace

std::array<double, 3> viridis(double t) {
  // Matplotlib's viridis at 9 evenly spaced points, interpolated linearly.
  static constexpr double table[9][3] = {
      {0.267, 0.005, 0.329}, {0.279, 0.175, 0.483}, {0.230, 0.322, 0.546},
      {0.173, 0.449, 0.558}, {0.128, 0.567, 0.551}, {0.158, 0.684, 0.502},
      {0.369, 0.789, 0.383}, {0.678, 0.864, 0.190}, {0.993, 0.906, 0.144}};
  if (!std::isfinite(t)) {
    t = 0.0;
  }
  t = std::clamp(t, 0.0, 1.0) * 8.0;
  const int i = std::min(static_cast<int>(t), 7);
  const double f = t - i;
  return {table[i][0] + f * (table[i + 1][0] - table[i][0]),
          table[i][1] + f * (table[i + 1][1] - table[i][1]),
          table[i][2] + f * (table[i + 1][2] - table[i][2])};
}

PictureImage render_picture(const PictureScene& scene, const PictureOptions& options) {
  check_scene(scene, options);
  return picture_detail::render_image(options.width, options.height,
                                      [&](cairo_t* cr) { draw(cr, scene, options); });
}

bool is_picture_file(const std::string& path) {
  const std::string extension = lowercase_extension(path);
  return extension == ".png" || extension == ".svg";
}

void write_picture(const std::string& path, const PictureScene& scene,
                   const PictureOptions& options) {
  const std::string extension = lowercase_extension(path);
  TESSERA_CHECK(extension == ".png" || extension == ".svg",
                "cannot write the picture '" << path << "': unknown extension '" << extension
                                             << "' (use .png or .svg)");
  check_scene(scene, options);
  picture_detail::write_drawing(
      path, options.width, options.height, [&](cairo_t* cr) { draw(cr, scene, options); },
      options.title, options.legend ? legend_entries(scene) : std::vector<LegendEntry>());
}

PictureCurve styled_curve(Eigen::Matrix3Xd points, bool is_closed, const CurveStyle& style) {
  PictureCurve curve;
  curve.points = std::move(points);
  curve.is_closed = is_closed;
  curve.rgb = style.rgb;
  curve.width = style.width;
  curve.dash = style.dash;
  curve.label = style.label;
  return curve;
}

void colour_by_stability(PictureScene& scene, const std::vector<double>& unstable_counts) {
  TESSERA_CHECK(unstable_counts.size() == static_cast<std::size_t>(scene.positions.cols()),
                "colour_by_stability: " << unstable_counts.size() << " unstable counts for "
                                        << scene.positions.cols() << " vertices");
  scene.categories = stability_categories();
  scene.vertex_categories.resize(unstable_counts.size());
  for (std::size_t v = 0; v < unstable_counts.size(); ++v) {
    scene.vertex_categories[v] = stability_category(unstable_counts[v]);
  }
  scene.triangle_categories.clear();
  scene.triangle_values.resize(0);
}

std::vector<PictureCurve> boundary_curves(const TriangleMesh& mesh_in_scene) {
  TESSERA_CHECK(mesh_in_scene.ambient_dimension() == 3,
                "boundary curves of a picture need a mesh in R^3, got R^"
                    << mesh_in_scene.ambient_dimension());
  std::vector<PictureCurve> curves;
  if (mesh_in_scene.triangle_count() == 0) {
    return curves;
  }
  const MeshTopology topology(mesh_in_scene);
  for (int loop = 0; loop < topology.boundary_loop_count(); ++loop) {
    const auto vertices = topology.boundary_loop(loop);
    PictureCurve curve;
    curve.points.resize(3, static_cast<Eigen::Index>(vertices.size()));
    for (std::size_t i = 0; i < vertices.size(); ++i) {
      curve.points.col(static_cast<Eigen::Index>(i)) = mesh_in_scene.point(vertices[i]);
    }
    curve.is_closed = true;
    curve.rgb = {0.15, 0.15, 0.15};
    curve.width = 1.5;
    curves.push_back(std::move(curve));
  }
  return curves;
}

}  // namespace tessera
