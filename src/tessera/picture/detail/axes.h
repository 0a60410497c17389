// SPDX-License-Identifier: MIT
// Internal to the picture module: what tells the reader the scale of a surface picture. Axes
// along three edges of the scene's bounding box with ticks at round values, their labels and
// the axes' names (continuation views and maps), the small triad of geometry pictures, and the
// colour bar. Every label is measured with cairo and laid out so that none overlaps another or
// leaves the picture.
#pragma once

#include <cairo.h>

#include <array>
#include <string>
#include <vector>

#include "tessera/picture/detail/camera.h"

namespace tessera::picture_detail {

/// A line of text placed in the picture: its ink rectangle and where cairo_show_text starts.
struct PlacedLabel {
  std::string text;
  Rect rect;
  Eigen::Vector2d origin = Eigen::Vector2d::Zero();
  double font_size = 11.0;
};

/// Axes along three edges of the bounding box of the scene, as matplotlib draws 3-D axes: the
/// two horizontal axes along the box's lowest edges on the screen, the vertical (third) axis
/// along its leftmost edge, each with ticks at nice_ticks values pointing away from the box,
/// labels beyond them and the axis name beyond the labels; the three faces at the back of the box
/// as light panes with grid lines at the ticks. An axis seen end-on (projected shorter than 20
/// pixels, as the third axis of a map seen from above) is left out, and so is the pane of a
/// face seen edge-on.
class BoxAxes {
 public:
  /// Lays the axes out for the fitted `camera`. Tick labels that would overlap a name or another
  /// label, or leave `bounds`, are left out; names are moved along their axis until they are
  /// free of each other.
  BoxAxes(cairo_t* cr, const Camera& camera, const std::array<std::string, 3>& names,
          const Rect& bounds);

  /// The rectangle that holds the box's projection and every label.
  Rect extent() const { return extent_; }
  /// The back panes and their grid lines: drawn before the surface.
  void draw_panes(cairo_t* cr) const;
  /// The axis lines, ticks, tick labels and names: drawn after the surface.
  void draw(cairo_t* cr) const;
  /// Every label placed (tick labels, then names): what tests check for overlaps.
  const std::vector<PlacedLabel>& labels() const { return labels_; }

 private:
  struct Axis {
    int k = 0;                   // the scene axis
    Eigen::Vector3d start, end;  // the chosen edge in scene coordinates
    Eigen::Vector2d outward;     // unit screen normal pointing away from the box
    std::vector<double> ticks;
  };
  Camera camera_;
  std::vector<Axis> axes_;
  std::vector<PlacedLabel> labels_;
  Rect extent_;
};

/// The names of the triad of geometry pictures: each axis's screen direction, 28 pixels long
/// from `origin`, named beyond its end; the names measured, kept apart and inside `bounds`.
std::vector<PlacedLabel> triad_labels(cairo_t* cr, const Camera& camera,
                                      const std::array<std::string, 3>& names,
                                      const Eigen::Vector2d& origin, const Rect& bounds);
void draw_triad(cairo_t* cr, const Camera& camera, const Eigen::Vector2d& origin,
                const std::vector<PlacedLabel>& labels);

/// The width the colour bar of values in [low, high] needs with its tick labels and `title`.
double colour_bar_width(cairo_t* cr, double low, double high, const std::string& title);

/// The colour bar in `area` (the right panel below the title): viridis from `low` (bottom) to
/// `high` (top) as one gradient, ticks at nice_ticks values (at least four where the bar is
/// tall enough) labelled by tick_labels, `title` above it.
struct ColourBar {
  Rect bar;
  double low = 0, high = 1;
  std::vector<double> ticks;
  std::vector<PlacedLabel> labels;  ///< one per tick, then the title
  /// The pixel row of `value` on the bar (the middle where low == high).
  double y_of(double value) const {
    return bar.y1 - (high > low ? (value - low) / (high - low) : 0.5) * bar.height();
  }
};
ColourBar colour_bar_layout(cairo_t* cr, const Rect& area, double low, double high,
                            const std::string& title);
void draw_colour_bar(cairo_t* cr, const ColourBar& bar);

}  // namespace tessera::picture_detail
