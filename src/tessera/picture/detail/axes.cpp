// SPDX-License-Identifier: MIT
#include "tessera/picture/detail/axes.h"

#include <algorithm>
#include <cmath>

#include "tessera/picture/detail/cairo_drawing.h"
#include "tessera/picture/ticks.h"

namespace tessera::picture_detail {

namespace {

constexpr double kTickFont = 11.0;       // tick labels
constexpr double kNameFont = 12.0;       // axis names, the colour bar's title
constexpr double kTickLength = 5.0;      // pixels, outward from the axis
constexpr double kGap = 3.0;             // between a tick's end and its label, a label and a name
constexpr double kMinAxisPixels = 20.0;  // an axis projected shorter is seen end-on: left out
constexpr double kTriadLength = 28.0;    // pixels
constexpr std::array<double, 3> kInk = {0.1, 0.1, 0.1};
constexpr std::array<double, 3> kAxisLine = {0.25, 0.25, 0.25};
constexpr std::array<double, 3> kPane = {0.95, 0.95, 0.96};
constexpr std::array<double, 3> kGrid = {0.83, 0.83, 0.85};

// The label `text` at `font_size` with its ink rectangle centred at `centre`. The rectangle
// spans at least the height of the digit 0, so that labels of numbers share one baseline
// however many of their glyphs descend or are short (a minus sign).
PlacedLabel measure_label(cairo_t* cr, const std::string& text, double font_size,
                          const Eigen::Vector2d& centre) {
  cairo_set_font_size(cr, font_size);
  cairo_text_extents_t ink, zero;
  cairo_text_extents(cr, text.c_str(), &ink);
  cairo_text_extents(cr, "0", &zero);
  const double top = std::min(ink.y_bearing, zero.y_bearing);       // above the baseline
  const double bottom = std::max(ink.y_bearing + ink.height, 0.0);  // below it
  const double width = std::max(ink.x_advance, ink.x_bearing + ink.width);
  PlacedLabel label;
  label.text = text;
  label.font_size = font_size;
  label.rect = {centre(0) - width / 2.0, centre(1) - (bottom - top) / 2.0, centre(0) + width / 2.0,
                centre(1) + (bottom - top) / 2.0};
  label.origin = Eigen::Vector2d(label.rect.x0, label.rect.y0 - top);
  return label;
}

void move_label(PlacedLabel& label, const Eigen::Vector2d& by) {
  label.rect = {label.rect.x0 + by(0), label.rect.y0 + by(1), label.rect.x1 + by(0),
                label.rect.y1 + by(1)};
  label.origin += by;
}

// How far a rectangle of this size reaches from its centre in the direction `n` (unit).
double support(const Rect& rect, const Eigen::Vector2d& n) {
  return std::abs(n(0)) * rect.width() / 2.0 + std::abs(n(1)) * rect.height() / 2.0;
}

// Moves `label` by the least amount that keeps it inside `bounds` (where it fits).
void keep_inside(PlacedLabel& label, const Rect& bounds) {
  Eigen::Vector2d by = Eigen::Vector2d::Zero();
  if (label.rect.x1 > bounds.x1) {
    by(0) = bounds.x1 - label.rect.x1;
  }
  if (label.rect.x0 + by(0) < bounds.x0) {
    by(0) = bounds.x0 - label.rect.x0;
  }
  if (label.rect.y1 > bounds.y1) {
    by(1) = bounds.y1 - label.rect.y1;
  }
  if (label.rect.y0 + by(1) < bounds.y0) {
    by(1) = bounds.y0 - label.rect.y0;
  }
  move_label(label, by);
}

bool overlaps_any(const PlacedLabel& label, const std::vector<PlacedLabel>& placed, double gap) {
  return std::any_of(placed.begin(), placed.end(), [&](const PlacedLabel& other) {
    return label.rect.intersects(other.rect, gap);
  });
}

void show(cairo_t* cr, const PlacedLabel& label) {
  cairo_set_font_size(cr, label.font_size);
  cairo_move_to(cr, label.origin(0), label.origin(1));
  cairo_show_text(cr, label.text.c_str());
}

Rect united(const Rect& a, const Rect& b) {
  return {std::min(a.x0, b.x0), std::min(a.y0, b.y0), std::max(a.x1, b.x1), std::max(a.y1, b.y1)};
}

Rect point_rect(const Eigen::Vector2d& p) { return {p(0), p(1), p(0), p(1)}; }

// The scene point with coordinate k at `value` on the edge that `axis` runs along.
Eigen::Vector3d on_edge(const Eigen::Vector3d& start, int k, double value) {
  Eigen::Vector3d p = start;
  p(k) = value;
  return p;
}

}  // namespace

BoxAxes::BoxAxes(cairo_t* cr, const Camera& camera, const std::array<std::string, 3>& names,
                 const Rect& bounds)
    : camera_(camera) {
  const Eigen::Vector3d lower = camera.lower();
  const Eigen::Vector3d upper = camera.upper();
  const Eigen::Vector2d centre = camera.pixel(0.5 * (lower + upper));
  extent_ = point_rect(centre);
  for (int corner = 0; corner < 8; ++corner) {
    const Eigen::Vector3d p((corner & 1) ? upper(0) : lower(0), (corner & 2) ? upper(1) : lower(1),
                            (corner & 4) ? upper(2) : lower(2));
    extent_ = united(extent_, point_rect(camera.pixel(p)));
  }
  // Choose each axis's edge: of the four edges parallel to axis k, the lowest on the screen for
  // the horizontal axes (0, 1) and the leftmost for the vertical one (2), as plots put their
  // axes at the bottom and the left; such an edge lies on the box's outline, so labels beyond it
  // stay clear of the box. Ties (a box seen from straight above) go to the left, then to the
  // lower edge.
  for (int k = 0; k < 3; ++k) {
    if (!(upper(k) > lower(k))) {
      continue;  // a flat axis: the scene lies in a plane of it
    }
    const int i = (k + 1) % 3, j = (k + 2) % 3;
    double best_score = -INFINITY;
    Axis axis;
    axis.k = k;
    for (int si = 0; si < 2; ++si) {
      for (int sj = 0; sj < 2; ++sj) {
        Eigen::Vector3d start = lower;
        start(i) = si ? upper(i) : lower(i);
        start(j) = sj ? upper(j) : lower(j);
        const Eigen::Vector3d end = on_edge(start, k, upper(k));
        const Eigen::Vector2d middle = 0.5 * (camera.pixel(start) + camera.pixel(end));
        const double x = std::round(2.0 * middle(0)) / 2.0, y = std::round(2.0 * middle(1)) / 2.0;
        const double score = k == 2 ? -1e4 * x + y : 1e4 * y - x;
        if (score > best_score) {
          best_score = score;
          axis.start = start;
          axis.end = end;
        }
      }
    }
    const Eigen::Vector2d p0 = camera.pixel(axis.start), p1 = camera.pixel(axis.end);
    const double length = (p1 - p0).norm();
    if (length < kMinAxisPixels) {
      continue;
    }
    const Eigen::Vector2d along = (p1 - p0) / length;
    axis.outward = Eigen::Vector2d(-along(1), along(0));
    const Eigen::Vector2d middle = 0.5 * (p0 + p1);
    const double side = axis.outward.dot(middle - centre);
    if (std::abs(side) < 1e-6) {
      axis.outward = k == 2 ? Eigen::Vector2d(-1, 0) : Eigen::Vector2d(0, 1);  // a flat box
    } else if (side < 0) {
      axis.outward = -axis.outward;
    }
    // About one tick per 80 pixels of axis, 2 to 6.
    const int target = std::clamp(static_cast<int>(length / 80.0) + 1, 2, 6);
    axis.ticks = nice_ticks_at_least(lower(k), upper(k), target, std::min(target, 3));
    axes_.push_back(axis);
  }
  // The tick labels' candidates, and the names beyond the farthest reach of their labels.
  std::vector<std::vector<PlacedLabel>> tick_labels_of(axes_.size());
  std::vector<PlacedLabel> names_placed;
  for (std::size_t a = 0; a < axes_.size(); ++a) {
    const Axis& axis = axes_[a];
    const std::vector<std::string> texts = tick_labels(axis.ticks);
    double reach = 0.0;
    for (std::size_t t = 0; t < axis.ticks.size(); ++t) {
      const Eigen::Vector2d p = camera.pixel(on_edge(axis.start, axis.k, axis.ticks[t]));
      PlacedLabel label = measure_label(cr, texts[t], kTickFont, p);
      const double s = support(label.rect, axis.outward);
      move_label(label, axis.outward * (kTickLength + kGap + s));
      reach = std::max(reach, 2.0 * s);
      tick_labels_of[a].push_back(std::move(label));
    }
    const Eigen::Vector2d p0 = camera.pixel(axis.start), p1 = camera.pixel(axis.end);
    PlacedLabel name =
        measure_label(cr, names[static_cast<std::size_t>(axis.k)], kNameFont, 0.5 * (p0 + p1));
    move_label(name, axis.outward * (kTickLength + kGap + reach + kGap + 2.0 +
                                     support(name.rect, axis.outward)));
    // Slide along the axis, alternately to either side, until free of the names placed.
    const Eigen::Vector2d along = (p1 - p0).normalized();
    const PlacedLabel original = name;
    for (int step = 1; step <= 24 && overlaps_any(name, names_placed, 4.0); ++step) {
      name = original;
      move_label(name, along * (8.0 * ((step + 1) / 2) * (step % 2 ? 1.0 : -1.0)));
    }
    names_placed.push_back(std::move(name));
  }
  labels_ = names_placed;
  for (const auto& candidates : tick_labels_of) {
    for (const PlacedLabel& label : candidates) {
      if (!overlaps_any(label, labels_, 3.0)) {
        labels_.push_back(label);
      }
    }
  }
  for (const Axis& axis : axes_) {
    for (const double tick : axis.ticks) {
      const Eigen::Vector2d p = camera.pixel(on_edge(axis.start, axis.k, tick));
      extent_ = united(extent_, point_rect(p + kTickLength * axis.outward));
    }
  }
  for (const PlacedLabel& label : labels_) {
    extent_ = united(extent_, label.rect);
  }
  // Inside the picture: names moved in, tick labels that still leave it dropped (the caller
  // fits the camera so that none does, except when zoomed in).
  std::vector<PlacedLabel> kept;
  for (std::size_t l = 0; l < labels_.size(); ++l) {
    PlacedLabel label = labels_[l];
    if (l < names_placed.size()) {
      keep_inside(label, bounds);
    } else if (!bounds.contains(label.rect)) {
      continue;
    }
    kept.push_back(std::move(label));
  }
  labels_ = std::move(kept);
}

void BoxAxes::draw_panes(cairo_t* cr) const {
  const Eigen::Vector3d lower = camera_.lower(), upper = camera_.upper();
  std::array<std::vector<double>, 3> ticks;
  for (const Axis& axis : axes_) {
    ticks[static_cast<std::size_t>(axis.k)] = axis.ticks;
  }
  cairo_set_line_join(cr, CAIRO_LINE_JOIN_MITER);
  for (int k = 0; k < 3; ++k) {
    const int i = (k + 1) % 3, j = (k + 2) % 3;
    const double facing = camera_.toward_eye()(k);
    if (!(upper(i) > lower(i)) || !(upper(j) > lower(j)) || std::abs(facing) < 0.02) {
      continue;  // a degenerate face or one seen edge-on
    }
    // The face at the back: the one whose outer normal points away from the eye.
    const double level = facing > 0 ? lower(k) : upper(k);
    auto point = [&](double u, double v) {
      Eigen::Vector3d p;
      p(k) = level;
      p(i) = u;
      p(j) = v;
      return camera_.pixel(p);
    };
    const Eigen::Vector2d c[4] = {point(lower(i), lower(j)), point(upper(i), lower(j)),
                                  point(upper(i), upper(j)), point(lower(i), upper(j))};
    cairo_move_to(cr, c[0](0), c[0](1));
    for (int corner = 1; corner < 4; ++corner) {
      cairo_line_to(cr, c[corner](0), c[corner](1));
    }
    cairo_close_path(cr);
    set_rgb(cr, kPane);
    cairo_fill(cr);
    for (const double u : ticks[static_cast<std::size_t>(i)]) {
      const Eigen::Vector2d a = point(u, lower(j)), b = point(u, upper(j));
      cairo_move_to(cr, a(0), a(1));
      cairo_line_to(cr, b(0), b(1));
    }
    for (const double v : ticks[static_cast<std::size_t>(j)]) {
      const Eigen::Vector2d a = point(lower(i), v), b = point(upper(i), v);
      cairo_move_to(cr, a(0), a(1));
      cairo_line_to(cr, b(0), b(1));
    }
    set_rgb(cr, kGrid);
    cairo_set_line_width(cr, 0.6);
    cairo_stroke(cr);
  }
}

void BoxAxes::draw(cairo_t* cr) const {
  cairo_set_line_cap(cr, CAIRO_LINE_CAP_SQUARE);
  for (const Axis& axis : axes_) {
    const Eigen::Vector2d p0 = camera_.pixel(axis.start), p1 = camera_.pixel(axis.end);
    cairo_move_to(cr, p0(0), p0(1));
    cairo_line_to(cr, p1(0), p1(1));
    set_rgb(cr, kAxisLine);
    cairo_set_line_width(cr, 1.0);
    cairo_stroke(cr);
    for (const double tick : axis.ticks) {
      const Eigen::Vector2d p = camera_.pixel(on_edge(axis.start, axis.k, tick));
      cairo_move_to(cr, p(0), p(1));
      cairo_line_to(cr, p(0) + kTickLength * axis.outward(0), p(1) + kTickLength * axis.outward(1));
    }
    cairo_set_line_width(cr, 0.8);
    cairo_stroke(cr);
  }
  cairo_set_line_cap(cr, CAIRO_LINE_CAP_BUTT);
  set_rgb(cr, kInk);
  for (const PlacedLabel& label : labels_) {
    show(cr, label);
  }
  cairo_set_font_size(cr, kNameFont);
}

std::vector<PlacedLabel> triad_labels(cairo_t* cr, const Camera& camera,
                                      const std::array<std::string, 3>& names,
                                      const Eigen::Vector2d& origin, const Rect& bounds) {
  std::vector<PlacedLabel> placed;
  for (int k = 0; k < 3; ++k) {
    const Eigen::Vector2d d = camera.axis_direction(k);
    const Eigen::Vector2d screen(d(0), -d(1));  // y down
    const Eigen::Vector2d end = origin + kTriadLength * screen;
    // The name beyond the axis's end; an axis toward the eye (short on the screen) names
    // itself above the origin, moved on where another name is in the way.
    const Eigen::Vector2d direction =
        screen.norm() > 0.2 ? Eigen::Vector2d(screen.normalized()) : Eigen::Vector2d(0.0, -1.0);
    PlacedLabel label = measure_label(cr, names[static_cast<std::size_t>(k)], kNameFont, end);
    move_label(label, direction * (4.0 + support(label.rect, direction)));
    for (int step = 0; step < 12 && overlaps_any(label, placed, 2.0); ++step) {
      move_label(label, direction * 4.0 + Eigen::Vector2d(direction(1), -direction(0)) * 3.0);
    }
    keep_inside(label, bounds);
    placed.push_back(std::move(label));
  }
  cairo_set_font_size(cr, kNameFont);
  return placed;
}

void draw_triad(cairo_t* cr, const Camera& camera, const Eigen::Vector2d& origin,
                const std::vector<PlacedLabel>& labels) {
  set_rgb(cr, kInk);
  for (int k = 0; k < 3; ++k) {
    const Eigen::Vector2d d = camera.axis_direction(k);
    cairo_move_to(cr, origin(0), origin(1));
    cairo_line_to(cr, origin(0) + kTriadLength * d(0), origin(1) - kTriadLength * d(1));
  }
  cairo_set_line_width(cr, 1.2);
  cairo_stroke(cr);
  for (const PlacedLabel& label : labels) {
    show(cr, label);
  }
  cairo_set_font_size(cr, kNameFont);
}

namespace {

constexpr double kBarLeft = 14.0;  // from the panel's left edge to the bar
constexpr double kBarWidth = 16.0;
constexpr double kBarTop = 30.0;  // room for the title above the bar

std::vector<double> bar_ticks(double low, double high, double bar_height) {
  const int target = std::clamp(static_cast<int>(bar_height / 50.0), 2, 8);
  return nice_ticks_at_least(low, high, target, std::min(target, 4));
}

}  // namespace

double colour_bar_width(cairo_t* cr, double low, double high, const std::string& title) {
  double widest = 0.0;
  cairo_set_font_size(cr, kTickFont);
  for (const std::string& text : tick_labels(bar_ticks(low, high, 400.0))) {
    cairo_text_extents_t extents;
    cairo_text_extents(cr, text.c_str(), &extents);
    widest = std::max(widest, extents.x_advance);
  }
  cairo_set_font_size(cr, kNameFont);
  cairo_text_extents_t extents;
  cairo_text_extents(cr, title.c_str(), &extents);
  cairo_set_font_size(cr, kNameFont);
  return std::max(kBarLeft + kBarWidth + kTickLength + kGap + widest + 10.0,
                  kBarLeft - 6.0 + extents.x_advance + 8.0);
}

ColourBar colour_bar_layout(cairo_t* cr, const Rect& area, double low, double high,
                            const std::string& title) {
  ColourBar bar;
  const double top = area.y0 + kBarTop;
  bar.bar = {area.x0 + kBarLeft, top, area.x0 + kBarLeft + kBarWidth,
             std::max(top + 20.0, area.y1)};
  bar.low = low;
  bar.high = high;
  bar.ticks = bar_ticks(low, high, bar.bar.height());
  const std::vector<std::string> texts = tick_labels(bar.ticks);
  for (std::size_t t = 0; t < bar.ticks.size(); ++t) {
    PlacedLabel label =
        measure_label(cr, texts[t], kTickFont, Eigen::Vector2d(0, bar.y_of(bar.ticks[t])));
    move_label(label, Eigen::Vector2d(bar.bar.x1 + kTickLength + kGap - label.rect.x0, 0.0));
    bar.labels.push_back(std::move(label));
  }
  PlacedLabel heading = measure_label(cr, title, kNameFont, Eigen::Vector2d(0, top - 14.0));
  move_label(heading, Eigen::Vector2d(bar.bar.x0 - 6.0 - heading.rect.x0, 0.0));
  keep_inside(heading, {area.x0 + 2.0, area.y0, area.x1 - 2.0, area.y1});
  bar.labels.push_back(std::move(heading));
  cairo_set_font_size(cr, kNameFont);
  return bar;
}

void draw_colour_bar(cairo_t* cr, const ColourBar& bar) {
  // One gradient through the colour map's nine points, as viridis() interpolates them.
  cairo_pattern_t* gradient = cairo_pattern_create_linear(0.0, bar.bar.y1, 0.0, bar.bar.y0);
  for (int i = 0; i <= 8; ++i) {
    const auto rgb = viridis(i / 8.0);
    cairo_pattern_add_color_stop_rgb(gradient, i / 8.0, rgb[0], rgb[1], rgb[2]);
  }
  cairo_rectangle(cr, bar.bar.x0, bar.bar.y0, bar.bar.width(), bar.bar.height());
  cairo_set_source(cr, gradient);
  cairo_fill_preserve(cr);
  cairo_pattern_destroy(gradient);
  set_rgb(cr, {0.45, 0.45, 0.45});
  cairo_set_line_width(cr, 0.6);
  cairo_stroke(cr);
  set_rgb(cr, kInk);
  for (const double tick : bar.ticks) {
    const double y = bar.y_of(tick);
    cairo_move_to(cr, bar.bar.x1, y);
    cairo_line_to(cr, bar.bar.x1 + kTickLength, y);
  }
  cairo_set_line_width(cr, 0.8);
  cairo_stroke(cr);
  for (const PlacedLabel& label : bar.labels) {
    show(cr, label);
  }
  cairo_set_font_size(cr, kNameFont);
}

}  // namespace tessera::picture_detail
