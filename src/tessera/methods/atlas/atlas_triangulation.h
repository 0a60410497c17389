// SPDX-License-Identifier: MIT
// The triangulation of an atlas: the dual of its polygon complex, made valid where the charts
// disagree (section 6.2 of Henderson's paper, done after the fact instead of incrementally).
#pragma once

#include <Eigen/Core>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "tessera/geometry/triangle_mesh.h"
#include "tessera/methods/atlas/chart_polygon.h"

namespace tessera {

/// Read access to the charts of an atlas (kept abstract so that the triangulation can be
/// tested on hand-made polygons).
struct AtlasCells {
  int ambient_dimension = 0;  ///< rows of a centre (this rank's, when `space` is distributed)
  /// The split of R^n the centres and bases are rows of; null: R^n in one process.
  std::shared_ptr<const AmbientSpace> space;
  int chart_count = 0;
  std::function<Eigen::VectorXd(int)> center;   ///< n-vector on M
  std::function<Eigen::MatrixXd(int)> tangent;  ///< n×2 orthonormal basis of the chart's plane
  std::function<const ChartPolygon&(int)> polygon;
  std::function<double(int)> radius;
  /// The chart's polygon is finished: every edge comes from a neighbour and every vertex lies
  /// inside its disk. Only holes surrounded by closed charts are filled.
  std::function<bool(int)> is_closed;
  /// Optional: the centres of the charts marked, in chart order, handed over for the mesh's
  /// vertices without a copy (the last use of the centres). Without it they are copied.
  std::function<PointStorage(const std::vector<bool>&)> take_centers;
};

struct AtlasTriangulation {
  TriangleMesh mesh;       ///< vertices: the centres of the charts that carry triangles
  std::vector<double> radius;  ///< per mesh vertex: the radius of its chart
  int consistent_triangles = 0;  ///< emitted by all three of their charts
  int filled_holes = 0;    ///< places where the charts disagreed, triangulated afterwards
  int dropped_triangles = 0;  ///< removed so that every vertex has one fan (vertex-manifold)
  std::string message;     ///< non-empty if a hole between closed charts could not be filled
};

/// Every polygon vertex of chart i where the edges of neighbours j and k meet (inside i's
/// disk) proposes the triangle (i, j, k), counter-clockwise in i's tangent plane. A triangle
/// proposed by all three of its charts is kept. Where the charts' polygons disagree (nearly
/// cocircular centres, seen from three slightly different tangent planes) a small hole is
/// left; it is triangulated with the largest smallest angle, judged in R^n, among the
/// triangulations that are counter-clockwise in the tangent plane of one of its vertices and
/// repeat no existing edge. The result is edge-manifold and consistently oriented where the
/// charts' frames are.
AtlasTriangulation triangulate_atlas(const AtlasCells& cells);

}  // namespace tessera
