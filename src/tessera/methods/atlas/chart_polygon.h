// SPDX-License-Identifier: MIT
// The region of one chart's tangent plane that the chart is responsible for: a convex polygon
// cut by the half-planes of its neighbours (Henderson's later "polyhedron" representation).
#pragma once

#include <utility>
#include <vector>

namespace tessera {

/// A convex polygon in the (s, t) coordinates of a chart's tangent plane, counter-clockwise.
/// Edge i runs from vertex i to vertex i+1 and remembers what made it: the index of the
/// neighbouring chart whose half-plane cut it, or kNoNeighbour for the initial square.
class ChartPolygon {
 public:
  static constexpr int kNoNeighbour = -1;

  struct Vertex {
    double s = 0.0;
    double t = 0.0;
    int edge_label = kNoNeighbour;  ///< label of the edge from this vertex to the next
  };

  ChartPolygon() = default;
  /// The square [−half_width, half_width]², every edge labelled kNoNeighbour.
  explicit ChartPolygon(double half_width);
  /// A polygon as vertices() returned it (a checkpoint's).
  static ChartPolygon from_vertices(std::vector<Vertex> vertices) {
    ChartPolygon polygon;
    polygon.vertices_ = std::move(vertices);
    return polygon;
  }

  /// Keeps {p : normal·p ≤ offset}; the new edge on the line gets `label`.
  /// \return true if the polygon changed.
  bool cut(double normal_s, double normal_t, double offset, int label);

  const std::vector<Vertex>& vertices() const { return vertices_; }
  bool is_empty() const { return vertices_.size() < 3; }

  /// Index of the vertex farthest from the origin if it lies outside the disk of `radius`
  /// (an "exterior" vertex: the chart does not cover that corner), else −1.
  int farthest_exterior_vertex(double radius) const;

 private:
  std::vector<Vertex> vertices_;
};

}  // namespace tessera
