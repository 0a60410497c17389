// SPDX-License-Identifier: MIT
// The two-parameter bifurcation diagram: fold, Hopf, neutral saddle and level curves and the
// special points (cusp, Bogdanov–Takens, zero-Hopf) projected on the parameter plane (p1, p2),
// with axes, ticks at round values, axis labels, a legend and a title, as PNG or SVG. The
// picture a continuation user draws with AUTO or MatCont; curves in the styles of
// picture_styles.h (fold solid, Hopf dashed, neutral saddle dotted).
#pragma once

#include <Eigen/Core>
#include <array>
#include <string>
#include <vector>

#include "tessera/io/polylines.h"
#include "tessera/picture/picture.h"
#include "tessera/picture/picture_styles.h"
#include "tessera/picture/ticks.h"  // nice_ticks, tick_labels

namespace tessera {

/// A curve in the parameter plane.
struct DiagramCurve {
  Eigen::Matrix2Xd points;  ///< 2×m: (p1, p2) of each point, in order
  bool is_closed = false;   ///< the last point joins the first
  CurveKind kind = CurveKind::Fold;
  std::string kind_name;  ///< for CurveKind::Other: its name (the legend's label)
};

/// A special point in the parameter plane.
struct DiagramPoint {
  Eigen::Vector2d point = Eigen::Vector2d::Zero();  ///< (p1, p2)
  PointKind kind = PointKind::Generic;
};

/// What the diagram shows.
struct BifurcationDiagramScene {
  std::vector<DiagramCurve> curves;
  std::vector<DiagramPoint> points;
  std::array<std::string, 2> parameter_names = {"p1", "p2"};  ///< the axis labels
};

struct BifurcationDiagramOptions {
  int width = 800;  ///< pixels (SVG: points), 16 … 20000
  int height = 600;
  std::string title;   ///< above the axes; none when empty
  bool legend = true;  ///< the curve kinds and point kinds that occur, at the right
  /// Margin around the data inside the axes, as a fraction of the data's extent on each axis,
  /// so that curves and markers at the extremes do not lie on the frame.
  double margin = 0.05;
};

/// Where the diagram's axes box lies in the picture and which values it spans: what a test or a
/// caller needs to place a point on the picture.
struct DiagramLayout {
  double left = 0, top = 0, right = 0, bottom = 0;  ///< the axes box in pixels (y down)
  std::array<double, 2> p1_range = {0, 1};          ///< p1 at the left and right edge
  std::array<double, 2> p2_range = {0, 1};          ///< p2 at the bottom and top edge
  std::vector<double> p1_ticks, p2_ticks;           ///< the ticks drawn and labelled
  /// The pixel of (p1, p2) (x right, y down).
  Eigen::Vector2d pixel(const Eigen::Vector2d& p) const;
};

/// Adds polylines as written by write_polylines (columns `options.names`, curve kind
/// `options.kind`, marked points of kind `options.marker_name`) to `scene`: their columns named
/// `p1` and `p2` as curves, their marked points as special points. What the mesh command holds
/// in memory and what `tessera render --diagram` reads from files go through here alike.
/// \throw InvalidArgument if `p1` or `p2` is not among options.names (the message lists them),
///        or a polyline's row count differs from the names'.
void add_to_diagram(BifurcationDiagramScene& scene, const std::vector<Polyline>& polylines,
                    const PolylineFileOptions& options, const std::string& p1,
                    const std::string& p2);

/// The layout render_bifurcation_diagram and write_bifurcation_diagram use for these inputs.
/// \throw InvalidArgument as render_bifurcation_diagram.
DiagramLayout bifurcation_diagram_layout(const BifurcationDiagramScene& scene,
                                         const BifurcationDiagramOptions& options);

/// The diagram drawn into an image (what write_bifurcation_diagram writes as PNG).
/// \throw InvalidArgument for a scene with no curve points and no special points, a point that
///        is not finite, or a size out of range (the message names it).
PictureImage render_bifurcation_diagram(const BifurcationDiagramScene& scene,
                                        const BifurcationDiagramOptions& options);

/// Writes the diagram to `path`: .png or .svg by extension (case-insensitive), replacing the
/// file atomically; an SVG holds the title as `<title>` and the legend's labels in `<desc>`.
/// \throw InvalidArgument as render_bifurcation_diagram, for another extension, and if the file
///        cannot be written.
void write_bifurcation_diagram(const std::string& path, const BifurcationDiagramScene& scene,
                               const BifurcationDiagramOptions& options);

}  // namespace tessera
