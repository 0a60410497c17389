// SPDX-License-Identifier: MIT
#include "tessera/methods/components/component_coverage.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

namespace tessera {

Eigen::VectorXd closest_point_on_triangle(const Eigen::Ref<const Eigen::VectorXd>& p,
                                          const Eigen::Ref<const Eigen::VectorXd>& a,
                                          const Eigen::Ref<const Eigen::VectorXd>& b,
                                          const Eigen::Ref<const Eigen::VectorXd>& c) {
  // The Voronoi regions of the corners, then of the edges, then the face.
  const Eigen::VectorXd ab = b - a;
  const Eigen::VectorXd ac = c - a;
  const Eigen::VectorXd ap = p - a;
  const double d1 = ab.dot(ap);
  const double d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) {
    return a;
  }
  const Eigen::VectorXd bp = p - b;
  const double d3 = ab.dot(bp);
  const double d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) {
    return b;
  }
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) {
    return a + (d1 / (d1 - d3)) * ab;
  }
  const Eigen::VectorXd cp = p - c;
  const double d5 = ab.dot(cp);
  const double d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) {
    return c;
  }
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) {
    return a + (d2 / (d2 - d6)) * ac;
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
    return b + ((d4 - d3) / ((d4 - d3) + (d5 - d6))) * (c - b);
  }
  const double denominator = va + vb + vc;
  if (!(std::abs(denominator) > 0)) {  // a degenerate triangle: its nearest corner
    const double da = ap.squaredNorm();
    const double db = bp.squaredNorm();
    const double dc = cp.squaredNorm();
    return da <= db && da <= dc ? Eigen::VectorXd(a)
           : db <= dc           ? Eigen::VectorXd(b)
                                : Eigen::VectorXd(c);
  }
  return a + (vb / denominator) * ab + (vc / denominator) * ac;
}

ComponentCoverage::ComponentCoverage(const TriangleMesh& mesh, Eigen::VectorXd weights,
                                     double tolerance)
    : mesh_(mesh), weights_(std::move(weights)), tolerance_(tolerance) {}

Eigen::VectorXd ComponentCoverage::scaled(const Eigen::Ref<const Eigen::VectorXd>& x) const {
  return weights_.size() > 0 ? Eigen::VectorXd(weights_.cwiseProduct(x)) : Eigen::VectorXd(x);
}

void ComponentCoverage::add_component() {
  const int begin = component_ends_.empty() ? 0 : component_ends_.back();
  for (int t = begin; t < mesh_.triangle_count(); ++t) {
    const Triangle& triangle = mesh_.triangle(t);
    double longest = 0.0;
    for (int k = 0; k < 3; ++k) {
      const Eigen::VectorXd edge =
          scaled(mesh_.point(triangle[(k + 1) % 3]) - mesh_.point(triangle[k]));
      longest = std::max(longest, edge.norm());
    }
    longest_edges_.push_back(longest);
    longest_edge_ = std::max(longest_edge_, longest);
  }
  component_ends_.push_back(mesh_.triangle_count());
}

int ComponentCoverage::covering_component(const Eigen::Ref<const Eigen::VectorXd>& x) const {
  const int triangle_end = component_ends_.empty() ? 0 : component_ends_.back();
  if (triangle_end == 0) {
    return -1;
  }
  // A triangle within reach has its corners within reach + its longest edge of x: the
  // triangles with such a corner are the only candidates (one pass over the vertices).
  const double reach = kCoveredFraction * longest_edge_ + tolerance_;
  const double candidate_radius = reach + longest_edge_;
  const Eigen::VectorXd y = scaled(x);
  std::vector<bool> is_near(static_cast<std::size_t>(mesh_.vertex_count()), false);
  for (int v = 0; v < mesh_.vertex_count(); ++v) {
    const double distance = weights_.size() > 0 ? (weights_.cwiseProduct(mesh_.point(v)) - y).norm()
                                                : (mesh_.point(v) - y).norm();
    is_near[static_cast<std::size_t>(v)] = distance <= candidate_radius;
  }
  int found = -1;
  double nearest = std::numeric_limits<double>::infinity();
  int component = 0;
  for (int t = 0; t < triangle_end; ++t) {
    while (t >= component_ends_[static_cast<std::size_t>(component)]) {
      ++component;
    }
    const Triangle& triangle = mesh_.triangle(t);
    if (!is_near[static_cast<std::size_t>(triangle[0])] &&
        !is_near[static_cast<std::size_t>(triangle[1])] &&
        !is_near[static_cast<std::size_t>(triangle[2])]) {
      continue;
    }
    const Eigen::VectorXd a = scaled(mesh_.point(triangle[0]));
    const Eigen::VectorXd b = scaled(mesh_.point(triangle[1]));
    const Eigen::VectorXd c = scaled(mesh_.point(triangle[2]));
    const double distance = (closest_point_on_triangle(y, a, b, c) - y).norm();
    const double triangle_reach =
        kCoveredFraction * longest_edges_[static_cast<std::size_t>(t)] + tolerance_;
    if (distance <= triangle_reach && distance < nearest) {
      nearest = distance;
      found = component;
    }
  }
  return found;
}

}  // namespace tessera
