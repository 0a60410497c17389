// SPDX-License-Identifier: MIT
#include "tessera/picture/detail/surface_drawing.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <vector>

#include "tessera/picture/detail/cairo_drawing.h"

namespace tessera::picture_detail {

namespace {

using Rgb = std::array<double, 3>;

constexpr Rgb kGrey = {0.5, 0.5, 0.5};   // a value that is not finite
constexpr double kEdgeWidth = 0.5;       // pixels
constexpr double kEdgeDarkening = 0.45;  // an edge at full strength: 55 % of its face's shade
constexpr double kSeamStroke = 0.8;      // pixels: the stroke in a fill's colour that closes seams

Rgb scaled(const Rgb& rgb, double factor) {
  return {factor * rgb[0], factor * rgb[1], factor * rgb[2]};
}

Rgb mean_of(const std::array<Rgb, 3>& corners) {
  Rgb mean = {0.0, 0.0, 0.0};
  for (const Rgb& corner : corners) {
    for (std::size_t c = 0; c < 3; ++c) {
      mean[c] += corner[c] / 3.0;
    }
  }
  return mean;
}


void triangle_path(cairo_t* cr, const std::array<Eigen::Vector2d, 3>& p) {
  cairo_move_to(cr, p[0](0), p[0](1));
  cairo_line_to(cr, p[1](0), p[1](1));
  cairo_line_to(cr, p[2](0), p[2](1));
  cairo_close_path(cr);
}

// The colours (before light) of the three corners of each triangle: its values' colours,
// its value's colour, or the surface's colour.
class CornerColours {
 public:
  CornerColours(const PictureScene& scene, const PictureOptions& options, double low, double high)
      : scene_(scene), options_(options), low_(low), high_(high) {}

  std::array<Rgb, 3> of(std::size_t t) const {
    const Triangle& triangle = scene_.triangles[t];
    if (scene_.vertex_values.size() > 0) {
      std::array<Rgb, 3> corners;
      for (std::size_t k = 0; k < 3; ++k) {
        const double value = scene_.vertex_values(triangle[k]);
        if (!std::isfinite(value)) {
          return {kGrey, kGrey, kGrey};  // a NaN corner: the triangle is grey, as its mean
        }
        corners[k] = colour_of(value);
      }
      return corners;
    }
    if (scene_.triangle_values.size() > 0) {
      const double value = scene_.triangle_values(static_cast<Eigen::Index>(t));
      const Rgb rgb = std::isfinite(value) ? colour_of(value) : kGrey;
      return {rgb, rgb, rgb};
    }
    return {options_.surface_rgb, options_.surface_rgb, options_.surface_rgb};
  }

 private:
  Rgb colour_of(double value) const {
    return viridis(high_ > low_ ? (value - low_) / (high_ - low_) : 0.5);
  }
  const PictureScene& scene_;
  const PictureOptions& options_;
  double low_, high_;
};

// The category of corner k of triangle t (triangle or vertex categories), or -1 without.
int category_of(const PictureScene& scene, std::size_t t, std::size_t k) {
  if (!scene.triangle_categories.empty()) {
    return scene.triangle_categories[t];
  }
  if (!scene.vertex_categories.empty()) {
    return scene.vertex_categories[static_cast<std::size_t>(scene.triangles[t][k])];
  }
  return -1;
}

// Corners of different categories: the part of each corner (the corner, the midpoints of its
// two edges, the centroid) in its colour, each stroked thinly in its own colour to close the
// seams between parts. \return the parts' mean colour, for the triangle's edges.
Rgb draw_split_triangle(cairo_t* cr, const PictureScene& scene, std::size_t t,
                        const std::array<Eigen::Vector2d, 3>& corners, double light) {
  const Eigen::Vector2d centroid = (corners[0] + corners[1] + corners[2]) / 3.0;
  std::array<Rgb, 3> parts;
  for (std::size_t k = 0; k < 3; ++k) {
    const Eigen::Vector2d& corner = corners[k];
    const Eigen::Vector2d next = 0.5 * (corner + corners[(k + 1) % 3]);
    const Eigen::Vector2d previous = 0.5 * (corner + corners[(k + 2) % 3]);
    cairo_move_to(cr, corner(0), corner(1));
    cairo_line_to(cr, next(0), next(1));
    cairo_line_to(cr, centroid(0), centroid(1));
    cairo_line_to(cr, previous(0), previous(1));
    cairo_close_path(cr);
    parts[k] = scene.categories[static_cast<std::size_t>(category_of(scene, t, k))].rgb;
    set_rgb(cr, scaled(parts[k], light));
    cairo_fill_preserve(cr);
    cairo_set_line_width(cr, 0.8);
    cairo_stroke(cr);
  }
  return mean_of(parts);
}

// One triangle as a cairo mesh pattern whose corners carry their colours: painted (without
// antialiasing, so neighbours meet without seams) over the triangle's antialiased flat fill,
// which leaves only the silhouette's antialiased fringe showing.
void paint_gouraud(cairo_t* cr, const std::array<Eigen::Vector2d, 3>& p,
                   const std::array<Rgb, 3>& rgb) {
  cairo_pattern_t* pattern = cairo_pattern_create_mesh();
  cairo_mesh_pattern_begin_patch(pattern);
  cairo_mesh_pattern_move_to(pattern, p[0](0), p[0](1));
  cairo_mesh_pattern_line_to(pattern, p[1](0), p[1](1));
  cairo_mesh_pattern_line_to(pattern, p[2](0), p[2](1));
  for (unsigned corner = 0; corner < 4; ++corner) {  // a triangle: corner 3 is corner 0
    const Rgb& c = rgb[corner % 3];
    cairo_mesh_pattern_set_corner_color_rgb(pattern, corner, c[0], c[1], c[2]);
  }
  cairo_mesh_pattern_end_patch(pattern);
  cairo_set_source(cr, pattern);
  cairo_paint(cr);
  cairo_pattern_destroy(pattern);
}

}  // namespace

double edge_strength(const PictureScene& scene, const Camera& camera, PictureEdges edges) {
  if (edges != PictureEdges::Automatic) {
    return edges == PictureEdges::On ? 1.0 : 0.0;
  }
  std::vector<double> lengths;
  lengths.reserve(3 * scene.triangles.size());
  for (const Triangle& triangle : scene.triangles) {
    for (std::size_t k = 0; k < 3; ++k) {
      lengths.push_back((camera.pixel(scene.positions.col(triangle[k])) -
                         camera.pixel(scene.positions.col(triangle[(k + 1) % 3])))
                            .norm());
    }
  }
  if (lengths.empty()) {
    return 0.0;
  }
  auto middle = lengths.begin() + static_cast<std::ptrdiff_t>(lengths.size() / 2);
  std::nth_element(lengths.begin(), middle, lengths.end());
  constexpr double kNone = 6.0, kFull = 14.0;  // pixels
  return std::clamp((*middle - kNone) / (kFull - kNone), 0.0, 1.0);
}

std::array<double, 2> value_range(const PictureScene& scene) {
  const Eigen::VectorXd& values =
      scene.vertex_values.size() > 0 ? scene.vertex_values : scene.triangle_values;
  double low = INFINITY, high = -INFINITY;
  for (Eigen::Index i = 0; i < values.size(); ++i) {
    if (std::isfinite(values(i))) {
      low = std::min(low, values(i));
      high = std::max(high, values(i));
    }
  }
  if (!(low <= high)) {
    return {0.0, 1.0};
  }
  return {low, high};
}

void draw_surface(cairo_t* cr, const PictureScene& scene, const Camera& camera,
                  const PictureOptions& options, double low, double high, double strength,
                  bool is_raster) {
  const std::size_t count = scene.triangles.size();
  const CornerColours colours(scene, options, low, high);
  // Light per triangle and, for Gouraud shading, per vertex: the mean of its triangles' light
  // (not a vertex normal, whose sign would depend on the triangles' orientations).
  std::vector<double> light(count, 1.0);
  std::vector<double> depth(count);
  Eigen::VectorXd vertex_light = Eigen::VectorXd::Zero(scene.positions.cols());
  Eigen::VectorXd vertex_weight = Eigen::VectorXd::Zero(scene.positions.cols());
  for (std::size_t t = 0; t < count; ++t) {
    const auto& [a, b, c] = scene.triangles[t];
    if (!options.flat_shading) {
      // Lambert, two-sided, the light at the eye; the ambient part keeps grazing faces visible.
      light[t] = 0.35 + 0.65 * camera.facing(scene.positions.col(a), scene.positions.col(b),
                                             scene.positions.col(c));
    }
    for (const int v : scene.triangles[t]) {
      vertex_light(v) += light[t];
      vertex_weight(v) += 1.0;
    }
    depth[t] = camera.depth(
        (scene.positions.col(a) + scene.positions.col(b) + scene.positions.col(c)) / 3.0);
  }
  vertex_light = vertex_light.cwiseQuotient(vertex_weight.cwiseMax(1.0));
  // Painter's algorithm: far triangles first, by the depth of the centroid. Correct where
  // triangles do not interpenetrate and are small against the distance between sheets, which
  // holds for the fine meshes of smooth surfaces; cyclic overlaps are not split.
  std::vector<int> order(count);
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](int s, int t) {
    return depth[static_cast<std::size_t>(s)] < depth[static_cast<std::size_t>(t)];
  });
  cairo_set_line_join(cr, CAIRO_LINE_JOIN_ROUND);
  cairo_set_line_width(cr, kEdgeWidth);
  const double edge_shade = 1.0 - kEdgeDarkening * strength;
  for (const int index : order) {
    const auto t = static_cast<std::size_t>(index);
    const Triangle& triangle = scene.triangles[t];
    std::array<Eigen::Vector2d, 3> p;
    for (std::size_t k = 0; k < 3; ++k) {
      p[k] = camera.pixel(scene.positions.col(triangle[k]));
    }
    const int c0 = category_of(scene, t, 0);
    if (c0 != category_of(scene, t, 1) || c0 != category_of(scene, t, 2)) {
      const Rgb mean = draw_split_triangle(cr, scene, t, p, light[t]);
      if (strength > 0) {
        triangle_path(cr, p);
        set_rgb(cr, scaled(mean, edge_shade * light[t]));
        cairo_set_line_width(cr, kEdgeWidth);
        cairo_stroke(cr);
      }
      continue;
    }
    const std::array<Rgb, 3> corners =
        c0 >= 0 ? std::array<Rgb, 3>{scene.categories[static_cast<std::size_t>(c0)].rgb,
                                     scene.categories[static_cast<std::size_t>(c0)].rgb,
                                     scene.categories[static_cast<std::size_t>(c0)].rgb}
                : colours.of(t);
    // A triangle seen edge-on or smaller than a quarter pixel: cairo's mesh rasterizer would
    // draw it as a line of full pixels; the antialiased fill shows it as it is.
    const Eigen::Vector2d u = p[1] - p[0], v = p[2] - p[0];
    const bool is_gouraud = is_raster && c0 < 0 && std::abs(u(0) * v(1) - u(1) * v(0)) > 0.5;
    std::array<Rgb, 3> lit;
    for (std::size_t k = 0; k < 3; ++k) {
      lit[k] = scaled(corners[k], is_gouraud ? vertex_light(triangle[k]) : light[t]);
    }
    const Rgb flat = mean_of(lit);
    const Rgb edge = scaled(flat, edge_shade);
    if (is_gouraud || is_raster) {
      triangle_path(cr, p);
      set_rgb(cr, flat);
      if (is_gouraud) {
        cairo_fill(cr);
        paint_gouraud(cr, p, lit);
      } else {
        // Antialiased neighbours leave a faint seam along shared edges; a thin stroke in the
        // fill's colour closes it.
        cairo_fill_preserve(cr);
        cairo_set_line_width(cr, kSeamStroke);
        cairo_stroke(cr);
        cairo_set_line_width(cr, kEdgeWidth);
      }
      if (strength > 0) {
        triangle_path(cr, p);
        set_rgb(cr, edge);
        cairo_stroke(cr);
      }
    } else if (strength > 0) {
      triangle_path(cr, p);  // one SVG element with its fill and its stroke
      set_rgb(cr, flat);
      cairo_fill_preserve(cr);
      set_rgb(cr, edge);
      cairo_stroke(cr);
    } else {
      // Vector output: the fill stroked thinly in its own colour closes the seams viewers leave
      // between antialiased neighbours (one element; svg_compaction.h names its colour once).
      // All triangles in one orientation on the screen, so that consecutive ones of one colour
      // merge into one path under the nonzero rule.
      std::array<Eigen::Vector2d, 3> oriented = p;
      if (u(0) * v(1) - u(1) * v(0) > 0) {
        std::swap(oriented[1], oriented[2]);
      }
      triangle_path(cr, oriented);
      set_rgb(cr, flat);
      cairo_fill_preserve(cr);
      cairo_set_line_width(cr, kSeamStroke);
      cairo_stroke(cr);
      cairo_set_line_width(cr, kEdgeWidth);
    }
  }
}

}  // namespace tessera::picture_detail
