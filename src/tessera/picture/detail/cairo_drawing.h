// SPDX-License-Identifier: MIT
// Internal to the picture module: what the surface pictures and the bifurcation diagram share on
// top of cairo (owning handles, PNG/SVG output through one drawing function, dashes, marker
// shapes, the legend). The only header that includes cairo; no public header includes it.
#pragma once

#include <cairo.h>

#include <array>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "tessera/picture/picture.h"
#include "tessera/picture/picture_styles.h"

namespace tessera::picture_detail {

struct SurfaceDeleter {
  void operator()(cairo_surface_t* surface) const { cairo_surface_destroy(surface); }
};
struct ContextDeleter {
  void operator()(cairo_t* cr) const { cairo_destroy(cr); }
};
using Surface = std::unique_ptr<cairo_surface_t, SurfaceDeleter>;
using Context = std::unique_ptr<cairo_t, ContextDeleter>;

/// Sets the source colour of `cr` to `rgb` (each in [0, 1]).
inline void set_rgb(cairo_t* cr, const std::array<double, 3>& rgb) {
  cairo_set_source_rgb(cr, rgb[0], rgb[1], rgb[2]);
}

/// \throw InvalidArgument "<what>: cairo says <reason>" unless `status` is a success.
void check_status(cairo_status_t status, const std::string& what);

/// A drawing of `width`×`height` pixels (SVG: points) onto a cairo context.
using Drawing = std::function<void(cairo_t*)>;

/// The drawing rasterised (ARGB32).
PictureImage render_image(int width, int height, const Drawing& draw);

/// One entry of a legend: a filled swatch (a category), a line sample (a curve) or a marker.
struct LegendEntry {
  enum class Sample { Swatch, Line, Marker };
  Sample sample = Sample::Swatch;
  std::string label;
  std::array<double, 3> rgb = {0.5, 0.5, 0.5};
  CurveDash dash = CurveDash::Solid;     ///< Line
  double width = 2.0;                    ///< Line
  PointKind point = PointKind::Generic;  ///< Marker
};

/// Writes the drawing to `path`, .png or .svg by extension (checked by the caller), replacing
/// the file atomically. An SVG, made small by compact_svg, gets `<title>` (`title`, when not
/// empty) and `<desc>` with the lines of `description` (e.g. "axes: lambda, epsilon, max_u")
/// and a last line naming the legend's entries ("legend: fold; cusp"), as text that readers,
/// screen readers and searches find (cairo writes text as glyph outlines).
void write_drawing(const std::string& path, int width, int height, const Drawing& draw,
                   const std::string& title, const std::vector<LegendEntry>& legend,
                   const std::vector<std::string>& description = {});

/// Sets the dash of the next stroke for a line of `width` pixels (and round caps for dots).
void set_dash(cairo_t* cr, CurveDash dash, double width);

/// Draws a marker of `kind` centred at (x, y): filled, with a dark outline.
void draw_marker(cairo_t* cr, PointKind kind, double x, double y);

/// The width in pixels the legend needs (samples and the longest label).
double legend_width(cairo_t* cr, const std::vector<LegendEntry>& entries);

/// The height in pixels draw_legend uses for `entries`.
double legend_height(const std::vector<LegendEntry>& entries);

/// Draws the legend's entries from the top left corner (x, y) down, 18 pixels apart, on a
/// white box with a thin frame when `boxed`. \return the height used.
double draw_legend(cairo_t* cr, const std::vector<LegendEntry>& entries, double x, double y,
                   bool boxed);

/// Legend entries of the curves (one per distinct label, in order of appearance) and the kinds
/// of marked points that occur.
void append_curve_entries(const std::vector<CurveStyle>& curves, std::vector<LegendEntry>& out);
void append_point_entries(const std::vector<PointKind>& points, std::vector<LegendEntry>& out);

}  // namespace tessera::picture_detail
