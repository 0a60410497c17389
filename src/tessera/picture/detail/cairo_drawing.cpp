// SPDX-License-Identifier: MIT
#include "tessera/picture/detail/cairo_drawing.h"

#include <cairo-svg.h>

#include <numbers>
#include <algorithm>
#include <cmath>
#include <set>

#include "tessera/core/error.h"
#include "tessera/io/detail/file_buffer.h"
#include "tessera/io/file_names.h"
#include "tessera/io/text_file.h"
#include "tessera/picture/detail/svg_compaction.h"

namespace tessera::picture_detail {

namespace {

constexpr double kLegendRow = 18.0;     // pixels from one entry to the next
constexpr double kLegendSample = 28.0;  // width of a line sample or swatch column

// cairo writes PNG and SVG through this callback into memory; the file is then replaced
// atomically like every other output.
cairo_status_t append_to_string(void* closure, const unsigned char* data, unsigned int length) {
  static_cast<std::string*>(closure)->append(reinterpret_cast<const char*>(data), length);
  return CAIRO_STATUS_SUCCESS;
}

std::array<double, 3> marker_fill(PointKind kind) {
  switch (kind) {
    case PointKind::Cusp:
      return {1.0, 0.85, 0.1};  // yellow, as cusps were drawn before kinds
    case PointKind::BogdanovTakens:
      return {0.2, 0.8, 0.3};  // green: apart from the stability colours and the curves
    case PointKind::ZeroHopf:
      return {0.85, 0.35, 0.9};  // violet
    case PointKind::Generic:
      break;
  }
  return {1.0, 0.85, 0.1};  // a yellow dot, as marked points were drawn before kinds
}

}  // namespace

void check_status(cairo_status_t status, const std::string& what) {
  TESSERA_CHECK(status == CAIRO_STATUS_SUCCESS,
                what << ": cairo says " << cairo_status_to_string(status));
}

PictureImage render_image(int width, int height, const Drawing& draw) {
  Surface surface(cairo_image_surface_create(CAIRO_FORMAT_ARGB32, width, height));
  check_status(cairo_surface_status(surface.get()), "picture");
  {
    Context cr(cairo_create(surface.get()));
    draw(cr.get());
    check_status(cairo_status(cr.get()), "picture");
  }
  cairo_surface_flush(surface.get());
  PictureImage image;
  image.width = width;
  image.height = height;
  image.pixels.resize(static_cast<std::size_t>(width) * static_cast<std::size_t>(height));
  const unsigned char* data = cairo_image_surface_get_data(surface.get());
  const int stride = cairo_image_surface_get_stride(surface.get());
  for (int y = 0; y < height; ++y) {
    const auto* row =
        reinterpret_cast<const std::uint32_t*>(data + static_cast<std::ptrdiff_t>(y) * stride);
    std::copy(row, row + width, image.pixels.begin() + static_cast<std::ptrdiff_t>(y) * width);
  }
  return image;
}

void write_drawing(const std::string& path, int width, int height, const Drawing& draw,
                   const std::string& title, const std::vector<LegendEntry>& legend,
                   const std::vector<std::string>& description) {
  const std::string extension = lowercase_extension(path);
  std::string bytes;
  if (extension == ".png") {
    Surface surface(cairo_image_surface_create(CAIRO_FORMAT_ARGB32, width, height));
    check_status(cairo_surface_status(surface.get()), "picture '" + path + "'");
    {
      Context cr(cairo_create(surface.get()));
      draw(cr.get());
      check_status(cairo_status(cr.get()), "picture '" + path + "'");
    }
    check_status(cairo_surface_write_to_png_stream(surface.get(), append_to_string, &bytes),
                 "picture '" + path + "'");
  } else {
    {
      Surface surface(cairo_svg_surface_create_for_stream(append_to_string, &bytes, width, height));
      check_status(cairo_surface_status(surface.get()), "picture '" + path + "'");
      Context cr(cairo_create(surface.get()));
      draw(cr.get());
      check_status(cairo_status(cr.get()), "picture '" + path + "'");
      cairo_surface_finish(surface.get());  // the SVG's last bytes go to `bytes` here
    }
    bytes = compact_svg(bytes);
    std::string text;
    if (!title.empty()) {
      text += "<title>" + xml_escaped(title) + "</title>\n";
    }
    std::string lines;
    for (const std::string& line : description) {
      if (!lines.empty()) {
        lines += '\n';
      }
      lines += xml_escaped(line);
    }
    if (!legend.empty()) {
      lines += lines.empty() ? "legend:" : "\nlegend:";
      for (std::size_t i = 0; i < legend.size(); ++i) {
        lines += (i == 0 ? " " : "; ") + xml_escaped(legend[i].label);
      }
    }
    if (!lines.empty()) {
      text += "<desc>" + lines + "</desc>\n";
    }
    const std::size_t root = bytes.find("<svg");
    const std::size_t end = root == std::string::npos ? root : bytes.find('>', root);
    if (end != std::string::npos && !text.empty()) {
      bytes.insert(end + 1, "\n" + text);
    }
  }
  io_detail::write_whole_file(extension == ".png" ? "PNG" : "SVG", path, bytes);
}

void set_dash(cairo_t* cr, CurveDash dash, double width) {
  switch (dash) {
    case CurveDash::Solid:
      cairo_set_dash(cr, nullptr, 0, 0.0);
      cairo_set_line_cap(cr, CAIRO_LINE_CAP_BUTT);
      return;
    case CurveDash::Dashed: {
      const double pattern[] = {4.0 * width, 2.5 * width};
      cairo_set_dash(cr, pattern, 2, 0.0);
      cairo_set_line_cap(cr, CAIRO_LINE_CAP_BUTT);
      return;
    }
    case CurveDash::Dotted: {
      // Zero-length dashes with round caps are round dots of the line's width.
      const double pattern[] = {0.0, 3.0 * width};
      cairo_set_dash(cr, pattern, 2, 0.0);
      cairo_set_line_cap(cr, CAIRO_LINE_CAP_ROUND);
      return;
    }
  }
}

void draw_marker(cairo_t* cr, PointKind kind, double x, double y) {
  constexpr double r = 5.5;
  cairo_new_path(cr);
  switch (kind) {
    case PointKind::Cusp:
      cairo_move_to(cr, x, y - 1.2 * r);
      cairo_line_to(cr, x + 1.1 * r, y + 0.8 * r);
      cairo_line_to(cr, x - 1.1 * r, y + 0.8 * r);
      cairo_close_path(cr);
      break;
    case PointKind::BogdanovTakens:
      cairo_rectangle(cr, x - 0.9 * r, y - 0.9 * r, 1.8 * r, 1.8 * r);
      break;
    case PointKind::ZeroHopf:
      cairo_move_to(cr, x, y - 1.25 * r);
      cairo_line_to(cr, x + 1.05 * r, y);
      cairo_line_to(cr, x, y + 1.25 * r);
      cairo_line_to(cr, x - 1.05 * r, y);
      cairo_close_path(cr);
      break;
    case PointKind::Generic:
      cairo_arc(cr, x, y, 0.9 * r, 0.0, 2 * std::numbers::pi);
      break;
  }
  const auto fill = marker_fill(kind);
  cairo_set_source_rgb(cr, fill[0], fill[1], fill[2]);
  cairo_fill_preserve(cr);
  cairo_set_source_rgb(cr, 0.1, 0.1, 0.1);
  cairo_set_line_width(cr, 1.2);
  set_dash(cr, CurveDash::Solid, 1.2);
  cairo_stroke(cr);
}

double legend_width(cairo_t* cr, const std::vector<LegendEntry>& entries) {
  double longest = 0.0;
  for (const auto& entry : entries) {
    cairo_text_extents_t extents;
    cairo_text_extents(cr, entry.label.c_str(), &extents);
    longest = std::max(longest, extents.x_advance);
  }
  return kLegendSample + 8.0 + longest + 8.0;
}

double legend_height(const std::vector<LegendEntry>& entries) {
  return entries.empty() ? 0.0 : kLegendRow * static_cast<double>(entries.size()) + 8.0;
}

double draw_legend(cairo_t* cr, const std::vector<LegendEntry>& entries, double x, double y,
                   bool boxed) {
  if (entries.empty()) {
    return 0.0;
  }
  const double height = legend_height(entries);
  if (boxed) {
    cairo_rectangle(cr, x, y, legend_width(cr, entries) + 6.0, height);
    cairo_set_source_rgb(cr, 1.0, 1.0, 1.0);
    cairo_fill_preserve(cr);
    cairo_set_source_rgb(cr, 0.6, 0.6, 0.6);
    cairo_set_line_width(cr, 0.8);
    set_dash(cr, CurveDash::Solid, 0.8);
    cairo_stroke(cr);
  }
  for (std::size_t i = 0; i < entries.size(); ++i) {
    const LegendEntry& entry = entries[i];
    const double row = y + 4.0 + kLegendRow * static_cast<double>(i);
    const double middle = row + kLegendRow / 2.0;
    const double left = x + 6.0;
    switch (entry.sample) {
      case LegendEntry::Sample::Swatch:
        cairo_rectangle(cr, left + 4.0, row + 3.0, kLegendSample - 8.0, kLegendRow - 6.0);
        cairo_set_source_rgb(cr, entry.rgb[0], entry.rgb[1], entry.rgb[2]);
        cairo_fill_preserve(cr);
        cairo_set_source_rgb(cr, 0.3, 0.3, 0.3);
        cairo_set_line_width(cr, 0.6);
        set_dash(cr, CurveDash::Solid, 0.6);
        cairo_stroke(cr);
        break;
      case LegendEntry::Sample::Line:
        cairo_move_to(cr, left, middle);
        cairo_line_to(cr, left + kLegendSample, middle);
        cairo_set_source_rgb(cr, entry.rgb[0], entry.rgb[1], entry.rgb[2]);
        cairo_set_line_width(cr, entry.width);
        set_dash(cr, entry.dash, entry.width);
        cairo_stroke(cr);
        set_dash(cr, CurveDash::Solid, entry.width);
        break;
      case LegendEntry::Sample::Marker:
        draw_marker(cr, entry.point, left + kLegendSample / 2.0, middle);
        break;
    }
    cairo_set_source_rgb(cr, 0.1, 0.1, 0.1);
    cairo_move_to(cr, left + kLegendSample + 8.0, middle + 4.0);
    cairo_show_text(cr, entry.label.c_str());
  }
  return height;
}

void append_curve_entries(const std::vector<CurveStyle>& curves, std::vector<LegendEntry>& out) {
  std::set<std::string> seen;
  for (const auto& style : curves) {
    if (style.label.empty() || !seen.insert(style.label).second) {
      continue;
    }
    LegendEntry entry;
    entry.sample = LegendEntry::Sample::Line;
    entry.label = style.label;
    entry.rgb = style.rgb;
    entry.dash = style.dash;
    entry.width = style.width;
    out.push_back(std::move(entry));
  }
}

void append_point_entries(const std::vector<PointKind>& points, std::vector<LegendEntry>& out) {
  for (const PointKind kind :
       {PointKind::Cusp, PointKind::BogdanovTakens, PointKind::ZeroHopf, PointKind::Generic}) {
    if (std::find(points.begin(), points.end(), kind) != points.end()) {
      LegendEntry entry;
      entry.sample = LegendEntry::Sample::Marker;
      entry.label = point_kind_label(kind);
      entry.point = kind;
      out.push_back(std::move(entry));
    }
  }
}

}  // namespace tessera::picture_detail
