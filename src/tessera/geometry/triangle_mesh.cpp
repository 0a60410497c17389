// SPDX-License-Identifier: MIT
#include "tessera/geometry/triangle_mesh.h"

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
  TESSERA_CHECK(x.size() == dimension_, "vertex has " << x.size() << " coordinates, mesh is in R^"
                                                      << dimension_);
  coordinates_.insert(coordinates_.end(), x.data(), x.data() + x.size());
  return vertex_count() - 1;
}

int TriangleMesh::add_triangle(int a, int b, int c) {
  triangles_.push_back({a, b, c});
  return triangle_count() - 1;
}

void TriangleMesh::reserve(int vertices, int triangles) {
  coordinates_.reserve(static_cast<std::size_t>(vertices) * dimension_);
  triangles_.reserve(triangles);
}

}  // namespace tessera
