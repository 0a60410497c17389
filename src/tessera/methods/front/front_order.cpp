// SPDX-License-Identifier: MIT
// The order in which the front takes its frontal points: the paper's FIFO queue, or smallest
// gap first with a term per layer behind the front and per deferral (FrontOrder,
// docs/algorithms/front.md, *Order*).
#include <cmath>
#include <limits>

#include "tessera/methods/front/front_builder.h"

namespace tessera::front_detail {

std::optional<int> FrontBuilder::next_frontal() {
  if (options_.order == FrontOrder::Fifo) {
    return state_.pop_frontal();
  }
  // Lazy priority queue: a popped key is re-checked and re-inserted if it went stale.
  while (!by_gap_.empty()) {
    const auto [key, v] = *by_gap_.begin();
    by_gap_.erase(by_gap_.begin());
    gap_key_[v] = std::numeric_limits<double>::quiet_NaN();
    if (state_.type(v) != VertexType::Frontal) {
      continue;
    }
    const double current = priority(v);
    if (current > key + 1e-12) {
      by_gap_.emplace(current, v);
      gap_key_[v] = current;
      continue;
    }
    return v;
  }
  // Vertices made frontal but never keyed (none expected): fall back to the FIFO queue.
  return state_.pop_frontal();
}

void FrontBuilder::refresh_priority(int v) {
  if (gap_key_.size() <= static_cast<std::size_t>(v)) {
    gap_key_.resize(v + 1, std::numeric_limits<double>::quiet_NaN());
  }
  if (!std::isnan(gap_key_[v])) {
    by_gap_.erase({gap_key_[v], v});
    gap_key_[v] = std::numeric_limits<double>::quiet_NaN();
  }
  if (state_.type(v) != VertexType::Frontal) {
    return;
  }
  gap_key_[v] = priority(v);
  by_gap_.emplace(gap_key_[v], v);
}

double FrontBuilder::priority(int v) {
  // Smallest gap first alone is blind to the front's shape at large scale: there, the gap angles
  // differ from π by O(h·curvature) only, far less than their local scatter, so at fine steps
  // the front wanders, grows fingers and narrow channels, and meets itself (the sphere at
  // h = 0.003 stopped at 1.19 million vertices with a front 2.6 times its natural length). The
  // layer term makes parts of the front that lag behind by a few layers go first, as in a
  // layered advancing front, while gaps that need a merge are still closed at once.
  const double gap = smallest_gap(v);
  if (gap < options_.min_gap_angle) {
    return gap + deferral_penalty(v);
  }
  const int layer = static_cast<std::size_t>(v) < layer_.size() ? layer_[v] : 0;
  return gap + kLayerWeight * layer + deferral_penalty(v);
}

double FrontBuilder::smallest_gap(int v) {
  const auto chains = state_.fan_chains(v);
  if (chains.empty() || (chains.size() == 1 && chains[0].is_closed)) {
    return -1.0;  // nothing to close: process at once, it only changes the vertex type
  }
  if (tangent_cache_.size() <= static_cast<std::size_t>(v)) {
    tangent_cache_.resize(v + 1);
  }
  if (tangent_cache_[v].size() == 0) {
    Linearization& frame = gap_frame_;
    if (!frame.factor(problem_, state_.point(v), cached_tangent_near(v))) {
      return -1.0;  // process() will report the singular point
    }
    tangent_cache_[v] = frame.tangent_basis();
  }
  const Eigen::MatrixXd U = oriented_frame(v, tangent_cache_[v], chains);
  double smallest = std::numeric_limits<double>::infinity();
  for (const Gap& gap : find_gaps(v, chains, U)) {
    smallest = std::min(smallest, gap.angle);
  }
  return smallest;
}

}  // namespace tessera::front_detail
