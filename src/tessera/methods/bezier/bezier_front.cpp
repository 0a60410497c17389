// SPDX-License-Identifier: MIT
// Method `bezier`: the bookkeeping of the triangulation (vertices, triangles, the front of free
// edges and its angles) and the final mesh with its patches.
#include "tessera/methods/bezier/bezier_builder.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>

#include "tessera/core/describe.h"
#include "tessera/core/error.h"
#include "tessera/geometry/pinched_vertices.h"

namespace tessera::detail {
namespace {


}  // namespace

std::vector<int> BezierBuilder::faces_of(const Eigen::VectorXd& y) const {
  std::vector<int> faces;
  for (int k = 0; k < static_cast<int>(domain_.half_spaces().size()); ++k) {
    if (std::abs(domain_.signed_distance(k, y)) <= 1e-9 * (1.0 + y.norm())) {
      faces.push_back(k);
    }
  }
  return faces;
}

bool BezierBuilder::is_boundary_edge(int a, int b) const {
  for (int k : vertices_[a].faces) {
    if (std::find(vertices_[b].faces.begin(), vertices_[b].faces.end(), k) !=
        vertices_[b].faces.end()) {
      return true;
    }
  }
  return false;
}

int BezierBuilder::third_vertex(int t, int a, int b) const {
  for (int v : triangles_[t]) {
    if (v != a && v != b) {
      return v;
    }
  }
  TESSERA_ASSERT(false);
  return -1;
}

int BezierBuilder::add_vertex(VertexData vertex) {
  // Section 5's step control sees only M. Across a band of M ∩ S narrower than the steps it
  // grows to (bvp near u = 0: 0.3 wide, steps up to 8 × 0.1), new points fall beyond the
  // opposite face and the front folds over itself; there the step is held to half its width
  // (never below the initial step).
  if (!domain_.is_unbounded()) {
    vertex.band_limit =
        std::max(options_.step, 0.5 * domain_.band_width(vertex.x, vertex.T, 2.0 * max_step_));
  }
  if (static_cast<int>(vertices_.size()) >= options_.max_vertices) {
    std::ostringstream message;
    message << "stopped at max_vertices = " << options_.max_vertices;
    throw StopRun{CoveringTermination::VertexLimit, message.str()};
  }
  if (options_.stop_requested && options_.stop_requested()) {
    throw StopRun{CoveringTermination::Interrupted,
                  "interrupted at " + std::to_string(vertices_.size()) + " vertices"};
  }
  vertices_.push_back(std::move(vertex));
  vertex_triangles_.emplace_back();
  front_out_.emplace_back();
  front_in_.emplace_back();
  if (options_.progress && progress_schedule_.is_due(static_cast<int>(vertices_.size()))) {
    CoveringProgress progress;
    progress.vertex_count = static_cast<int>(vertices_.size());
    progress.triangle_count = static_cast<int>(triangles_.size());
    progress.front_size = static_cast<int>(queue_.size());
    options_.progress(progress);
  }
  return static_cast<int>(vertices_.size()) - 1;
}

void BezierBuilder::update_front_membership(int v) {
  VertexData& data = vertices_[v];
  const bool front = is_front_vertex(v);
  if (front && !data.in_grid) {
    grid_.insert(v, data.x);
    data.in_grid = true;
    grid_.refit_if_due([this](int id) -> const Eigen::VectorXd& { return vertices_[id].x; });
  } else if (!front && data.in_grid) {
    grid_.remove(v, data.x);
    data.in_grid = false;
  }
}

void BezierBuilder::add_triangle(int i, int j, int k) {
  const int t = static_cast<int>(triangles_.size());
  triangles_.push_back({i, j, k});
  Eigen::MatrixXd corners(n_, 3);
  std::array<Eigen::MatrixXd, 3> bases;
  const std::array<int, 3> ids{i, j, k};
  for (int c = 0; c < 3; ++c) {
    longest_edge_ =
        std::max(longest_edge_, (vertices_[ids[c]].x - vertices_[ids[(c + 1) % 3]].x).norm());
    corners.col(c) = vertices_[ids[c]].x;
    bases[c] = vertices_[ids[c]].T;
  }
  // Eq. 3.5. The edge curve of edge (y_i, y_j) depends only on y_i, y_j, T_i and T_j, so the
  // patches of the two triangles at an edge share it: the cubic surface is continuous.
  patches_.push_back(CubicBezierPatch::interpolate_triangle_on_manifold(
      corners, bases, options_.edge_length_factor));
  for (int c = 0; c < 3; ++c) {
    const int u = ids[c];
    const int w = ids[(c + 1) % 3];
    TESSERA_ASSERT(!has_edge(u, w));
    edge_triangle_[edge_key(u, w)] = t;
    vertex_triangles_[u].push_back(t);
    if (has_edge(w, u)) {
      // w→u was free: the new triangle closes it.
      auto& out = front_out_[w];
      out.erase(std::remove(out.begin(), out.end(), u), out.end());
      auto& in = front_in_[u];
      in.erase(std::remove(in.begin(), in.end(), w), in.end());
    } else {
      front_out_[u].push_back(w);
      front_in_[w].push_back(u);
    }
  }
  for (int v : ids) {
    update_front_membership(v);
  }
  for (int v : ids) {
    push_edges_of(v);
  }
}

void BezierBuilder::push_edges_of(int v) {
  const auto push = [&](int a, int b) {
    if (!is_boundary_edge(a, b)) {
      queue_.push({front_angle(a, b), a, b});
    }
  };
  for (int w : front_out_[v]) {
    push(v, w);
  }
  for (int u : front_in_[v]) {
    push(u, v);
  }
}

double BezierBuilder::wedge_angle(int v, int u, int c, int w) const {
  // In the tangent plane at v: the triangle at edge (v, u) lies between directions u and c;
  // the unfilled side is the other one. Returns the angle from u to w through that side.
  const Eigen::MatrixXd& T = vertices_[v].T;
  const Eigen::VectorXd& x = vertices_[v].x;
  const Eigen::Vector2d pu = T.transpose() * (vertices_[u].x - x);
  const Eigen::Vector2d pc = T.transpose() * (vertices_[c].x - x);
  const Eigen::Vector2d pw = T.transpose() * (vertices_[w].x - x);
  const auto angle_from_u = [&](const Eigen::Vector2d& p) {
    return std::atan2(cross(pu, p), pu.dot(p));
  };
  const double side = angle_from_u(pc) >= 0 ? -1.0 : 1.0;
  double angle = side * angle_from_u(pw);
  if (angle < 0) {
    angle += 2 * std::numbers::pi;
  }
  return angle;
}

std::optional<int> BezierBuilder::previous_on_front(int a, int b, int c) const {
  // The free edge p→a that bounds the unfilled wedge at a next to a→b (at a pinched vertex
  // there are several; the one with the smallest wedge is the neighbour).
  std::optional<int> best;
  double best_angle = std::numeric_limits<double>::infinity();
  for (int p : front_in_[a]) {
    if (p == b) {
      continue;
    }
    const double angle = wedge_angle(a, b, c, p);
    if (angle < best_angle) {
      best_angle = angle;
      best = p;
    }
  }
  return best;
}

std::optional<int> BezierBuilder::next_on_front(int a, int b, int c) const {
  std::optional<int> best;
  double best_angle = std::numeric_limits<double>::infinity();
  for (int q : front_out_[b]) {
    if (q == a) {
      continue;
    }
    const double angle = wedge_angle(b, a, c, q);
    if (angle < best_angle) {
      best_angle = angle;
      best = q;
    }
  }
  return best;
}

double BezierBuilder::front_angle(int a, int b) const {
  const int c = third_vertex(edge_triangle_.at(edge_key(a, b)), a, b);
  double angle = 2 * std::numbers::pi;
  if (const auto p = previous_on_front(a, b, c)) {
    angle = std::min(angle, wedge_angle(a, b, c, *p));
  }
  if (const auto q = next_on_front(a, b, c)) {
    angle = std::min(angle, wedge_angle(b, a, c, *q));
  }
  const auto it = failures_.find(edge_key(a, b));
  return angle + (it == failures_.end() ? 0.0 : 4 * std::numbers::pi * it->second);
}

std::vector<int> BezierBuilder::front_vertices_near(const Eigen::VectorXd& x, double radius) const {
  return grid_.near(x, std::min(radius, search_radius_),
                    [&](int id) -> const Eigen::VectorXd& { return vertices_[id].x; });
}

void BezierBuilder::extract(CoveringResult& result) const {
  // A partial run may leave pinched vertices (two fans meeting at a vertex, a state the
  // completed run always resolves): keep the largest fan there, so that the mesh is valid.
  const std::vector<bool> keep = keep_largest_fans(static_cast<int>(vertices_.size()), triangles_);
  std::vector<int> new_index(vertices_.size(), -1);
  std::vector<Triangle> triangles;
  for (std::size_t t = 0; t < triangles_.size(); ++t) {
    if (!keep[t]) {
      continue;
    }
    Triangle tri = triangles_[t];
    for (int& v : tri) {
      if (new_index[v] < 0) {
        new_index[v] = 0;
      }
    }
    triangles.push_back(tri);
    result.patches.push_back(patches_[t]);
  }
  int count = 0;
  for (int& index : new_index) {
    if (index >= 0) {
      index = count++;
    }
  }
  Eigen::MatrixXd points(n_, count);
  for (std::size_t v = 0; v < vertices_.size(); ++v) {
    if (new_index[v] >= 0) {
      points.col(new_index[v]) = vertices_[v].x;
    }
  }
  for (Triangle& tri : triangles) {
    for (int& v : tri) {
      v = new_index[v];
    }
  }
  result.mesh = TriangleMesh(points, std::move(triangles));
}

}  // namespace tessera::detail
