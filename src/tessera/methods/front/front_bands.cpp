// SPDX-License-Identifier: MIT
// The front on bands of M ∩ S narrower than its step: exterior vertices reopened where an open
// edge between two of them runs across S, small gaps at exterior vertices closed inside a band.
// See docs/algorithms/front.md, *Bands narrower than h*.
#include <algorithm>
#include <vector>

#include "tessera/methods/front/front_builder.h"

namespace tessera::front_detail {

// An open edge between two exterior vertices that runs deeper than this fraction of h inside S
// reopens them (FrontBuilder::reopen_bridges).
constexpr double kBridgeDepth = 0.05;

void FrontBuilder::add_triangle(int a, int b, int c) {
  state_.add_triangle(a, b, c);
  for (int v : {a, b, c}) {
    reopen_bridges(v);
  }
}

// Vertices outside S are not advanced: the front stops one triangle beyond the boundary and the
// clipping cuts the rest. That assumes the triangles the front stops with cover S up to the
// boundary. Where M ∩ S is a band narrower than the step (bratu2d near u = 0, ε ∈ [0, 0.3], at
// steps of 0.3 and more), a triangle can have two exterior corners on opposite sides of the
// band, and its open edge between them spans the band: nothing beyond that edge would ever be
// covered, and the run ended with a hole. The same happens at a corner of S that an open edge
// cuts. Such an edge's ends are therefore advanced like frontal vertices: the front goes on
// along the band as a strip of triangles straddling it, until the band ends. An edge that cuts
// S by less than kBridgeDepth·h is left: the corner it cuts off is below the mesh's resolution
// (the clipping snaps vertices within boundary_snap_fraction·h anyway).
void FrontBuilder::reopen_bridges(int v) {
  if (state_.type(v) != VertexType::Exterior) {
    return;
  }
  for (const FanChain& chain : state_.fan_chains(v)) {
    if (chain.is_closed) {
      continue;
    }
    for (int w : {chain.vertices.front(), chain.vertices.back()}) {
      if (state_.type(w) != VertexType::Exterior ||
          !domain_.segment_meets_interior(state_.point(v), state_.point(w), kBridgeDepth * step_)) {
        continue;
      }
      bridged_ = true;
      for (int u : {v, w}) {
        state_.set_type(u, VertexType::Frontal);
        if (options_.order == FrontOrder::SmallestGapFirst) {
          refresh_priority(u);
        }
      }
    }
  }
}

// A frontal vertex next to an exterior one z whose gap is below α_min: were z frontal, it would
// close that gap first (a merge or one triangle). Exterior vertices are never processed, so a
// triangle of the frontal vertex could overlap the triangles at z instead; seen where the front
// runs along a band narrower than h and meets the part of itself that stopped at the band's
// face. The triangle is added from the centre's frame (z lies within h of it): no merge,
// because that would move the centre. Only in a band (a bridge was reopened, or the centre has
// exterior neighbours beyond two opposite faces): elsewhere it lets runs go on that would stop,
// e.g. over a cap of M outside S smaller than the step (sphere in the box [−0.97, 0.97]³ at step
// 0.53), which no vertex then falls into and which the mesh covers over.
void FrontBuilder::close_small_gap_outside(int z, const Eigen::MatrixXd& U) {
  if (state_.type(z) != VertexType::Exterior) {
    return;
  }
  const auto chains = state_.fan_chains(z);
  if (chains.size() != 1 || chains[0].is_closed) {
    return;
  }
  const Gap gap = find_gaps(z, chains, U).front();
  if (gap.angle <= 0 || gap.angle >= options_.min_gap_angle || gap.first == gap.last ||
      state_.are_adjacent(gap.first, gap.last)) {
    return;
  }
  if (state_.can_add_edge(gap.last, gap.first) &&
      state_.triangle_fits({z, gap.last, gap.first}, U)) {
    add_triangle(z, gap.last, gap.first);
  }
}

bool FrontBuilder::is_in_band(int v) {
  if (domain_.is_unbounded()) {
    return false;
  }
  const auto& faces = domain_.half_spaces();
  const int K = static_cast<int>(faces.size());
  std::vector<int> exterior;
  for (int w : state_.ring(v, 1)) {
    if (state_.type(w) == VertexType::Exterior) {
      exterior.push_back(w);
    }
  }
  if (exterior.empty()) {
    return false;
  }
  // Every neighbour's distances in one call (one reduction on split states).
  const Eigen::MatrixXd distances = domain_.signed_distances(state_.points(), exterior);
  std::vector<int> beyond;  // faces that some exterior neighbour of v lies beyond
  for (std::size_t j = 0; j < exterior.size(); ++j) {
    for (int k = 0; k < K; ++k) {
      if (distances(k, static_cast<Eigen::Index>(j)) < 0 &&
          std::find(beyond.begin(), beyond.end(), k) == beyond.end()) {
        beyond.push_back(k);
      }
    }
  }
  if (beyond.empty()) {
    return false;
  }
  if (face_cosines_.size() == 0) {
    face_cosines_.resize(K, K);
    for (int k = 0; k < K; ++k) {
      for (int l = 0; l < K; ++l) {
        face_cosines_(k, l) = faces[k].normal.dot(faces[l].normal);
      }
    }
    space_->sum(face_cosines_.data(), static_cast<int>(face_cosines_.size()));
  }
  for (int k : beyond) {
    for (int l : beyond) {
      if (face_cosines_(k, l) < -0.5) {
        return true;
      }
    }
  }
  return false;
}

}  // namespace tessera::front_detail
