// SPDX-License-Identifier: MIT
// FrontState's holes: a short loop of the front filled by the triangulation of largest
// minimum angle (front_loop, triangulate_hole).
#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <limits>
#include <map>
#include <utility>

#include "tessera/geometry/mesh_quality.h"
#include "tessera/geometry/planar.h"
#include "tessera/methods/front/front_state.h"

namespace tessera {

std::vector<int> FrontState::front_loop(int v, int max_length) const {
  std::vector<int> loop{v};
  int current = v;
  while (true) {
    const auto chains = fan_chains(current);
    if (chains.size() != 1 || chains[0].is_closed) {
      return {};
    }
    current = chains[0].vertices.front();
    if (current == v) {
      return loop;
    }
    if (static_cast<int>(loop.size()) >= max_length) {
      return {};
    }
    loop.push_back(current);
  }
}

bool FrontState::triangulate_hole(const std::vector<int>& loop, const Eigen::MatrixXd& U,
                                  double min_angle) {
  // The hole lies to the left of the reversed loop: polygon (v0, v_{L−1}, …, v1) is
  // counterclockwise in U, and each triangle (p_i, p_j, p_k), i < j < k, keeps that orientation.
  std::vector<int> polygon{loop[0]};
  for (std::size_t i = loop.size() - 1; i >= 1; --i) {
    polygon.push_back(loop[i]);
  }
  const int L = static_cast<int>(polygon.size());
  std::vector<Eigen::Vector2d> planar;
  // Split states: the smallest angle of every triangle the search may try, from the Gram
  // matrices of its sides summed in one reduction (corner_angle's formula).
  std::map<Triangle, double> split_smallest_angle;
  if (space_->is_distributed()) {
    const Eigen::Matrix2Xd y = split_tangent_coordinates(U, polygon[0], polygon);
    for (Eigen::Index j = 0; j < y.cols(); ++j) {
      planar.push_back(y.col(j));
    }
    std::vector<Triangle> candidates;
    std::vector<double> products;  // per corner: u·w, |u|², |w|²
    for (int i = 0; i < L; ++i) {
      for (int j = i + 1; j < L; ++j) {
        for (int k = j + 1; k < L; ++k) {
          const Triangle t{polygon[i], polygon[j], polygon[k]};
          candidates.push_back(t);
          for (int r = 0; r < 3; ++r) {
            const auto apex = point(t[r]);
            const auto u = point(t[(r + 1) % 3]) - apex;
            const auto w = point(t[(r + 2) % 3]) - apex;
            products.insert(products.end(), {u.dot(w), u.squaredNorm(), w.squaredNorm()});
          }
        }
      }
    }
    if (!products.empty()) {
      space_->sum(products.data(), static_cast<int>(products.size()));
    }
    for (std::size_t c = 0; c < candidates.size(); ++c) {
      double smallest = std::numeric_limits<double>::infinity();
      for (std::size_t r = 0; r < 3; ++r) {
        const double* g = &products[9 * c + 3 * r];
        const double wedge = std::sqrt(std::max(0.0, g[1] * g[2] - g[0] * g[0]));
        smallest = std::min(smallest, std::atan2(wedge, g[0]));
      }
      split_smallest_angle[candidates[c]] = smallest;
    }
  } else {
    const Eigen::VectorXd center = point(polygon[0]);
    for (int p : polygon) {
      planar.push_back(U.transpose() * (point(p) - center));
    }
  }
  std::vector<Triangle> best;
  double best_score = -1.0;
  std::vector<Triangle> current;
  // Enumerate the triangulations of the sub-polygon [i, k] by the apex j of edge (i, k).
  std::function<void(std::vector<std::pair<int, int>>)> search =
      [&](std::vector<std::pair<int, int>> pending) {
        if (pending.empty()) {
          double score = std::numeric_limits<double>::infinity();
          for (const Triangle& t : current) {
            if (space_->is_distributed()) {
              score = std::min(score, split_smallest_angle.at(t));
              continue;
            }
            for (int r = 0; r < 3; ++r) {
              score = std::min(
                  score, corner_angle(point(t[r]), point(t[(r + 1) % 3]), point(t[(r + 2) % 3])));
            }
          }
          if (score > best_score) {
            best_score = score;
            best = current;
          }
          return;
        }
        const auto [i, k] = pending.back();
        pending.pop_back();
        if (k - i < 2) {
          search(pending);
          return;
        }
        for (int j = i + 1; j < k; ++j) {
          if (cross(planar[j] - planar[i], planar[k] - planar[i]) <= 0) {
            continue;
          }
          // A diagonal that already is a mesh edge would create a non-manifold edge.
          const bool diagonal_ij = j - i > 1;
          const bool diagonal_jk = k - j > 1;
          if ((diagonal_ij && are_adjacent(polygon[i], polygon[j])) ||
              (diagonal_jk && are_adjacent(polygon[j], polygon[k]))) {
            continue;
          }
          current.push_back({polygon[i], polygon[j], polygon[k]});
          auto next = pending;
          next.emplace_back(i, j);
          next.emplace_back(j, k);
          search(next);
          current.pop_back();
        }
      };
  if (L == 3 && are_adjacent(polygon[1], polygon[2]) && !can_add_edge(polygon[1], polygon[2])) {
    return false;
  }
  search({{0, L - 1}});
  if (best.empty() || best_score < min_angle) {
    return false;
  }
  for (const Triangle& t : best) {
    add_triangle(t[0], t[1], t[2]);
  }
  for (int p : polygon) {
    if (types_[p] == VertexType::Frontal) {
      // Their fans are now closed; processing them would find nothing to do.
      set_type(p, VertexType::Interior);
    }
  }
  return true;
}

}  // namespace tessera
