// SPDX-License-Identifier: MIT
// A triangulation of points in the plane carrying one data value per point, with the
// triangle adjacency needed to swap diagonals.
#pragma once

#include <Eigen/Core>
#include <array>
#include <string>
#include <vector>

#include "tessera/geometry/triangle_mesh.h"

namespace tessera {

/// The quadrilateral around an interior edge: the edge runs from `a` to `b`; the triangle on
/// its left is (a, b, c) and the one on its right is (b, a, d), both counter-clockwise. The
/// other diagonal is c–d.
struct EdgeQuadrilateral {
  int a = -1;
  int b = -1;
  int c = -1;
  int d = -1;
};

/// Points of the plane (columns of a 2×N matrix), a value z_i at each point, and
/// counter-clockwise triangles with their neighbours.
///
/// Local edge k of triangle t = (t0, t1, t2) runs from t[k] to t[(k+1) % 3], as in
/// MeshTopology; neighbour(t, k) is the triangle across that edge, or -1 on the boundary.
/// Swapping keeps the vertex set, the boundary edges and counter-clockwise orientation.
class PlanarTriangulation {
 public:
  PlanarTriangulation() = default;
  /// \param points 2×N, one point per column. \param values N data values (z_i at point i).
  /// \param triangles counter-clockwise, edge-manifold (each edge in at most two triangles,
  ///        traversed in opposite directions).
  /// \throw InvalidArgument if a shape is wrong, an index is out of range, a triangle is not
  ///        strictly counter-clockwise or an edge is not manifold (the message names it).
  PlanarTriangulation(const Eigen::Ref<const Eigen::Matrix2Xd>& points,
                      const Eigen::Ref<const Eigen::VectorXd>& values,
                      std::vector<Triangle> triangles);

  int vertex_count() const { return static_cast<int>(points_.cols()); }
  int triangle_count() const { return static_cast<int>(triangles_.size()); }
  /// 2×N: column i is point i.
  const Eigen::Matrix2Xd& points() const { return points_; }
  Eigen::Vector2d point(int vertex) const { return points_.col(vertex); }
  const Eigen::VectorXd& values() const { return values_; }
  double value(int vertex) const { return values_[vertex]; }
  /// Replaces the data values (the triangles are kept). \pre values.size() == vertex_count().
  void set_values(const Eigen::Ref<const Eigen::VectorXd>& values);

  const std::vector<Triangle>& triangles() const { return triangles_; }
  const Triangle& triangle(int t) const { return triangles_[t]; }
  /// Triangle across local edge k of t, or -1 if that edge is on the boundary.
  int neighbour(int t, int k) const { return neighbours_[t][k]; }
  bool is_interior_edge(int t, int k) const { return neighbours_[t][k] >= 0; }

  /// The quadrilateral of the interior local edge k of t (a = t[k], b = t[k+1], c = t[k+2]).
  /// \pre is_interior_edge(t, k).
  EdgeQuadrilateral quadrilateral(int t, int k) const;
  /// True if the edge is interior and its quadrilateral is strictly convex, so that the other
  /// diagonal gives two non-degenerate counter-clockwise triangles. Orientation tests use a
  /// relative tolerance (see the .cpp): nearly flat corners count as not convex.
  bool is_swap_valid(int t, int k) const;
  /// Replaces the edge a–b of quadrilateral(t, k) by c–d. Afterwards t is (c, a, d) and its
  /// former neighbour u is (d, b, c): the new diagonal is local edge 2 of both, so
  /// swap(t, 2) undoes the swap. The neighbours of all four triangles are updated.
  /// \pre is_swap_valid(t, k) (checked; InvalidArgument otherwise).
  void swap(int t, int k);

  /// Every edge once, as {a, b} with a < b, boundary edges included.
  std::vector<std::array<int, 2>> edges() const;
  /// Boundary edges as directed pairs (the interior on their left), sorted.
  std::vector<std::array<int, 2>> boundary_edges() const;

  /// A mesh in R^3 with the values as z (for writing PLY files and for measures).
  TriangleMesh to_mesh() const;

  /// Checks orientation, adjacency symmetry and edge-manifoldness from scratch (O(N log N)).
  /// \param why if not null, receives the first defect found.
  bool is_valid(std::string* why = nullptr) const;

 private:
  void build_adjacency();

  Eigen::Matrix2Xd points_;
  Eigen::VectorXd values_;
  std::vector<Triangle> triangles_;
  std::vector<std::array<int, 3>> neighbours_;
};

/// Twice the signed area of (p, q, r): > 0 when counter-clockwise.
double orientation(const Eigen::Vector2d& p, const Eigen::Vector2d& q, const Eigen::Vector2d& r);

}  // namespace tessera
