// SPDX-License-Identifier: MIT
// The admissibility tests of a new triangle in Hohmann's continuation (ZIB SC 91-20, sections 4
// and 5): the angle between the new edges' tangents, no overlap with the mesh near it, and the
// distance of its new edges from M.
#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <vector>

#include "tessera/core/corrector.h"
#include "tessera/methods/bezier/bezier_builder.h"
#include "tessera/methods/bezier/bezier_plane_geometry.h"

namespace tessera::detail {

std::optional<double> BezierBuilder::worst_tangent_angle(int a, const NewPoint& point,
                                                         int b) const {
  // Section 4: |⟨t_ij, t_ji⟩| ≥ α_min on the two new real edges. Returns the largest angle
  // arccos|⟨t_ij, t_ji⟩| if it is too large, nullopt if both edges pass.
  double worst = 0.0;
  for (int v : {a, b}) {
    if (v < 0) {
      continue;
    }
    const Eigen::VectorXd t_vy = edge_tangent(vertices_[v].T, vertices_[v].x, point.vertex.x);
    const Eigen::VectorXd t_yv = edge_tangent(point.vertex.T, point.vertex.x, vertices_[v].x);
    worst = std::max(worst, std::acos(std::min(1.0, std::abs(t_vy.dot(t_yv)))));
  }
  if (std::cos(worst) >= options_.min_tangent_cosine) {
    return std::nullopt;
  }
  return worst;
}

bool BezierBuilder::overlaps_mesh(int a, int b, int v, const Eigen::VectorXd& y) const {
  // Does the triangle (a, b, y) overlap a triangle of the mesh near it? The test is in the
  // plane of the new triangle (the paper's local plane model), with triangles far from that
  // plane (another sheet of M) left out.
  const PlaneFrame plane(vertices_[a].x, vertices_[b].x, y);
  if (!plane.valid) {
    return true;
  }
  const std::array<Eigen::Vector2d, 3> P{plane.project(vertices_[a].x),
                                         plane.project(vertices_[b].x), plane.project(y)};
  const double size = std::max({(vertices_[a].x - vertices_[b].x).norm(),
                                (vertices_[a].x - y).norm(), (vertices_[b].x - y).norm()});
  const Eigen::VectorXd centroid = (vertices_[a].x + vertices_[b].x + y) / 3.0;
  // Every triangle that overlaps the new one has a vertex within size + (longest edge) of its
  // centroid, and one that overlaps it without crossing the front cannot exist.
  std::vector<int> nearby = front_vertices_near(centroid, size + longest_edge_);
  nearby.push_back(a);
  nearby.push_back(b);
  if (v >= 0) {
    nearby.push_back(v);
  }
  std::vector<int> checked;
  for (int w : nearby) {
    for (int t : vertex_triangles_[w]) {
      if (std::find(checked.begin(), checked.end(), t) != checked.end()) {
        continue;
      }
      checked.push_back(t);
      const Triangle& tri = triangles_[t];
      const Eigen::VectorXd c =
          (vertices_[tri[0]].x + vertices_[tri[1]].x + vertices_[tri[2]].x) / 3.0;
      const double size_q = std::max({(vertices_[tri[0]].x - vertices_[tri[1]].x).norm(),
                                      (vertices_[tri[1]].x - vertices_[tri[2]].x).norm(),
                                      (vertices_[tri[2]].x - vertices_[tri[0]].x).norm()});
      if (plane.offset(c) > 0.5 * std::max(size, size_q)) {
        continue;
      }
      const std::array<Eigen::Vector2d, 3> Q{plane.project(vertices_[tri[0]].x),
                                             plane.project(vertices_[tri[1]].x),
                                             plane.project(vertices_[tri[2]].x)};
      if (triangles_overlap(P, Q)) {
        return true;
      }
    }
  }
  return false;
}

double BezierBuilder::new_edges_distance(int a, int b, int v) const {
  // The distance to M of the midpoints of the edges (a, v) and (b, v) that do not exist yet,
  // estimated by one Gauss–Newton step from the midpoint.
  double distance = 0.0;
  Eigen::VectorXd F(n_ - 2), dx(n_);
  Linearization linearization;
  for (int end : {a, b}) {
    if (has_edge(end, v) || has_edge(v, end)) {
      continue;
    }
    const Eigen::VectorXd mid = 0.5 * (vertices_[end].x + vertices_[v].x);
    problem_.evaluate(mid, F);
    if (!F.allFinite() || !linearization.factor(problem_, mid)) {
      return std::numeric_limits<double>::infinity();
    }
    linearization.solve_minimum_norm(-F, dx);
    distance = std::max(distance, dx.norm());
  }
  return distance;
}

bool BezierBuilder::is_admissible(int a, int b, int c, int v, const Eigen::VectorXd& y) const {
  // Can triangle (b, a, v) be added at free edge a→b (whose triangle has third vertex c)?
  // Combinatorially: the edges a→v and v→b must be new (or close free edges v→a, b→v), so
  // every edge keeps at most two consistently oriented triangles.
  if (v >= 0 && (v == a || v == b || v == c || has_edge(a, v) || has_edge(v, b))) {
    return false;
  }
  // Geometrically: y lies on the unfilled side of a→b in the tangent planes at a and at b.
  for (int end : {a, b}) {
    const Eigen::MatrixXd& T = vertices_[end].T;
    const Eigen::VectorXd& x = vertices_[end].x;
    const int other = end == a ? b : a;
    const Eigen::Vector2d pe = T.transpose() * (vertices_[other].x - x);
    const Eigen::Vector2d pc = T.transpose() * (vertices_[c].x - x);
    const Eigen::Vector2d py = T.transpose() * (y - x);
    if (cross(pe, pc) * cross(pe, py) >= 0) {
      return false;
    }
  }
  return !overlaps_mesh(a, b, v, y);
}

}  // namespace tessera::detail
