// SPDX-License-Identifier: MIT
// Pictures of a surface: shaded triangles seen from a camera, coloured by a quantity, with curves
// and points drawn over them, as PNG or SVG through cairo (one code path for both). Hidden
// surfaces by depth-sorted painting. The cairo headers stay in picture.cpp.
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "tessera/geometry/triangle_mesh.h"
#include "tessera/picture/picture_styles.h"

namespace tessera {

/// A polyline drawn over the surface (a boundary, a fold curve, a Hopf curve).
struct PictureCurve {
  Eigen::Matrix3Xd points;                    ///< 3×m, in the scene's coordinates
  bool is_closed = false;                     ///< the last point joins the first
  std::array<double, 3> rgb = {0.8, 0.1, 0.1};  ///< colour, components in [0, 1]
  double width = 2.0;                         ///< line width in pixels
  /// Where seen; a part hidden behind the surface is drawn thinner and finely dashed whatever
  /// its dash (Hopf curves: dashed, neutral saddle curves: dotted; see curve_style).
  CurveDash dash = CurveDash::Solid;
  std::string label;  ///< its legend entry (curves of one label share one); empty: none
};

/// A curve styled as its kind: points, rgb, width, dash and label of `style`.
PictureCurve styled_curve(Eigen::Matrix3Xd points, bool is_closed, const CurveStyle& style);

/// What is drawn: triangles in R³ (the three coordinates of a view), optionally values (viridis
/// and a colour bar), one per vertex or one per triangle, or a category per vertex or triangle
/// (its colour and a legend), curves and marked points.
struct PictureScene {
  Eigen::Matrix3Xd positions;  ///< 3×V vertex positions
  std::vector<Triangle> triangles;
  /// One value per vertex, or empty. A PNG interpolates the colours of the corners across each
  /// triangle (Gouraud shading, through cairo's mesh patterns); an SVG fills each triangle with
  /// the mean of its corners' colours (SVG has no such gradients that viewers draw alike, and
  /// cairo would embed them as a raster). A triangle with a NaN corner is grey.
  Eigen::VectorXd vertex_values;
  Eigen::VectorXd triangle_values;  ///< one per triangle, or empty (not with vertex_values)
  std::string value_label;          ///< the colour bar's title, e.g. "min angle (deg)"
  /// Categorical colouring (instead of values): the categories' colours and legend labels, and
  /// either one category (index into `categories`) per vertex or one per triangle.
  std::vector<PictureCategory> categories;
  /// One per vertex, or empty. A triangle whose corners agree is drawn in their colour; one
  /// whose corners differ is split through its edge midpoints and centroid into the three parts
  /// nearest to its corners (each corner's share of the barycentric dual cell), each in its
  /// corner's colour. So every vertex shows its category (a band one vertex wide does not
  /// vanish, as it would under a majority vote) and a boundary between categories runs midway
  /// between vertices that differ: within half an edge of the curve where the category changes
  /// (a fold or Hopf curve), which is as close as vertex data can place it.
  std::vector<int> vertex_categories;
  std::vector<int> triangle_categories;  ///< one per triangle, or empty
  std::vector<PictureCurve> curves;
  Eigen::Matrix3Xd markers;             ///< 3×k marked points (e.g. cusps); may be 3×0
  std::vector<PointKind> marker_kinds;  ///< k shapes, or empty: every marker Generic (a dot)
  /// The names of the three coordinates: the axes' labels, e.g. {"lambda", "epsilon", "max_u"}.
  std::array<std::string, 3> axis_names = {"x", "y", "z"};
};

/// Colours `scene` by stability: categories = stability_categories(), vertex_categories from
/// stability_category of each vertex's count of unstable eigenvalues (−1 or NaN: unknown).
/// Clears triangle_values and triangle_categories.
/// \throw InvalidArgument if unstable_counts.size() != scene.positions.cols() (naming both).
void colour_by_stability(PictureScene& scene, const std::vector<double>& unstable_counts);

/// PictureAspect::Automatic keeps equal scales up to this ratio of the largest to the smallest
/// axis extent (`tessera render --help` quotes it). Geometry stays below it (a torus of R/r = 9
/// has 10; at 4 a torus of R = 2, r = 0.5 was drawn as a barrel), continuation views lie far
/// above it (bvp:points=100 in (λ, ε, max u): 66; cstr in (x1, x2, Da): 27).
constexpr double kMaxEqualAspectRatio = 10.0;

/// How the axes of the scene are scaled before the camera looks at it.
enum class PictureAspect {
  /// Equal scales where the axes' extents are comparable (within kMaxEqualAspectRatio:
  /// geometry, e.g. a torus up to R/r = 9), else each axis scaled to its own extent
  /// (continuation views such as (λ, ε, max u), whose axes have unrelated units: bvp 66, cstr
  /// 27).
  Automatic,
  Equal,  ///< one scale for all three axes
  Box,    ///< each axis scaled to the same length: the bounding box becomes a cube
};

/// Which edges of the triangles are drawn.
enum class PictureEdges {
  /// Where the triangles are large enough on the screen to show them: none while the median
  /// edge is shorter than 6 pixels (a dense mesh would only be darkened by its edges), faint
  /// from there, full at 14 pixels and above.
  Automatic,
  On,   ///< every edge, in a darker shade of its face
  Off,  ///< none
};

/// What tells the reader the scale and the names of the axes.
enum class PictureAxes {
  /// Ticked where the axes have units to read (a continuation view, whose axes are scaled
  /// apart: see PictureAspect; a map seen from straight above), else the triad.
  Automatic,
  /// Axes along three edges of the bounding box with ticks at round values (1, 2 or 5 × 10^k),
  /// their labels and the axes' names, over light back panes with grid lines, as matplotlib's
  /// 3-D axes; the camera is fitted so that every label lies inside the picture.
  Ticked,
  Triad,  ///< a small triad naming the axes, at the lower left or beneath the colour bar
  Off,
};

struct PictureOptions {
  int width = 800;   ///< pixels (SVG: points)
  int height = 600;
  /// The camera looks from direction (cos e cos a, cos e sin a, sin e) at the scene's centre:
  /// a = azimuth about the third axis, e = elevation above the plane of the first two.
  double azimuth_degrees = -60.0;
  double elevation_degrees = 30.0;
  /// Look from best_view_direction (view_direction.h) instead of the two angles above: the
  /// direction that shows most of a folded surface (callers set it for continuation views when
  /// no angles were asked for).
  bool choose_view = false;
  double zoom = 1.0;         ///< 1: the surface fills the frame with a small margin
  bool perspective = false;  ///< else orthographic
  PictureEdges edges = PictureEdges::Automatic;
  bool colour_bar = true;  ///< when the scene has values
  /// The legend: at the right (in the colour bar's place) for a categorical scene, listing the
  /// categories, the labelled curves and the kinds of markers; else, when there are labelled
  /// curves or markers of a kind, in a box at the upper left.
  bool legend = true;
  PictureAxes axes = PictureAxes::Automatic;
  /// No shading: every triangle in its colour as it is (maps of data seen from above, where
  /// light would only darken steep triangles).
  bool flat_shading = false;
  PictureAspect aspect = PictureAspect::Automatic;
  std::array<double, 3> surface_rgb = {0.62, 0.72, 0.86};  ///< without values
  std::array<double, 3> background_rgb = {1.0, 1.0, 1.0};
  std::string title;
};

/// A raster picture: `pixels` row by row from the top, 0xAARRGGBB (cairo's ARGB32, opaque).
struct PictureImage {
  int width = 0;
  int height = 0;
  std::vector<std::uint32_t> pixels;
  std::uint32_t at(int x, int y) const {
    return pixels[static_cast<std::size_t>(y) * static_cast<std::size_t>(width) +
                  static_cast<std::size_t>(x)];
  }
};

/// The scene drawn into an image (what write_picture writes as PNG).
/// \throw InvalidArgument for a scene with no triangles, indices out of range, values or
///        categories of the wrong count or out of range (or values per vertex and per triangle,
///        or values and categories together),
///        marker kinds of the wrong count, non-finite positions (of vertices, curves or
///        markers), or options out of range (the message names them).
PictureImage render_picture(const PictureScene& scene, const PictureOptions& options);

/// A line of text as a picture places it: its words and its rectangle in pixels (y down).
struct PictureLabel {
  std::string text;
  double x0 = 0, y0 = 0, x1 = 0, y1 = 0;
};

/// How render_picture lays out a picture: what a caller or a test needs to know about it.
struct PictureLayout {
  double azimuth_degrees = 0;  ///< the camera's direction: given, or chosen (choose_view)
  double elevation_degrees = 0;
  PictureAxes axes = PictureAxes::Off;  ///< Ticked, Triad or Off (Automatic resolved)
  double edge_strength = 0;             ///< 0: no edges … 1: edges at full strength
  /// The axes' names and tick labels, the triad's names and the colour bar's labels and title,
  /// measured in the picture's font; none overlaps another or leaves the picture.
  std::vector<PictureLabel> labels;
};

/// The layout of the picture render_picture draws for these inputs.
/// \throw InvalidArgument as render_picture.
PictureLayout picture_layout(const PictureScene& scene, const PictureOptions& options);

/// Writes the picture to `path`: .png (raster) or .svg (vector; the same drawing), by extension
/// (case-insensitive); the file is replaced atomically. An SVG holds the title as `<title>` and
/// the legend's labels in `<desc>` (cairo draws text as outlines).
/// \throw InvalidArgument as render_picture, for another extension (naming both) and if the
///        file cannot be written.
void write_picture(const std::string& path, const PictureScene& scene,
                   const PictureOptions& options);

/// True if write_picture knows the extension of `path`.
bool is_picture_file(const std::string& path);

/// True if `aspect` scales each axis of `positions` (3×V) to its own extent: Box, or Automatic
/// where the largest extent exceeds the smallest nonzero one more than 10 times. Such are the
/// views of continuation problems (λ, ε, max u), whose axes have unrelated units; the picture
/// gives them ticked axes (PictureAxes::Automatic).
bool has_axes_scaled_apart(const Eigen::Matrix3Xd& positions, PictureAspect aspect);

/// The colour of `t` in [0, 1] in the viridis colour map (clamped), components in [0, 1].
std::array<double, 3> viridis(double t);

/// The boundary of a mesh as closed curves in the scene's positions (3×V), one per loop.
std::vector<PictureCurve> boundary_curves(const TriangleMesh& mesh_in_scene);

}  // namespace tessera
