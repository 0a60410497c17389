// SPDX-License-Identifier: MIT
// A triangle mesh whose vertices are points of R^n.
#pragma once

#include <Eigen/Core>
#include <array>
#include <memory>
#include <vector>

#include "tessera/core/ambient_space.h"
#include "tessera/core/point_storage.h"

namespace tessera {

/// Three vertex indices; their order defines the orientation of the triangle.
using Triangle = std::array<int, 3>;

/// Vertices in R^n (stored as the columns of an n×N matrix) and oriented triangles.
///
/// This is a plain container: topology (edges, adjacency, boundary loops) is computed by
/// MeshTopology, checks by validate(), measures by measure_quality().
class TriangleMesh {
 public:
  TriangleMesh() = default;
  explicit TriangleMesh(int ambient_dimension) : points_(ambient_dimension) {}
  /// \param points n×N matrix, one vertex per column. \param triangles indices into the columns.
  TriangleMesh(const Eigen::Ref<const Eigen::MatrixXd>& points, std::vector<Triangle> triangles);
  /// Takes the points over without copying them (at large n they are most of the memory).
  TriangleMesh(PointStorage points, std::vector<Triangle> triangles)
      : points_(std::move(points)), triangles_(std::move(triangles)) {}

  /// The rows of each stored point: n in one process; this rank's rows of a mesh whose points
  /// are split over the ranks of a distributed problem (SPMD, see set_space), whose n is then
  /// space().dimension().
  int ambient_dimension() const { return points_.dimension(); }
  /// Where the points live and how they are measured (AmbientSpace): R^n in one process unless
  /// set_space gave the split of a distributed problem. Geometry on the mesh (validate) reduces
  /// through it, so that every rank of a split mesh computes the same numbers.
  const AmbientSpace& space() const;
  std::shared_ptr<const AmbientSpace> shared_space() const;
  /// Declares the points to be this rank's rows of a distributed space.
  /// \pre space->local_rows() == ambient_dimension().
  void set_space(std::shared_ptr<const AmbientSpace> space);
  int vertex_count() const { return points_.size(); }
  int triangle_count() const { return static_cast<int>(triangles_.size()); }

  /// n×N view of all vertices (column j is vertex j).
  Eigen::Map<const Eigen::MatrixXd> points() const { return points_.matrix(); }
  Eigen::Map<const Eigen::VectorXd> point(int vertex) const { return points_.column(vertex); }
  Eigen::Map<Eigen::VectorXd> mutable_point(int vertex) { return points_.column(vertex); }
  const std::vector<Triangle>& triangles() const { return triangles_; }
  const Triangle& triangle(int t) const { return triangles_[t]; }

  /// Appends a vertex and returns its index. \pre x.size() == ambient_dimension().
  int add_vertex(const Eigen::Ref<const Eigen::VectorXd>& x);
  /// Appends a triangle and returns its index. Indices are not checked here; see validate().
  int add_triangle(int a, int b, int c);
  /// Replaces all triangles.
  void set_triangles(std::vector<Triangle> triangles) { triangles_ = std::move(triangles); }
  void reserve(int vertices, int triangles);
  /// Drops the vertices from index `count` on (the last ones added), e.g. to undo an attempt.
  /// \pre no triangle refers to them.
  void truncate_vertices(int count);
  /// Keeps the triangles t with keep[t] (in order) and the vertices they use (in order).
  /// \return the new index of every old vertex, −1 for a vertex dropped.
  /// \pre keep.size() == triangle_count(), indices in range.
  std::vector<int> keep_triangles(const std::vector<bool>& keep);

 private:
  PointStorage points_;  // column-major n×N
  // Null: R^n in one process (made on first use, which is not thread-safe: the coverings run
  // in one thread; copies share it).
  mutable std::shared_ptr<const AmbientSpace> space_;
  std::vector<Triangle> triangles_;
};

}  // namespace tessera
