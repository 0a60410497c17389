// SPDX-License-Identifier: MIT
#include "tessera/geometry/triangle_mesh.h"

#include <algorithm>

#include "tessera/core/error.h"

namespace tessera {

TriangleMesh::TriangleMesh(const Eigen::Ref<const Eigen::MatrixXd>& points,
                           std::vector<Triangle> triangles)
    : dimension_(static_cast<int>(points.rows())),
      coordinates_(static_cast<std::size_t>(points.size())),
      triangles_(std::move(triangles)) {
  Eigen::Map<Eigen::MatrixXd>(coordinates_.data(), points.rows(), points.cols()) = points;
}

int TriangleMesh::add_vertex(const Eigen::Ref<const Eigen::VectorXd>& x) {
  TESSERA_CHECK(x.size() == dimension_,
                "vertex has " << x.size() << " coordinates, mesh is in R^" << dimension_);
  coordinates_.insert(coordinates_.end(), x.data(), x.data() + x.size());
  return vertex_count() - 1;
}

int TriangleMesh::add_triangle(int a, int b, int c) {
  triangles_.push_back({a, b, c});
  return triangle_count() - 1;
}

TriangleMesh TriangleMesh::copy_with_room(int extra_vertices, int extra_triangles) const {
  TriangleMesh copy(dimension_);
  copy.reserve(vertex_count() + extra_vertices, triangle_count() + extra_triangles);
  copy.coordinates_.assign(coordinates_.begin(), coordinates_.end());
  copy.triangles_.assign(triangles_.begin(), triangles_.end());
  return copy;
}

void TriangleMesh::reserve(int vertices, int triangles) {
  coordinates_.reserve(static_cast<std::size_t>(vertices) * dimension_);
  triangles_.reserve(triangles);
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
      const auto from = coordinates_.begin() + static_cast<std::ptrdiff_t>(v) * dimension_;
      std::copy(from, from + dimension_,
                coordinates_.begin() + static_cast<std::ptrdiff_t>(count) * dimension_);
      new_index[v] = count++;
    }
  }
  coordinates_.resize(static_cast<std::size_t>(count) * dimension_);
  for (Triangle& triangle : kept) {
    for (int& v : triangle) {
      v = new_index[v];
    }
  }
  triangles_ = std::move(kept);
  return new_index;
}

}  // namespace tessera
