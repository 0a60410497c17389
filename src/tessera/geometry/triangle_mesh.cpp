// SPDX-License-Identifier: MIT
#include "tessera/geometry/triangle_mesh.h"

#include <algorithm>

#include "tessera/core/error.h"

namespace tessera {

TriangleMesh::TriangleMesh(const Eigen::Ref<const Eigen::MatrixXd>& points,
                           std::vector<Triangle> triangles)
    : points_(static_cast<int>(points.rows())), triangles_(std::move(triangles)) {
  points_.resize(static_cast<int>(points.cols()));
  if (points.size() > 0) {
    Eigen::Map<Eigen::MatrixXd>(points_.data(), points.rows(), points.cols()) = points;
  }
}

const AmbientSpace& TriangleMesh::space() const { return *shared_space(); }

std::shared_ptr<const AmbientSpace> TriangleMesh::shared_space() const {
  if (!space_ || (!space_->is_distributed() && space_->dimension() != ambient_dimension())) {
    space_ = std::make_shared<AmbientSpace>(ambient_dimension());
  }
  return space_;
}

void TriangleMesh::set_space(std::shared_ptr<const AmbientSpace> space) {
  TESSERA_CHECK(space && space->local_rows() == ambient_dimension(),
                "TriangleMesh::set_space: the space holds "
                    << (space ? space->local_rows() : 0) << " rows of each point, the mesh "
                    << ambient_dimension());
  space_ = std::move(space);
}

int TriangleMesh::add_vertex(const Eigen::Ref<const Eigen::VectorXd>& x) {
  TESSERA_CHECK(x.size() == ambient_dimension(), "vertex has " << x.size()
                                                              << " coordinates, mesh is in R^"
                                                              << ambient_dimension());
  points_.push_back(x);
  return vertex_count() - 1;
}

int TriangleMesh::add_triangle(int a, int b, int c) {
  triangles_.push_back({a, b, c});
  return triangle_count() - 1;
}

void TriangleMesh::reserve(int vertices, int triangles) {
  points_.reserve(vertices);
  triangles_.reserve(triangles);
}

void TriangleMesh::truncate_vertices(int count) {
  TESSERA_CHECK(count >= 0 && count <= vertex_count(),
                "truncate_vertices(" << count << ") of a mesh with " << vertex_count()
                                     << " vertices");
  points_.resize(count);
}

std::vector<int> TriangleMesh::keep_triangles(const std::vector<bool>& keep) {
  TESSERA_CHECK(
      static_cast<int>(keep.size()) == triangle_count(),
      "keep_triangles: " << keep.size() << " flags for " << triangle_count() << " triangles");
  std::vector<int> new_index(vertex_count(), -1);
  std::vector<Triangle> kept;
  for (int t = 0; t < triangle_count(); ++t) {
    if (keep[t]) {
      kept.push_back(triangles_[t]);
      for (int v : triangles_[t]) {
        new_index[v] = 0;
      }
    }
  }
  int count = 0;
  for (int v = 0; v < vertex_count(); ++v) {
    if (new_index[v] >= 0) {
      points_.move_column(v, count);
      new_index[v] = count++;
    }
  }
  points_.resize(count);
  for (Triangle& triangle : kept) {
    for (int& v : triangle) {
      v = new_index[v];
    }
  }
  triangles_ = std::move(kept);
  return new_index;
}

}  // namespace tessera
