// SPDX-License-Identifier: MIT
#include "tessera/picture/picture.h"

#include <algorithm>
#include <cmath>
#include <optional>

#include "tessera/core/error.h"
#include "tessera/geometry/mesh_topology.h"
#include "tessera/geometry/planar.h"
#include "tessera/io/file_names.h"
#include "tessera/picture/detail/axes.h"
#include "tessera/picture/detail/cairo_drawing.h"
#include "tessera/picture/detail/camera.h"
#include "tessera/picture/detail/surface_drawing.h"
#include "tessera/picture/view_direction.h"

namespace tessera {

namespace {

using picture_detail::Camera;
using picture_detail::LegendEntry;
using picture_detail::Rect;

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
  TESSERA_CHECK(scene.vertex_values.size() == 0 || scene.vertex_values.size() == vertex_count,
                "picture: " << scene.vertex_values.size() << " vertex values for " << vertex_count
                            << " vertices");
  TESSERA_CHECK(scene.vertex_values.size() == 0 || scene.triangle_values.size() == 0,
                "picture: values per vertex and per triangle at once; give one");
  TESSERA_CHECK(!has_categories || scene.vertex_values.size() == 0,
                "picture: values and categories at once; colour by one");
  TESSERA_CHECK(
      scene.triangle_values.size() == 0 ||
          scene.triangle_values.size() == static_cast<Eigen::Index>(scene.triangles.size()),
      "picture: " << scene.triangle_values.size() << " values for " << scene.triangles.size()
                  << " triangles");
  TESSERA_CHECK(options.width >= 16 && options.width <= 20000 && options.height >= 16 &&
                    options.height <= 20000,
                "picture size " << options.width << "x" << options.height
                                << " must be between 16 and 20000 pixels each way");
  TESSERA_CHECK(std::isfinite(options.zoom) && options.zoom > 0,
                "picture zoom " << options.zoom << " must be finite and > 0");
  TESSERA_CHECK(std::isfinite(options.azimuth_degrees) && std::isfinite(options.elevation_degrees),
                "picture: azimuth and elevation must be finite");
}

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

constexpr int kTitleHeight = 24;
constexpr double kTriadRoom = 100.0;  // pixels below the colour bar kept for the triad

// The axes drawn: Automatic is Ticked for continuation views (axes scaled apart) and maps seen
// from straight above, the triad for geometry.
PictureAxes axes_of(const PictureScene& scene, const PictureOptions& options) {
  if (options.axes != PictureAxes::Automatic) {
    return options.axes;
  }
  const bool is_map = std::abs(options.elevation_degrees) == 90.0;
  return is_map || has_axes_scaled_apart(scene.positions, options.aspect) ? PictureAxes::Ticked
                                                                          : PictureAxes::Triad;
}

// The points the camera fits into the frame: the surface, its curves and, with ticked axes, the
// corners of the bounding box the axes run along.
Eigen::Matrix3Xd points_to_fit(const PictureScene& scene, bool with_box) {
  Eigen::Index count = scene.positions.cols() + (with_box ? 8 : 0);
  for (const auto& curve : scene.curves) {
    count += curve.points.cols();
  }
  Eigen::Matrix3Xd points(3, count);
  Eigen::Index at = 0;
  points.leftCols(scene.positions.cols()) = scene.positions;
  at += scene.positions.cols();
  for (const auto& curve : scene.curves) {
    points.middleCols(at, curve.points.cols()) = curve.points;
    at += curve.points.cols();
  }
  if (with_box) {
    const Eigen::Vector3d lower = scene.positions.rowwise().minCoeff();
    const Eigen::Vector3d upper = scene.positions.rowwise().maxCoeff();
    for (int corner = 0; corner < 8; ++corner) {
      points.col(at++) =
          Eigen::Vector3d((corner & 1) ? upper(0) : lower(0), (corner & 2) ? upper(1) : lower(1),
                          (corner & 4) ? upper(2) : lower(2));
    }
  }
  return points;
}

void draw_curves(cairo_t* cr, const PictureScene& scene, const Camera& camera, int width,
                 int height) {
  // Curves over the surface, drawn last: solid where they are seen, dashed where a triangle
  // nearer to the eye covers them (a curve on the surface is level with its own triangles, so
  // only triangles nearer by more than 1 % of the scene's size count).
  const ScreenIndex index(scene, camera, width, height);
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
}

// Where the boxed legend goes: the corner of the frame where it covers the least of the surface
// (its vertices), the curves and markers (five times as much) and the axes' labels (each as
// much as 40 vertices); the upper left where they tie.
Eigen::Vector2d legend_corner(cairo_t* cr, const PictureScene& scene, const Camera& camera,
                              const std::vector<LegendEntry>& legend, const Rect& frame,
                              const std::vector<picture_detail::PlacedLabel>& labels) {
  const double width = picture_detail::legend_width(cr, legend) + 6.0;
  const double height = picture_detail::legend_height(legend);
  const Eigen::Vector2d corners[4] = {{frame.x0 + 6.0, frame.y0 + 6.0},
                                      {frame.x1 - 6.0 - width, frame.y0 + 6.0},
                                      {frame.x0 + 6.0, frame.y1 - 6.0 - height},
                                      {frame.x1 - 6.0 - width, frame.y1 - 6.0 - height}};
  // At most about 2000 points of the surface stand for it.
  const Eigen::Index stride = std::max<Eigen::Index>(1, scene.positions.cols() / 2000);
  double best = INFINITY;
  Eigen::Vector2d chosen = corners[0];
  for (const Eigen::Vector2d& corner : corners) {
    const Rect box{corner(0), corner(1), corner(0) + width, corner(1) + height};
    auto inside = [&](const Eigen::Vector3d& p) {
      const Eigen::Vector2d q = camera.pixel(p);
      return q(0) >= box.x0 && q(0) <= box.x1 && q(1) >= box.y0 && q(1) <= box.y1;
    };
    double cost = 0.0;
    for (Eigen::Index v = 0; v < scene.positions.cols(); v += stride) {
      cost += inside(scene.positions.col(v)) ? static_cast<double>(stride) : 0.0;
    }
    for (const PictureCurve& curve : scene.curves) {
      for (Eigen::Index i = 0; i < curve.points.cols(); ++i) {
        cost += inside(curve.points.col(i)) ? 5.0 : 0.0;
      }
    }
    for (Eigen::Index i = 0; i < scene.markers.cols(); ++i) {
      cost += inside(scene.markers.col(i)) ? 50.0 : 0.0;
    }
    for (const auto& label : labels) {
      cost += box.intersects(label.rect) ? 40.0 : 0.0;
    }
    if (cost < best - 1e-9) {
      best = cost;
      chosen = corner;
    }
  }
  return chosen;
}

// `options` with the view direction chosen where it asks for it.
PictureOptions resolved(const PictureScene& scene, const PictureOptions& options) {
  PictureOptions result = options;
  if (options.choose_view) {
    const ViewDirection view = best_view_direction(scene, options.aspect);
    result.azimuth_degrees = view.azimuth_degrees;
    result.elevation_degrees = view.elevation_degrees;
    result.choose_view = false;
  }
  return result;
}

// Everything placed before painting: the camera, the axes, the panel, the labels.
struct Layout {
  PictureOptions options;  // the view direction resolved
  double low = 0.0, high = 1.0;
  bool is_raster = true;
  Rect frame;
  double panel_width = 0.0;
  PictureAxes axes = PictureAxes::Off;
  std::optional<Camera> camera;
  std::optional<picture_detail::BoxAxes> box_axes;
  Eigen::Vector2d triad_origin = Eigen::Vector2d::Zero();
  std::vector<picture_detail::PlacedLabel> triad;
  std::optional<picture_detail::ColourBar> colour_bar;
  std::vector<LegendEntry> legend;
  bool has_side_legend = false;
  Eigen::Vector2d legend_corner = Eigen::Vector2d::Zero();
  double edge_strength = 0.0;
};

Layout lay_out(cairo_t* cr, const PictureScene& scene, const PictureOptions& given) {
  Layout layout;
  layout.options = resolved(scene, given);
  const PictureOptions& options = layout.options;
  const bool has_values = scene.triangle_values.size() > 0 || scene.vertex_values.size() > 0;
  const bool has_bar = has_values && options.colour_bar;
  layout.is_raster = cairo_surface_get_type(cairo_get_target(cr)) == CAIRO_SURFACE_TYPE_IMAGE;
  layout.legend = options.legend ? legend_entries(scene) : std::vector<LegendEntry>();
  cairo_select_font_face(cr, "sans-serif", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
  cairo_set_font_size(cr, 12.0);
  const auto range = picture_detail::value_range(scene);
  layout.low = range[0];
  layout.high = range[1];
  // The right panel: the colour bar, or the legend of a categorical scene in its place.
  layout.has_side_legend = has_categories(scene) && !layout.legend.empty();
  layout.panel_width =
      has_bar ? std::min(0.35 * options.width, picture_detail::colour_bar_width(
                                                   cr, layout.low, layout.high, scene.value_label))
      : layout.has_side_legend
          ? std::min(0.4 * options.width, picture_detail::legend_width(cr, layout.legend) + 12.0)
          : 0.0;
  const double top = options.title.empty() ? 0.0 : kTitleHeight;
  const Rect bounds{2.0, 2.0, options.width - 2.0, options.height - 2.0};
  layout.frame = {0.0, top, options.width - layout.panel_width,
                  static_cast<double>(options.height)};
  const Rect& frame = layout.frame;
  layout.axes = axes_of(scene, options);
  const bool is_ticked = layout.axes == PictureAxes::Ticked;
  layout.camera.emplace(scene.positions, options.aspect, options.azimuth_degrees,
                        options.elevation_degrees, options.perspective);
  Camera& camera = *layout.camera;
  const Eigen::Matrix3Xd fitted = points_to_fit(scene, is_ticked);
  if (is_ticked) {
    // Fit the box into the frame, then shrink the box's frame by what its labels need beyond
    // it, until every label lies inside the frame (labels keep their size as the box shrinks,
    // so a few rounds settle it).
    const Rect labels_frame{frame.x0 + 4.0, frame.y0 + 4.0, frame.x1 - 4.0, frame.y1 - 4.0};
    Rect box_frame = labels_frame;
    for (int round = 0; round < 4; ++round) {
      camera.fit(fitted, box_frame, options.zoom, 1.0);
      layout.box_axes.emplace(cr, camera, scene.axis_names, bounds);
      const Rect extent = layout.box_axes->extent();
      if (options.zoom > 1.0 || labels_frame.contains(extent)) {
        break;
      }
      const Rect next{box_frame.x0 + std::max(0.0, labels_frame.x0 - extent.x0),
                      box_frame.y0 + std::max(0.0, labels_frame.y0 - extent.y0),
                      box_frame.x1 - std::max(0.0, extent.x1 - labels_frame.x1),
                      box_frame.y1 - std::max(0.0, extent.y1 - labels_frame.y1)};
      if (next.width() < 16.0 || next.height() < 16.0) {
        break;  // a picture too small for its labels: the last layout
      }
      box_frame = next;
    }
  } else {
    camera.fit(fitted, frame, options.zoom);
  }
  if (layout.axes == PictureAxes::Triad) {
    // Beneath the colour bar where there is one (the surface fills the frame), else at the
    // lower left.
    layout.triad_origin =
        Eigen::Vector2d(layout.panel_width > 0 ? options.width - layout.panel_width / 2.0 : 45.0,
                        options.height - 38.0);
    layout.triad =
        picture_detail::triad_labels(cr, camera, scene.axis_names, layout.triad_origin, bounds);
  }
  if (has_bar) {
    const double bottom = options.height - (layout.axes == PictureAxes::Triad ? kTriadRoom : 30.0);
    layout.colour_bar = picture_detail::colour_bar_layout(
        cr, {frame.x1, top, static_cast<double>(options.width), bottom}, layout.low, layout.high,
        scene.value_label);
  }
  if (!layout.legend.empty() && !layout.has_side_legend) {
    layout.legend_corner = legend_corner(
        cr, scene, camera, layout.legend, frame,
        layout.box_axes ? layout.box_axes->labels() : std::vector<picture_detail::PlacedLabel>());
  }
  layout.edge_strength = picture_detail::edge_strength(scene, camera, options.edges);
  return layout;
}

void paint(cairo_t* cr, const PictureScene& scene, const Layout& layout) {
  const PictureOptions& options = layout.options;
  const Camera& camera = *layout.camera;
  cairo_set_source_rgb(cr, options.background_rgb[0], options.background_rgb[1],
                       options.background_rgb[2]);
  cairo_paint(cr);
  if (layout.box_axes) {
    layout.box_axes->draw_panes(cr);
  }
  picture_detail::draw_surface(cr, scene, camera, options, layout.low, layout.high,
                               layout.edge_strength, layout.is_raster);
  draw_curves(cr, scene, camera, options.width, options.height);
  if (layout.box_axes) {
    layout.box_axes->draw(cr);
  }
  cairo_set_source_rgb(cr, 0.1, 0.1, 0.1);
  cairo_set_font_size(cr, 12.0);
  if (!options.title.empty()) {
    cairo_move_to(cr, 8.0, 17.0);
    cairo_show_text(cr, options.title.c_str());
  }
  if (layout.axes == PictureAxes::Triad) {
    picture_detail::draw_triad(cr, camera, layout.triad_origin, layout.triad);
  }
  if (layout.colour_bar) {
    picture_detail::draw_colour_bar(cr, *layout.colour_bar);
  }
  if (layout.has_side_legend) {
    const double top = layout.frame.y0;
    if (!scene.value_label.empty()) {
      cairo_set_source_rgb(cr, 0.1, 0.1, 0.1);
      cairo_move_to(cr, layout.frame.x1 + 6.0, top + 18.0);
      cairo_show_text(cr, scene.value_label.c_str());
    }
    picture_detail::draw_legend(cr, layout.legend, layout.frame.x1, top + 26.0, false);
  } else if (!layout.legend.empty()) {
    picture_detail::draw_legend(cr, layout.legend, layout.legend_corner(0), layout.legend_corner(1),
                                true);
  }
}

void draw(cairo_t* cr, const PictureScene& scene, const PictureOptions& options) {
  paint(cr, scene, lay_out(cr, scene, options));
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

namespace {

// The SVG's description: the axes' names and what the colours show.
std::vector<std::string> description_of(const PictureScene& scene, const PictureOptions& options) {
  std::vector<std::string> lines;
  if (options.axes != PictureAxes::Off) {
    lines.push_back("axes: " + scene.axis_names[0] + ", " + scene.axis_names[1] + ", " +
                    scene.axis_names[2]);
  }
  const bool has_values = scene.triangle_values.size() > 0 || scene.vertex_values.size() > 0;
  if (has_values && !scene.value_label.empty()) {
    lines.push_back("colour: " + scene.value_label);
  }
  return lines;
}

}  // namespace

PictureLayout picture_layout(const PictureScene& scene, const PictureOptions& options) {
  check_scene(scene, options);
  // Text extents need a context: a 1×1 image has the output's font metrics (positions do not
  // depend on the surface's size).
  picture_detail::Surface surface(cairo_image_surface_create(CAIRO_FORMAT_ARGB32, 1, 1));
  picture_detail::Context cr(cairo_create(surface.get()));
  const Layout layout = lay_out(cr.get(), scene, options);
  PictureLayout result;
  result.azimuth_degrees = layout.options.azimuth_degrees;
  result.elevation_degrees = layout.options.elevation_degrees;
  result.axes = layout.axes;
  result.edge_strength = layout.edge_strength;
  auto add = [&](const std::vector<picture_detail::PlacedLabel>& labels) {
    for (const auto& label : labels) {
      result.labels.push_back(
          {label.text, label.rect.x0, label.rect.y0, label.rect.x1, label.rect.y1});
    }
  };
  if (layout.box_axes) {
    add(layout.box_axes->labels());
  }
  add(layout.triad);
  if (layout.colour_bar) {
    add(layout.colour_bar->labels);
  }
  return result;
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
      options.title, options.legend ? legend_entries(scene) : std::vector<LegendEntry>(),
      description_of(scene, options));
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
  scene.vertex_values.resize(0);
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
