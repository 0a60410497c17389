// SPDX-License-Identifier: MIT
#include "tessera/picture/bifurcation_diagram.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "tessera/core/error.h"
#include "tessera/io/file_names.h"
#include "tessera/picture/detail/cairo_drawing.h"

namespace tessera {

namespace {

using picture_detail::LegendEntry;

constexpr double kFontSize = 12.0;
constexpr double kTickLength = 5.0;

// Drawn from the back: level curves under the bifurcation curves, Hopf (dashed) last so that a
// fold beneath it shows through its gaps.
int drawing_order(CurveKind kind) {
  switch (kind) {
    case CurveKind::Level:
      return 0;
    case CurveKind::Other:
      return 1;
    case CurveKind::NeutralSaddle:
      return 2;
    case CurveKind::Fold:
      return 3;
    case CurveKind::Hopf:
      return 4;
  }
  return 1;
}

void check_diagram(const BifurcationDiagramScene& scene, const BifurcationDiagramOptions& options) {
  TESSERA_CHECK(options.width >= 16 && options.width <= 20000 && options.height >= 16 &&
                    options.height <= 20000,
                "diagram size " << options.width << "x" << options.height
                                << " must be between 16 and 20000 pixels each way");
  TESSERA_CHECK(std::isfinite(options.margin) && options.margin >= 0 && options.margin <= 1,
                "BifurcationDiagramOptions::margin = " << options.margin << " must be in [0, 1]");
  bool has_point = !scene.points.empty();
  for (std::size_t c = 0; c < scene.curves.size(); ++c) {
    TESSERA_CHECK(scene.curves[c].points.allFinite(),
                  "bifurcation diagram: curve " << c << " has a point that is not finite");
    has_point = has_point || scene.curves[c].points.cols() > 0;
  }
  for (std::size_t i = 0; i < scene.points.size(); ++i) {
    TESSERA_CHECK(scene.points[i].point.allFinite(),
                  "bifurcation diagram: special point " << i << " is not finite");
  }
  TESSERA_CHECK(has_point,
                "a bifurcation diagram needs a curve or a special point, the scene "
                "has none (were the curve files empty?)");
}

// The legend: the curve kinds in drawing order, then the point kinds.
std::vector<LegendEntry> legend_entries(const BifurcationDiagramScene& scene) {
  std::vector<const DiagramCurve*> curves;
  for (const auto& curve : scene.curves) {
    curves.push_back(&curve);
  }
  std::stable_sort(curves.begin(), curves.end(), [](const DiagramCurve* a, const DiagramCurve* b) {
    return drawing_order(a->kind) > drawing_order(b->kind);
  });
  std::vector<CurveStyle> styles;
  for (const auto* curve : curves) {
    styles.push_back(curve_style(curve->kind, curve->kind_name));
  }
  std::vector<LegendEntry> entries;
  picture_detail::append_curve_entries(styles, entries);
  std::vector<PointKind> kinds;
  for (const auto& point : scene.points) {
    kinds.push_back(point.kind);
  }
  picture_detail::append_point_entries(kinds, entries);
  return entries;
}

// The data range on one axis with the margin; an axis of one value gets a unit-sized window
// around it (or 10 % of its size).
std::array<double, 2> padded_range(double low, double high, double margin) {
  double extent = high - low;
  if (!(extent > 1e-12 * std::max(std::abs(low), std::abs(high)))) {
    const double half = std::max(0.1 * std::abs(low), 0.5);
    return {low - half, high + half};
  }
  return {low - margin * extent, high + margin * extent};
}

struct Measured {
  double legend_width = 0;
  std::vector<LegendEntry> legend;
  picture_detail::Surface surface;  // a 1×1 image: text extents in the output's font metrics
  picture_detail::Context cr;
};

Measured measure(const BifurcationDiagramScene& scene, const BifurcationDiagramOptions& options) {
  Measured measured;
  measured.surface.reset(cairo_image_surface_create(CAIRO_FORMAT_ARGB32, 1, 1));
  measured.cr.reset(cairo_create(measured.surface.get()));
  cairo_select_font_face(measured.cr.get(), "sans-serif", CAIRO_FONT_SLANT_NORMAL,
                         CAIRO_FONT_WEIGHT_NORMAL);
  cairo_set_font_size(measured.cr.get(), kFontSize);
  if (options.legend) {
    measured.legend = legend_entries(scene);
    measured.legend_width = picture_detail::legend_width(measured.cr.get(), measured.legend);
  }
  return measured;
}

DiagramLayout layout_of(const BifurcationDiagramScene& scene,
                        const BifurcationDiagramOptions& options, const Measured& measured) {
  Eigen::Vector2d low(INFINITY, INFINITY), high(-INFINITY, -INFINITY);
  for (const auto& curve : scene.curves) {
    for (Eigen::Index i = 0; i < curve.points.cols(); ++i) {
      low = low.cwiseMin(curve.points.col(i));
      high = high.cwiseMax(curve.points.col(i));
    }
  }
  for (const auto& point : scene.points) {
    low = low.cwiseMin(point.point);
    high = high.cwiseMax(point.point);
  }
  DiagramLayout layout;
  layout.p1_range = padded_range(low(0), high(0), options.margin);
  layout.p2_range = padded_range(low(1), high(1), options.margin);
  layout.top = options.title.empty() ? 16.0 : 34.0;
  layout.bottom = std::max(layout.top + 8.0, options.height - 52.0);
  const int p2_target = std::clamp(static_cast<int>((layout.bottom - layout.top) / 60.0), 2, 10);
  layout.p2_ticks = nice_ticks(layout.p2_range[0], layout.p2_range[1], p2_target);
  // Left of the box: the rotated name of p2 (about 24 pixels), the widest p2 label and the
  // tick, so that long labels (-0.000125) are not cut at the picture's edge.
  double widest = 0.0;
  for (const std::string& label : tick_labels(layout.p2_ticks)) {
    cairo_text_extents_t extents;
    cairo_text_extents(measured.cr.get(), label.c_str(), &extents);
    widest = std::max(widest, extents.x_advance);
  }
  layout.left = std::max(76.0, 28.0 + widest + kTickLength + 8.0);
  const double legend_space =
      measured.legend.empty() ? 0.0 : std::min(measured.legend_width + 16.0, 0.4 * options.width);
  layout.right = std::max(layout.left + 8.0, options.width - 20.0 - legend_space);
  const int p1_target = std::clamp(static_cast<int>((layout.right - layout.left) / 90.0), 2, 10);
  layout.p1_ticks = nice_ticks(layout.p1_range[0], layout.p1_range[1], p1_target);
  return layout;
}

void stroke_diagram_curve(cairo_t* cr, const DiagramCurve& curve, const DiagramLayout& layout) {
  const Eigen::Index m = curve.points.cols();
  if (m == 0) {
    return;
  }
  const CurveStyle style = curve_style(curve.kind, curve.kind_name);
  cairo_new_path(cr);
  for (Eigen::Index i = 0; i < m; ++i) {
    const Eigen::Vector2d p = layout.pixel(curve.points.col(i));
    if (i == 0) {
      cairo_move_to(cr, p(0), p(1));
    } else {
      cairo_line_to(cr, p(0), p(1));
    }
  }
  if (curve.is_closed && m > 2) {
    cairo_close_path(cr);
  }
  cairo_set_source_rgb(cr, style.rgb[0], style.rgb[1], style.rgb[2]);
  cairo_set_line_width(cr, style.width);
  picture_detail::set_dash(cr, style.dash, style.width);
  cairo_stroke(cr);
  picture_detail::set_dash(cr, CurveDash::Solid, 1.0);
}

void draw(cairo_t* cr, const BifurcationDiagramScene& scene,
          const BifurcationDiagramOptions& options, const Measured& measured,
          const DiagramLayout& layout) {
  cairo_set_source_rgb(cr, 1.0, 1.0, 1.0);
  cairo_paint(cr);
  cairo_select_font_face(cr, "sans-serif", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
  cairo_set_font_size(cr, kFontSize);
  cairo_set_line_join(cr, CAIRO_LINE_JOIN_ROUND);
  const double width = layout.right - layout.left;
  const double height = layout.bottom - layout.top;

  // A light grid at the ticks, under everything.
  cairo_set_source_rgb(cr, 0.9, 0.9, 0.9);
  cairo_set_line_width(cr, 1.0);
  for (const double tick : layout.p1_ticks) {
    const double x = layout.pixel({tick, layout.p2_range[0]})(0);
    cairo_move_to(cr, x, layout.top);
    cairo_line_to(cr, x, layout.bottom);
  }
  for (const double tick : layout.p2_ticks) {
    const double y = layout.pixel({layout.p1_range[0], tick})(1);
    cairo_move_to(cr, layout.left, y);
    cairo_line_to(cr, layout.right, y);
  }
  cairo_stroke(cr);

  // Curves and points inside the axes box only.
  cairo_save(cr);
  cairo_rectangle(cr, layout.left, layout.top, width, height);
  cairo_clip(cr);
  std::vector<const DiagramCurve*> curves;
  for (const auto& curve : scene.curves) {
    curves.push_back(&curve);
  }
  std::stable_sort(curves.begin(), curves.end(), [](const DiagramCurve* a, const DiagramCurve* b) {
    return drawing_order(a->kind) < drawing_order(b->kind);
  });
  for (const auto* curve : curves) {
    stroke_diagram_curve(cr, *curve, layout);
  }
  for (const auto& point : scene.points) {
    const Eigen::Vector2d p = layout.pixel(point.point);
    picture_detail::draw_marker(cr, point.kind, p(0), p(1));
  }
  cairo_restore(cr);

  // The frame, the ticks outside it, their labels and the axis names.
  cairo_set_source_rgb(cr, 0.1, 0.1, 0.1);
  cairo_set_line_width(cr, 1.0);
  cairo_rectangle(cr, layout.left, layout.top, width, height);
  cairo_stroke(cr);
  const std::vector<std::string> p1_labels = tick_labels(layout.p1_ticks);
  const std::vector<std::string> p2_labels = tick_labels(layout.p2_ticks);
  cairo_text_extents_t extents;
  for (std::size_t i = 0; i < layout.p1_ticks.size(); ++i) {
    const double x = layout.pixel({layout.p1_ticks[i], layout.p2_range[0]})(0);
    cairo_move_to(cr, x, layout.bottom);
    cairo_line_to(cr, x, layout.bottom + kTickLength);
    cairo_stroke(cr);
    const std::string& label = p1_labels[i];
    cairo_text_extents(cr, label.c_str(), &extents);
    cairo_move_to(cr, x - extents.x_advance / 2.0, layout.bottom + kTickLength + 14.0);
    cairo_show_text(cr, label.c_str());
  }
  for (std::size_t i = 0; i < layout.p2_ticks.size(); ++i) {
    const double y = layout.pixel({layout.p1_range[0], layout.p2_ticks[i]})(1);
    cairo_move_to(cr, layout.left - kTickLength, y);
    cairo_line_to(cr, layout.left, y);
    cairo_stroke(cr);
    const std::string& label = p2_labels[i];
    cairo_text_extents(cr, label.c_str(), &extents);
    cairo_move_to(cr, layout.left - kTickLength - 4.0 - extents.x_advance, y + 4.0);
    cairo_show_text(cr, label.c_str());
  }
  const std::string& p1_name = scene.parameter_names[0];
  cairo_text_extents(cr, p1_name.c_str(), &extents);
  cairo_move_to(cr, layout.left + width / 2.0 - extents.x_advance / 2.0, layout.bottom + 40.0);
  cairo_show_text(cr, p1_name.c_str());
  const std::string& p2_name = scene.parameter_names[1];
  cairo_text_extents(cr, p2_name.c_str(), &extents);
  cairo_save(cr);
  cairo_move_to(cr, 18.0, layout.top + height / 2.0 + extents.x_advance / 2.0);
  cairo_rotate(cr, -M_PI / 2.0);
  cairo_show_text(cr, p2_name.c_str());
  cairo_restore(cr);
  if (!options.title.empty()) {
    cairo_text_extents(cr, options.title.c_str(), &extents);
    cairo_move_to(cr, std::max(4.0, layout.left + width / 2.0 - extents.x_advance / 2.0), 22.0);
    cairo_show_text(cr, options.title.c_str());
  }
  if (!measured.legend.empty()) {
    picture_detail::draw_legend(cr, measured.legend, layout.right + 10.0, layout.top, true);
  }
}

}  // namespace

Eigen::Vector2d DiagramLayout::pixel(const Eigen::Vector2d& p) const {
  const double u = (p(0) - p1_range[0]) / (p1_range[1] - p1_range[0]);
  const double v = (p(1) - p2_range[0]) / (p2_range[1] - p2_range[0]);
  return {left + u * (right - left), bottom - v * (bottom - top)};
}

void add_to_diagram(BifurcationDiagramScene& scene, const std::vector<Polyline>& polylines,
                    const PolylineFileOptions& options, const std::string& p1,
                    const std::string& p2) {
  auto column_of = [&](const std::string& name) {
    const auto found = std::find(options.names.begin(), options.names.end(), name);
    if (found == options.names.end()) {
      std::string columns;
      for (const auto& column : options.names) {
        columns += (columns.empty() ? "" : ", ") + column;
      }
      TESSERA_CHECK(false, "no column '" << name << "' among the curves' columns ("
                                         << (columns.empty() ? "none named" : columns) << ")");
    }
    return static_cast<Eigen::Index>(found - options.names.begin());
  };
  const Eigen::Index i1 = column_of(p1);
  const Eigen::Index i2 = column_of(p2);
  const CurveKind kind = curve_kind_from_name(options.kind);
  const PointKind point_kind = point_kind_from_marker_name(options.marker_name);
  for (const Polyline& line : polylines) {
    TESSERA_CHECK(line.points.rows() == static_cast<Eigen::Index>(options.names.size()),
                  "a polyline has " << line.points.rows() << " coordinates, the columns "
                                    << options.names.size());
    DiagramCurve curve;
    curve.points.resize(2, line.points.cols());
    curve.points.row(0) = line.points.row(i1);
    curve.points.row(1) = line.points.row(i2);
    TESSERA_CHECK(curve.points.allFinite(), "a polyline has a point whose " << p1 << " or " << p2
                                                << " is not a number");
    curve.is_closed = line.is_closed;
    curve.kind = kind;
    curve.kind_name = options.kind;
    for (Eigen::Index i = 0; i < line.points.cols(); ++i) {
      if (!line.marked.empty() && line.marked[static_cast<std::size_t>(i)]) {
        scene.points.push_back({curve.points.col(i), point_kind});
      }
    }
    scene.curves.push_back(std::move(curve));
  }
}

DiagramLayout bifurcation_diagram_layout(const BifurcationDiagramScene& scene,
                                         const BifurcationDiagramOptions& options) {
  check_diagram(scene, options);
  return layout_of(scene, options, measure(scene, options));
}

PictureImage render_bifurcation_diagram(const BifurcationDiagramScene& scene,
                                        const BifurcationDiagramOptions& options) {
  check_diagram(scene, options);
  const Measured measured = measure(scene, options);
  const DiagramLayout layout = layout_of(scene, options, measured);
  return picture_detail::render_image(options.width, options.height, [&](cairo_t* cr) {
    draw(cr, scene, options, measured, layout);
  });
}

void write_bifurcation_diagram(const std::string& path, const BifurcationDiagramScene& scene,
                               const BifurcationDiagramOptions& options) {
  const std::string extension = lowercase_extension(path);
  TESSERA_CHECK(extension == ".png" || extension == ".svg",
                "cannot write the bifurcation diagram '" << path << "': unknown extension '"
                                                         << extension << "' (use .png or .svg)");
  check_diagram(scene, options);
  const Measured measured = measure(scene, options);
  const DiagramLayout layout = layout_of(scene, options, measured);
  picture_detail::write_drawing(
      path, options.width, options.height,
      [&](cairo_t* cr) { draw(cr, scene, options, measured, layout); }, options.title,
      measured.legend, {"axes: " + scene.parameter_names[0] + ", " + scene.parameter_names[1]});
}

}  // namespace tessera
