// SPDX-License-Identifier: MIT
// A triangulation of points in the plane carrying one data value per point, with the
// triangle adjacency needed to swap diagonals.
#include "tessera/methods/planar/planar_triangulation.h"

#include <algorithm>
#include <map>
#include <sstream>
#include <utility>

#include "tessera/core/error.h"

namespace tessera {
namespace {

// A corner whose doubled area is below this fraction of the squared size of the
// quadrilateral counts as flat: swapping there would create a sliver that rounding can turn
// over, so such quadrilaterals are treated as not strictly convex.
constexpr double kFlatRelativeArea = 1e-12;

}  // namespace

double orientation(const Eigen::Vector2d& p, const Eigen::Vector2d& q, const Eigen::Vector2d& r) {
  return (q.x() - p.x()) * (r.y() - p.y()) - (q.y() - p.y()) * (r.x() - p.x());
}

PlanarTriangulation::PlanarTriangulation(const Eigen::Ref<const Eigen::Matrix2Xd>& points,
                                         const Eigen::Ref<const Eigen::VectorXd>& values,
                                         std::vector<Triangle> triangles)
    : points_(points), values_(values), triangles_(std::move(triangles)) {
  TESSERA_CHECK(values_.size() == points_.cols(),
                "PlanarTriangulation: " << values_.size() << " values for " << points_.cols()
                                        << " points; need one value per point");
  const int n = vertex_count();
  for (int t = 0; t < triangle_count(); ++t) {
    const Triangle& tri = triangles_[t];
    for (int v : tri) {
      TESSERA_CHECK(v >= 0 && v < n, "PlanarTriangulation: triangle " << t << " has vertex " << v
                                                                      << " outside [0, " << n
                                                                      << ")");
    }
    TESSERA_CHECK(orientation(point(tri[0]), point(tri[1]), point(tri[2])) > 0,
                  "PlanarTriangulation: triangle " << t << " (" << tri[0] << ", " << tri[1] << ", "
                                                   << tri[2]
                                                   << ") is not strictly counter-clockwise");
  }
  build_adjacency();
}

void PlanarTriangulation::set_values(const Eigen::Ref<const Eigen::VectorXd>& values) {
  TESSERA_CHECK(values.size() == vertex_count(),
                "PlanarTriangulation::set_values: " << values.size() << " values for "
                                                    << vertex_count() << " points");
  values_ = values;
}

void PlanarTriangulation::build_adjacency() {
  // Directed edge (a, b) -> (triangle, local edge). A manifold, consistently oriented
  // triangulation has each directed edge at most once.
  std::map<std::pair<int, int>, std::pair<int, int>> directed;
  for (int t = 0; t < triangle_count(); ++t) {
    for (int k = 0; k < 3; ++k) {
      const int a = triangles_[t][k];
      const int b = triangles_[t][(k + 1) % 3];
      const bool inserted = directed.emplace(std::pair{a, b}, std::pair{t, k}).second;
      TESSERA_CHECK(inserted, "PlanarTriangulation: edge " << a << "→" << b
                                                           << " is used by two triangles in the "
                                                              "same direction (triangle "
                                                           << t << ")");
    }
  }
  neighbours_.assign(triangles_.size(), {-1, -1, -1});
  for (const auto& [edge, where] : directed) {
    const auto twin = directed.find({edge.second, edge.first});
    if (twin != directed.end()) {
      neighbours_[where.first][where.second] = twin->second.first;
    }
  }
}

EdgeQuadrilateral PlanarTriangulation::quadrilateral(int t, int k) const {
  const int u = neighbours_[t][k];
  TESSERA_ASSERT(u >= 0);
  const Triangle& tri = triangles_[t];
  EdgeQuadrilateral q{tri[k], tri[(k + 1) % 3], tri[(k + 2) % 3], -1};
  const Triangle& other = triangles_[u];
  for (int v : other) {
    if (v != q.a && v != q.b) {
      q.d = v;
    }
  }
  TESSERA_ASSERT(q.d >= 0);
  return q;
}

bool PlanarTriangulation::is_swap_valid(int t, int k) const {
  if (!is_interior_edge(t, k)) {
    return false;
  }
  const EdgeQuadrilateral q = quadrilateral(t, k);
  const Eigen::Vector2d a = point(q.a);
  const Eigen::Vector2d b = point(q.b);
  const Eigen::Vector2d c = point(q.c);
  const Eigen::Vector2d d = point(q.d);
  const double size = std::max((a - b).squaredNorm(), (c - d).squaredNorm());
  const double flat = kFlatRelativeArea * size;
  // The quadrilateral a, d, b, c (counter-clockwise) is strictly convex exactly when both new
  // triangles (c, a, d) and (d, b, c) are strictly counter-clockwise (the old ones are).
  return orientation(c, a, d) > flat && orientation(d, b, c) > flat;
}

void PlanarTriangulation::swap(int t, int k) {
  TESSERA_CHECK(is_swap_valid(t, k), "PlanarTriangulation::swap: edge " << k << " of triangle " << t
                                                                        << " is on the boundary "
                                                                           "or its quadrilateral "
                                                                           "is not strictly "
                                                                           "convex");
  const EdgeQuadrilateral q = quadrilateral(t, k);
  const int u = neighbours_[t][k];
  const auto local_edge = [this](int tri, int from, int to) {
    for (int j = 0; j < 3; ++j) {
      if (triangles_[tri][j] == from && triangles_[tri][(j + 1) % 3] == to) {
        return j;
      }
    }
    TESSERA_ASSERT(false);
    return -1;
  };
  const int n_ca = neighbours_[t][(k + 2) % 3];
  const int n_bc = neighbours_[t][(k + 1) % 3];
  const int n_ad = neighbours_[u][local_edge(u, q.a, q.d)];
  const int n_db = neighbours_[u][local_edge(u, q.d, q.b)];
  triangles_[t] = {q.c, q.a, q.d};
  triangles_[u] = {q.d, q.b, q.c};
  neighbours_[t] = {n_ca, n_ad, u};
  neighbours_[u] = {n_db, n_bc, t};
  // The edge a–d moved from u to t and b–c from t to u: their outer triangles must follow.
  if (n_ad >= 0) {
    neighbours_[n_ad][local_edge(n_ad, q.d, q.a)] = t;
  }
  if (n_bc >= 0) {
    neighbours_[n_bc][local_edge(n_bc, q.c, q.b)] = u;
  }
}

std::vector<std::array<int, 2>> PlanarTriangulation::edges() const {
  std::vector<std::array<int, 2>> result;
  for (int t = 0; t < triangle_count(); ++t) {
    for (int k = 0; k < 3; ++k) {
      const int a = triangles_[t][k];
      const int b = triangles_[t][(k + 1) % 3];
      // Interior edges are listed by the triangle that traverses them upwards only.
      if (neighbours_[t][k] < 0 || a < b) {
        result.push_back({std::min(a, b), std::max(a, b)});
      }
    }
  }
  std::sort(result.begin(), result.end());
  return result;
}

std::vector<std::array<int, 2>> PlanarTriangulation::boundary_edges() const {
  std::vector<std::array<int, 2>> result;
  for (int t = 0; t < triangle_count(); ++t) {
    for (int k = 0; k < 3; ++k) {
      if (neighbours_[t][k] < 0) {
        result.push_back({triangles_[t][k], triangles_[t][(k + 1) % 3]});
      }
    }
  }
  std::sort(result.begin(), result.end());
  return result;
}

TriangleMesh PlanarTriangulation::to_mesh() const {
  Eigen::MatrixXd xyz(3, vertex_count());
  xyz.topRows(2) = points_;
  xyz.row(2) = values_.transpose();
  return TriangleMesh(xyz, triangles_);
}

bool PlanarTriangulation::is_valid(std::string* why) const {
  const auto fail = [why](const std::string& message) {
    if (why != nullptr) {
      *why = message;
    }
    return false;
  };
  std::map<std::pair<int, int>, int> directed;
  for (int t = 0; t < triangle_count(); ++t) {
    const Triangle& tri = triangles_[t];
    for (int v : tri) {
      if (v < 0 || v >= vertex_count()) {
        return fail("triangle " + std::to_string(t) + " has an index out of range");
      }
    }
    if (!(orientation(point(tri[0]), point(tri[1]), point(tri[2])) > 0)) {
      return fail("triangle " + std::to_string(t) + " is not strictly counter-clockwise");
    }
    for (int k = 0; k < 3; ++k) {
      if (!directed.emplace(std::pair{tri[k], tri[(k + 1) % 3]}, t).second) {
        return fail("directed edge of triangle " + std::to_string(t) + " is used twice");
      }
    }
  }
  for (int t = 0; t < triangle_count(); ++t) {
    for (int k = 0; k < 3; ++k) {
      const int a = triangles_[t][k];
      const int b = triangles_[t][(k + 1) % 3];
      const auto twin = directed.find({b, a});
      const int expected = twin == directed.end() ? -1 : twin->second;
      if (neighbours_[t][k] != expected) {
        std::ostringstream message;
        message << "neighbour " << k << " of triangle " << t << " is " << neighbours_[t][k]
                << ", expected " << expected;
        return fail(message.str());
      }
    }
  }
  return true;
}

}  // namespace tessera
