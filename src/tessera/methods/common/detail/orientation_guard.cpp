// SPDX-License-Identifier: MIT
#include "tessera/methods/common/detail/orientation_guard.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <memory>

#include "tessera/core/ambient_space.h"

namespace tessera::detail {
namespace {

// Twice the signed area of the triangle projected onto span T (T: n×2).
double projected_area(const Eigen::MatrixXd& T, const Corners& p) {
  const Eigen::Vector2d a = T.transpose() * (p[1] - p[0]);
  const Eigen::Vector2d b = T.transpose() * (p[2] - p[0]);
  return a(0) * b(1) - a(1) * b(0);
}

}  // namespace

Corners corners(const TriangleMesh& mesh, const Triangle& t) {
  return {mesh.point(t[0]), mesh.point(t[1]), mesh.point(t[2])};
}

std::vector<std::vector<int>> vertex_neighbours(const TriangleMesh& mesh) {
  std::vector<std::vector<int>> neighbours(mesh.vertex_count());
  for (const Triangle& t : mesh.triangles()) {
    for (int r = 0; r < 3; ++r) {
      neighbours[t[r]].push_back(t[(r + 1) % 3]);
      neighbours[t[r]].push_back(t[(r + 2) % 3]);
    }
  }
  for (auto& list : neighbours) {
    std::sort(list.begin(), list.end());
    list.erase(std::unique(list.begin(), list.end()), list.end());
  }
  return neighbours;
}

OrientationGuard::OrientationGuard(const ImplicitProblem& problem, const TriangleMesh& mesh,
                                   std::vector<std::vector<int>> neighbours)
    : problem_(problem),
      mesh_(mesh),
      space_(problem.space()),
      shares_factorisations_(problem.has_sparse_jacobian()),
      neighbours_(std::move(neighbours)),
      kept_(kMaxKept, kMaxKeptBytes) {}

const Linearization* OrientationGuard::at_vertex(int v, const Eigen::VectorXd& x) {
  if (const Linearization* own = cached(v)) {
    return own;
  }
  if (shares_factorisations_ && v < static_cast<int>(neighbours_.size())) {
    // A neighbour's factorisation, else one two edges away: the chord from there still
    // contracts fast (as the validation's tangent planes from three rings show), and for
    // sparse problems a factorisation costs tens of its solves.
    for (int u : neighbours_[v]) {
      if (const Linearization* near = cached(u)) {
        return near;
      }
    }
    for (int u : neighbours_[v]) {
      for (int w : neighbours_[u]) {
        if (const Linearization* near = cached(w)) {
          return near;
        }
      }
    }
    // A kept factorisation farther away (the vertices come in index order, not along M):
    // borrowed, where its tangent iteration converges.
    double longest = 0.0;
    for (int u : neighbours_[v]) {
      if (u < mesh_.vertex_count()) {
        longest = std::max(longest, space_->distance(mesh_.point(u), x));
      }
    }
    Linearization borrowed;
    if (lenders_.borrow(problem_, x, longest, borrowed)) {
      const Linearization* kept = kept_.keep(v, problem_, std::move(borrowed));
      remember_tangent(v, kept->tangent_basis());
      return kept;
    }
  }
  return factor_at(v, x);
}

bool OrientationGuard::keeps_orientation(int v, const Eigen::VectorXd& x, const Corners& before,
                                         const Corners& after) {
  auto found = tangents_.find(v);
  if (found == tangents_.end()) {
    // A neighbour's factorisation gives the plane by tangent_basis_near (one DF, a few
    // solves); the vertex's own where that does not converge.
    const Linearization* near = at_vertex(v, x);
    Eigen::MatrixXd T;
    bool is_own = near != nullptr && near->point() == x;
    if (near != nullptr && space_->is_distributed()) {
      is_own = space_->maximum(is_own ? 0.0 : 1.0) == 0.0;  // the same point on every rank
    }
    if (near == nullptr ||
        (!is_own && !tangent_basis_near(problem_, *near, x, T, kNearTangentTolerance))) {
      near = factor_at(v, x);
      if (near == nullptr) {
        return false;
      }
      T = near->tangent_basis();
    } else if (is_own) {
      T = near->tangent_basis();
    }
    remember_tangent(v, std::move(T));
    found = tangents_.find(v);
  }
  const Eigen::MatrixXd& T = found->second;
  if (space_->is_distributed()) {
    // The corners' tangent coordinates and the new edges' squared lengths: one reduction.
    std::array<double, 11> parts{};
    Eigen::Map<Eigen::Vector2d>(parts.data()) = T.transpose() * (before[1] - before[0]);
    Eigen::Map<Eigen::Vector2d>(parts.data() + 2) = T.transpose() * (before[2] - before[0]);
    Eigen::Map<Eigen::Vector2d>(parts.data() + 4) = T.transpose() * (after[1] - after[0]);
    Eigen::Map<Eigen::Vector2d>(parts.data() + 6) = T.transpose() * (after[2] - after[0]);
    for (int r = 0; r < 3; ++r) {
      parts[8 + r] = (after[(r + 1) % 3] - after[r]).squaredNorm();
    }
    space_->sum(parts.data(), 11);
    const double area_before = parts[0] * parts[3] - parts[1] * parts[2];
    const double area_after = parts[4] * parts[7] - parts[5] * parts[6];
    const double longest = std::max({parts[8], parts[9], parts[10]});
    return area_before * area_after > 0 && std::abs(area_after) > kMinAreaRatio * longest;
  }
  const double area_before = projected_area(T, before);
  const double area_after = projected_area(T, after);
  double longest = 0.0;
  for (int r = 0; r < 3; ++r) {
    longest = std::max(longest, (after[(r + 1) % 3] - after[r]).squaredNorm());
  }
  return area_before * area_after > 0 && std::abs(area_after) > kMinAreaRatio * longest;
}

const Linearization* OrientationGuard::cached(int v) const {
  const Linearization* found = kept_.find(v);
  return found != nullptr && found->is_factored() ? found : nullptr;
}

const Linearization* OrientationGuard::factor_at(int v, const Eigen::VectorXd& x) {
  if (!shares_factorisations_) {  // dense: as the cache factors, nothing to lend
    const Linearization* linearization = kept_.factor(v, problem_, x);
    if (linearization != nullptr) {
      remember_tangent(v, linearization->tangent_basis());
    }
    return linearization;
  }
  Linearization own;
  if (!own.factor(problem_, x)) {
    kept_.keep(v, problem_, std::move(own));  // rank deficient: not tried again
    return nullptr;
  }
  Linearization at_v;
  lenders_.keep(problem_, std::move(own), at_v);  // at_v: own where not worth sharing
  const Linearization* linearization = kept_.keep(v, problem_, std::move(at_v));
  remember_tangent(v, linearization->tangent_basis());
  return linearization;
}

void OrientationGuard::remember_tangent(int v, Eigen::MatrixXd T) {
  const std::size_t bytes = static_cast<std::size_t>(T.size()) * sizeof(double);
  if (tangents_.contains(v)) {
    return;
  }
  if (!tangents_.empty() && (tangents_.size() + 1) * bytes > kMaxTangentBytes) {
    tangents_.clear();  // the simplest bound: the next checks take again what they need
  }
  tangents_.emplace(v, std::move(T));
}

}  // namespace tessera::detail
