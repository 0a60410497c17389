// SPDX-License-Identifier: MIT
// PITMAN (Brodzik & Rheinboldt 1994, section 4). The frontal points form a FIFO queue; each is
// given a complete neighbourhood of triangles by closing its gap, either by merging the two open
// edges (gap < α_min) or by n_new sectors whose new vertices are projected onto M with the chord
// corrector frozen at the frontal point (eq. 2.5). Afterwards the mesh is clipped to the domain.
// The builder's state is declared in front_builder.h; the order in which it takes the frontal
// points is in front_order.cpp, its handling of bands of M ∩ S narrower than the step in
// front_bands.cpp.
#include "tessera/methods/front/advancing_front.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>
#include <set>
#include <sstream>

#include "tessera/core/ambient_space.h"
#include "tessera/core/binary_stream.h"
#include "tessera/core/corrector.h"
#include "tessera/core/counted_problem.h"
#include "tessera/core/describe.h"
#include "tessera/core/error.h"
#include "tessera/core/linearization.h"
#include "tessera/core/process_memory.h"
#include "tessera/core/sparse_lu.h"
#include "tessera/methods/common/clip_to_domain.h"
#include "tessera/methods/front/front_builder.h"
#include "tessera/methods/front/front_state.h"
#include "tessera/methods/start_point.h"

namespace tessera {

void FrontOptions::validate() const {
  validate_common("FrontOptions");
  TESSERA_CHECK(
      min_gap_angle > 0 && min_gap_angle < std::numbers::pi / 2,
      "FrontOptions::min_gap_angle = " << min_gap_angle << " must lie in (0, π/2) radians");
  TESSERA_CHECK(max_valence >= 6 && max_valence <= 12,
                "FrontOptions::max_valence = " << max_valence << " must lie in [6, 12]");
  TESSERA_CHECK(min_step_fraction > 0 && min_step_fraction < 1,
                "FrontOptions::min_step_fraction = " << min_step_fraction << " must lie in (0, 1)");
  TESSERA_CHECK(collision_distance_fraction > 0 && collision_distance_fraction < 1,
                "FrontOptions::collision_distance_fraction = " << collision_distance_fraction
                                                               << " must lie in (0, 1)");
  TESSERA_CHECK(boundary_snap_fraction >= 0 && boundary_snap_fraction < 0.5,
                "FrontOptions::boundary_snap_fraction = " << boundary_snap_fraction
                                                          << " must lie in [0, 0.5)");
  TESSERA_CHECK(max_vertices >= 7,
                "FrontOptions::max_vertices = " << max_vertices << " must be >= 7");
}

namespace front_detail {

const Eigen::MatrixXd* FrontBuilder::cached_tangent_near(int v) const {
  const auto known = [&](int u) {
    return static_cast<std::size_t>(u) < tangent_cache_.size() && tangent_cache_[u].size() > 0;
  };
  if (known(v)) {
    return &tangent_cache_[v];
  }
  for (int u : state_.ring(v, 1)) {
    if (known(u)) {
      return &tangent_cache_[u];
    }
  }
  return nullptr;
}

Eigen::MatrixXd FrontBuilder::oriented_frame(int v, const Eigen::MatrixXd& basis,
                                             const std::vector<FanChain>& chains) const {
  Eigen::MatrixXd U = basis;
  double signed_area = 0.0;
  for (const auto& chain : chains) {
    signed_area += state_.fan_signed_area(v, chain, U);
  }
  if (signed_area < 0) {
    U.col(1) *= -1.0;
  }
  return U;
}

void FrontBuilder::sample_memory(CoveringSummary& summary) const {
  double boundary = 0.0;
  for (const Eigen::MatrixXd& basis : tangent_cache_) {
    boundary += static_cast<double>(sizeof(double) * basis.size());
  }
  summary.note_resident_memory(boundary);
  release_free_heap();
}

void FrontBuilder::run(const Eigen::VectorXd& start_point, const Linearization& start_frame,
                       CoveringSummary& summary) {
  const FrontCheckpointing& checkpoints = options_.checkpoint;
  // With checkpoints a factorisation must depend on its matrix alone, not on the object's
  // history (KLU refactors with its last pivots): a resumed build's objects are new. As for the
  // atlas (atlas_builder.cpp), only then: runs without checkpoints keep the cheaper refactoring.
  std::optional<FullPivotingScope> full_pivoting;
  if (checkpoints.save || checkpoints.resume_from) {
    full_pivoting.emplace();
  }
  start_ = start_point;
  build_start_ = std::chrono::steady_clock::now();
  step_ = options_.step;
  // The chord corrector contracts like O(h·curvature); a projection that needs to move the
  // point by more than the step itself has left the neighbourhood of x_c (paper: Proj fails).
  chord_options_.max_displacement = 0.75 * options_.step;
  if (checkpoints.resume_from) {
    // (Outside the try: a refused state is an InvalidArgument, not a stopped run.)
    BinaryReader in(*checkpoints.resume_from, "front checkpoint");
    read_state(in, summary);
  }
  try {
    if (!checkpoints.resume_from) {
      build_initial_hexagon(start_point, start_frame);
    }
    int& processed = processed_;
    ProgressSchedule progress_schedule;
    while (auto center = next_frontal()) {
      const FrontState::Checkpoint checkpoint = state_.checkpoint();
      const int merges_before = merges_;
      try {
        process(*center);
      } catch (const StopRun& stop) {
        if (!defer(*center, checkpoint, merges_before, stop)) {
          throw;
        }
        continue;
      }
      if (options_.order == FrontOrder::SmallestGapFirst) {
        for (int v : state_.ring(*center, 1)) {
          refresh_priority(v);
        }
      }
      ++processed;
      if (space_->local_rows() >= kReleaseHeapDimension && processed % kMemorySampleVertices == 0) {
        sample_memory(summary);
      }
      if (options_.progress && progress_schedule.is_due(processed)) {
        options_.progress(
            {state_.live_vertex_count(), state_.live_triangle_count(), state_.front_size()});
      }
      if (state_.live_vertex_count() >= options_.max_vertices) {
        throw StopRun{CoveringTermination::VertexLimit,
                      "stopped at the vertex limit of " + std::to_string(options_.max_vertices)};
      }
      if (options_.stop_requested && options_.stop_requested()) {
        save_checkpoint_at_stop(summary);  // before the state is made a valid partial mesh
        throw StopRun{CoveringTermination::Interrupted,
                      "interrupted at " + std::to_string(state_.live_vertex_count()) + " vertices"};
      }
      if (checkpoints.save && checkpoints.is_due && checkpoints.is_due()) {
        save_checkpoint();
      }
    }
    if (checkpoints.save) {
      save_checkpoint();  // the complete build: a run killed after it need not build again
    }
    // Parts of the front connected to an exterior vertex are never glued there (it is not
    // processed): bratu2d:N=8 at h = 0.15 had such a pinch at ε = −0.02, and every face's
    // clipping then failed its validation. The copies lie outside S and are cut away.
    state_.split_pinched_exterior_vertices();
  } catch (const StopRun& stop) {
    summary.termination = stop.termination;
    summary.message = stop.message;
    // Keep the work, but only as a valid mesh: undo connections that were not glued yet.
    // Removing one fan can pinch another vertex, so repeat until none is left.
    while (state_.drop_pinched_fans() > 0) {
    }
  }
  summary.step = step_;
  summary.merges = merges_;
  summary.step_reductions = step_reductions_;
  summary.front_connections = connections_;
  if (deferred_steps_ > 0) {
    summary.notes.push_back(std::to_string(deferred_steps_) +
                            " step(s) ran into the mesh and were undone, their vertices tried "
                            "again after their neighbours");
  }
}

bool FrontBuilder::defer(int center, const FrontState::Checkpoint& checkpoint,
                         int merges_before, const StopRun& stop) {
  if (deferrals_.size() <= static_cast<std::size_t>(center)) {
    deferrals_.resize(center + 1, 0);
  }
  if (stop.termination != CoveringTermination::FrontCollision || merges_ != merges_before ||
      deferrals_[center] >= kMaxDeferrals) {
    return false;
  }
  // The builder's per-vertex caches first (they are indexed by vertex), then the state.
  for (int v = checkpoint.vertices; v < static_cast<int>(gap_key_.size()); ++v) {
    if (!std::isnan(gap_key_[v])) {
      by_gap_.erase({gap_key_[v], v});
    }
  }
  const auto keep = [&](auto& per_vertex) {
    if (per_vertex.size() > static_cast<std::size_t>(checkpoint.vertices)) {
      per_vertex.resize(checkpoint.vertices);
    }
  };
  keep(gap_key_);
  keep(tangent_cache_);
  keep(layer_);
  keep(deferrals_);
  std::vector<int> changed = state_.roll_back(checkpoint);
  ++deferrals_[center];
  ++deferred_steps_;
  if (options_.order == FrontOrder::Fifo) {
    state_.requeue(center);
  }
  const std::vector<int> around = state_.ring(center, 1);
  changed.insert(changed.end(), around.begin(), around.end());
  for (int v : changed) {
    refresh_priority(v);
  }
  return true;
}

void FrontBuilder::build_initial_hexagon(const Eigen::VectorXd& center,
                                         const Linearization& frame) {
  const int c = state_.add_vertex(center, VertexType::Interior);
  layer_.assign(1, 0);
  new_vertex_layer_ = 1;
  const Eigen::MatrixXd& U = frame.tangent_basis();
  // Paper: the user's h or a smaller one, whichever projects the first hexagon vertex; that h
  // is then kept for the whole run.
  std::vector<Eigen::VectorXd> corners(6);
  const auto corner_prediction = [&](int i) {
    const double angle = std::numbers::pi / 6 + i * std::numbers::pi / 3;
    return Eigen::VectorXd(center + step_ * U * Eigen::Vector2d(std::cos(angle), std::sin(angle)));
  };
  for (;;) {
    Eigen::VectorXd x = corner_prediction(0);
    chord_options_.max_displacement = 0.75 * step_;
    if (project_chord(problem_, frame, x, chord_options_).is_success()) {
      corners[0] = x;
      break;
    }
    step_ /= 2;
    ++step_reductions_;
    if (step_ < options_.step * options_.min_step_fraction) {
      throw StopRun{CoveringTermination::ProjectionFailed,
                    "cannot project the first hexagon vertex around the start " +
                        describe_point(center, *space_) + " even with step " +
                        std::to_string(step_) +
                        ": the corrector does not converge near the start"};
    }
  }
  int first_vertex = -1;
  int previous = -1;
  for (int i = 0; i < 6; ++i) {
    Eigen::VectorXd x =
        i == 0 ? corners[0]
               : new_point(c, frame, U, std::numbers::pi / 6 + i * std::numbers::pi / 3);
    const int v = add_point(x);
    if (i == 0) {
      first_vertex = v;
    } else {
      add_triangle(c, previous, v);
    }
    previous = v;
  }
  add_triangle(c, previous, first_vertex);
  if (options_.order == FrontOrder::SmallestGapFirst) {
    for (int v : state_.ring(c, 1)) {
      refresh_priority(v);
    }
  }
}

int FrontBuilder::add_point(const Eigen::VectorXd& x) {
  const bool inside = domain_.is_unbounded() || domain_.boundary_distance(x).signed_distance > 0;
  const int v = state_.add_vertex(x, inside ? VertexType::Frontal : VertexType::Exterior);
  layer_.resize(v + 1, new_vertex_layer_);
  layer_[v] = new_vertex_layer_;
  return v;
}

Eigen::VectorXd FrontBuilder::new_point(int center, const Linearization& frame,
                                        const Eigen::MatrixXd& U, double angle) {
  const Eigen::VectorXd direction = U * Eigen::Vector2d(std::cos(angle), std::sin(angle));
  const Eigen::VectorXd x_center = state_.point(center);
  Eigen::VectorXd x = x_center + step_ * direction;
  chord_options_.max_displacement = 0.75 * step_;
  if (project_chord(problem_, frame, x, chord_options_).is_success()) {
    return x;
  }
  // Paper, section 4: continuation along the direction t with h/2^k until a projection
  // succeeds, then further steps of that size until their sum exceeds h.
  ++step_reductions_;
  double sub_step = step_ / 2;
  double travelled = 0.0;
  Eigen::VectorXd current = x_center;
  // The continuation's frame: `frame` until the first sub-step, then its own factorisation.
  // One process copies `frame` (the copy keeps its border, which its next factorisation then
  // keeps too); a distributed factorisation is not copied (its copy is not factored), so on
  // split states the first sub-steps use `frame` itself and `moving` factors afresh.
  Linearization moving;
  const Linearization* current_frame = &frame;
  if (!space_->is_distributed()) {
    moving = frame;
    current_frame = &moving;
  }
  Eigen::VectorXd current_direction = direction;
  while (travelled < step_ * (1 - 1e-12)) {
    if (sub_step < step_ * options_.min_step_fraction) {
      std::ostringstream message;
      message << "projection onto M failed from frontal vertex " << center << " "
              << describe_point(x_center, *space_) << " in tangent direction " << angle
              << " rad even with step " << sub_step;
      throw StopRun{CoveringTermination::ProjectionFailed, message.str()};
    }
    Eigen::VectorXd trial = current + sub_step * current_direction;
    CorrectorOptions options = chord_options_;
    options.max_displacement = 0.75 * sub_step;
    if (!project_chord(problem_, *current_frame, trial, options).is_success()) {
      sub_step /= 2;
      continue;
    }
    travelled += sub_step;
    current = trial;
    const Eigen::MatrixXd previous_basis = current_frame->tangent_basis();
    current_frame = &moving;
    if (!moving.factor(problem_, current, &previous_basis)) {
      std::ostringstream message;
      message << "the Jacobian is rank deficient at " << describe_point(current, *space_)
              << " while continuing from frontal vertex " << center;
      throw StopRun{CoveringTermination::ProjectionFailed, message.str()};
    }
    // Keep the direction: its component in the new tangent plane, renormalised.
    const Eigen::MatrixXd& T = moving.tangent_basis();
    current_direction = T * space_->tangent_coordinates(T, current_direction);
    if (space_->is_distributed()) {
      const double length = space_->norm(current_direction);
      if (length > 0) {
        current_direction /= length;
      }
    } else {
      current_direction.normalize();
    }
  }
  return current;
}

void FrontBuilder::process(int center) {
  new_vertex_layer_ = layer_[center] + 1;
  // Reused between vertices: a sparse LU keeps its symbolic analysis while the pattern holds.
  Linearization& frame = center_frame_;
  // A nearby tangent basis lets a sparse factorisation border J with coordinate rows.
  const Eigen::MatrixXd* reference = cached_tangent_near(center);
  // Only a vertex reopened by reopen_bridges lies outside S.
  const bool outside = !domain_.is_unbounded() &&
                       domain_.boundary_distance(state_.point(center)).signed_distance <= 0;
  if (!frame.factor(problem_, state_.point(center), reference)) {
    if (outside) {
      state_.set_type(center, VertexType::Exterior);
      return;
    }
    std::ostringstream message;
    message << "the Jacobian is rank deficient at frontal vertex " << center << " "
            << describe_point(state_.point(center), *space_) << " (a singular point of M)";
    throw StopRun{CoveringTermination::ProjectionFailed, message.str()};
  }
  // Each pass closes one gap; a vertex normally has one gap, more only where the front was
  // connected to a non-adjacent part of itself. The bound only guards against a logic error.
  for (int pass = 0; pass < 4 * options_.max_valence; ++pass) {
    const auto chains = state_.fan_chains(center);
    if (chains.size() == 1 && chains[0].is_closed) {
      state_.set_type(center, VertexType::Interior);
      release_tangent(center);
      return;
    }
    for (const auto& chain : chains) {
      if (chain.is_closed) {
        std::ostringstream message;
        message << "vertex " << center << " " << describe_point(state_.point(center), *space_)
                << " has a closed fan and further triangles: the mesh folds there";
        throw StopRun{CoveringTermination::FrontCollision, message.str()};
      }
    }
    // Orient U so that the existing triangles turn counterclockwise in the local coordinates:
    // each gap is then the counterclockwise angle from an open edge to the next (this replaces
    // the paper's average-direction test in Agap; see docs/algorithms/front.md).
    const Eigen::MatrixXd U = oriented_frame(center, frame.tangent_basis(), chains);
    if (pass == 0 && (bridged_ || is_in_band(center))) {
      bool closed_outside = false;
      for (const auto& chain : chains) {
        for (int z : {chain.vertices.front(), chain.vertices.back()}) {
          const int triangles = state_.live_triangle_count();
          close_small_gap_outside(z, U);
          closed_outside = closed_outside || state_.live_triangle_count() > triangles;
        }
      }
      if (closed_outside) {
        continue;
      }
    }
    if (chains.size() == 1 && close_small_loop(center, U)) {
      continue;
    }
    const std::vector<Gap> gaps = find_gaps(center, chains, U);
    const Gap& smallest = *std::min_element(
        gaps.begin(), gaps.end(), [](const Gap& a, const Gap& b) { return a.angle < b.angle; });
    if (!outside) {
      close_gap(center, frame, U, smallest);
      continue;
    }
    // A reopened vertex lies outside S, where M may be singular or not even defined (bratu2d
    // at ε < 0 has 1 + εu = 0): where its gap cannot be closed it is left exterior with the
    // triangles it has. If M ∩ S beyond it is then uncovered, the coverage check reports it.
    try {
      close_gap(center, frame, U, smallest);
    } catch (const StopRun& stop) {
      if (stop.termination != CoveringTermination::ProjectionFailed) {
        throw;
      }
      state_.set_type(center, VertexType::Exterior);
      return;
    }
  }
  std::ostringstream message;
  message << "frontal vertex " << center << " " << describe_point(state_.point(center), *space_)
          << " could not be given a complete neighbourhood";
  throw StopRun{CoveringTermination::FrontCollision, message.str()};
}

std::vector<Gap> FrontBuilder::find_gaps(int center, const std::vector<FanChain>& chains,
                                         const Eigen::MatrixXd& U) const {
  if (chains.size() == 1) {
    return {{chains[0].vertices.back(), chains[0].vertices.front(),
             kTwoPi - state_.fan_angle(center, chains[0], U)}};
  }
  // Several fans: order them by the direction of their first edge; the gap after each fan
  // runs counterclockwise from its last edge to the first edge of the next fan.
  const auto direction = [&](int v) {
    const Eigen::Vector2d y =
        space_->tangent_coordinates(U, state_.point(v) - state_.point(center));
    return std::atan2(y(1), y(0));
  };
  std::vector<std::pair<double, const FanChain*>> ordered;
  for (const auto& chain : chains) {
    ordered.emplace_back(direction(chain.vertices.front()), &chain);
  }
  std::sort(ordered.begin(), ordered.end(),
            [](const auto& a, const auto& b) { return a.first < b.first; });
  std::vector<Gap> gaps;
  for (std::size_t i = 0; i < ordered.size(); ++i) {
    const FanChain& chain = *ordered[i].second;
    const FanChain& next = *ordered[(i + 1) % ordered.size()].second;
    double angle = direction(next.vertices.front()) - direction(chain.vertices.back());
    angle = std::fmod(angle + 2 * kTwoPi, kTwoPi);
    gaps.push_back({chain.vertices.back(), next.vertices.front(), angle});
  }
  return gaps;
}

void FrontBuilder::close_gap(int center, const Linearization& frame, const Eigen::MatrixXd& U,
                             const Gap& gap) {
  const int old_count = state_.valence(center);
  if (gap.angle < options_.min_gap_angle) {
    if (try_merge(center, gap.first, gap.last, frame)) {
      return;
    }
    if (gap.angle <= 0) {
      std::ostringstream message;
      message << "the triangles around frontal vertex " << center << " "
              << describe_point(state_.point(center), *space_)
              << " overlap (no room is left between the open edges to "
              << describe_point(state_.point(gap.last), *space_) << " and "
              << describe_point(state_.point(gap.first), *space_)
              << ") and the open edges cannot be merged";
      throw StopRun{CoveringTermination::FrontCollision, message.str()};
    }
    add_closing_triangle(center, gap.last, gap.first, U);
    return;
  }
  // The paper stops when a vertex already has its maximum of triangles; tessera first closes
  // a gap below 120° with one triangle, which keeps its angles bounded by 120°.
  if (old_count >= options_.max_valence && gap.angle < kTwoPi / 3) {
    add_closing_triangle(center, gap.last, gap.first, U);
    return;
  }
  if (old_count >= options_.max_valence) {
    std::ostringstream message;
    message << "frontal vertex " << center << " " << describe_point(state_.point(center), *space_)
            << " already has " << old_count << " triangles and a gap of " << gap.angle
            << " rad >= α_min remains (raise --max-valence or lower the step)";
    throw StopRun{CoveringTermination::FrontCollision, message.str()};
  }
  // Paper: n_new = max{i : gap/i ≥ α_min, 1 ≤ i ≤ max_valence − n_old}.
  int sectors = 1;
  for (int i = 1; i <= options_.max_valence - old_count; ++i) {
    if (gap.angle / i >= options_.min_gap_angle) {
      sectors = i;
    }
  }
  // A single sector whose far edge would be much longer than h is split in two after all
  // (sectors of at least 30°): otherwise the longest edges, and with them the distance of
  // the mesh to M, grow faster than h under refinement.
  const double far_edge = space_->distance(state_.point(gap.last), state_.point(gap.first));
  if (sectors == 1 && far_edge > kMaxEdgeRatio * step_ && gap.angle >= kTwoPi / 6 &&
      old_count < options_.max_valence) {
    sectors = 2;
  }
  if (sectors == 1) {
    add_closing_triangle(center, gap.last, gap.first, U);
    return;
  }
  const Eigen::Vector2d y_last =
      space_->tangent_coordinates(U, state_.point(gap.last) - state_.point(center));
  const double start_angle = std::atan2(y_last(1), y_last(0));
  int previous = gap.last;
  for (int i = 1; i < sectors; ++i) {
    const Eigen::VectorXd x = new_point(center, frame, U, start_angle + i * gap.angle / sectors);
    if (const auto w = colliding_front_vertex(center, previous, x, U)) {
      // The front meets a non-adjacent part of itself: connect to that vertex instead of
      // creating a new one (an extension of PITMAN; the front loop splits in two there).
      connect_to_front_vertex(center, previous, *w, U);
      return;
    }
    const int v = add_point(x);
    require_fit({center, previous, v}, U);
    add_triangle(center, previous, v);
    remember_tangent(v, frame);
    previous = v;
  }
  require_fit({center, previous, gap.first}, U);
  add_triangle(center, previous, gap.first);
}

// The smallest-gap order needs the tangent plane at every frontal vertex. Factoring DF there
// for it, and again when the vertex is processed, cost a sparse problem two factorisations per
// vertex; the chord of tangent_basis_near from the creator's factorisation (one DF and a few
// solves) gives the same basis, so that a vertex is factored once, when it is processed. Dense
// problems keep factoring: a QR of the (n−2)×n Jacobian at small n costs less than the solves.
void FrontBuilder::remember_tangent(int v, const Linearization& frame) {
  if (!problem_.has_sparse_jacobian() || state_.type(v) != VertexType::Frontal) {
    return;
  }
  Eigen::MatrixXd T;
  if (!tangent_basis_near(problem_, frame, state_.point(v), T)) {
    return;  // too far from the creator: smallest_gap factors at v
  }
  if (tangent_cache_.size() <= static_cast<std::size_t>(v)) {
    tangent_cache_.resize(v + 1);
  }
  tangent_cache_[v] = std::move(T);
}

std::optional<int> FrontBuilder::colliding_front_vertex(int center, int previous,
                                                        const Eigen::VectorXd& x,
                                                        const Eigen::MatrixXd& U) {
  // Vertices within two edges of x_c are the local overlap that PITMAN resolves itself: the
  // next frontal vertex sees a small gap and merges the pair.
  const double radius = options_.collision_distance_fraction * step_;
  const std::vector<int> nearby = state_.ring(center, 2);
  std::optional<int> closest;
  double closest_distance = radius;
  std::vector<int> candidates;
  for (int w : state_.vertices_near(x, radius)) {
    if (!std::binary_search(nearby.begin(), nearby.end(), w)) {
      candidates.push_back(w);
    }
  }
  const std::vector<double> distances = state_.distances(x, candidates);
  for (std::size_t k = 0; k < candidates.size(); ++k) {
    const int w = candidates[k];
    const double distance = distances[k];
    if (state_.type(w) == VertexType::Interior) {
      std::ostringstream message;
      message << "the front runs into the finished part of the mesh near "
              << describe_point(x, *space_)
              << ": a new vertex from frontal vertex " << center << " "
              << describe_point(state_.point(center), *space_) << " falls within " << distance
              << " of interior vertex " << w << " " << describe_point(state_.point(w), *space_);
      throw StopRun{CoveringTermination::FrontCollision, message.str()};
    }
    if (distance <= closest_distance && state_.triangle_fits({center, previous, w}, U) &&
        state_.can_add_edge(previous, w) && state_.can_add_edge(w, center)) {
      closest = w;
      closest_distance = distance;
    }
  }
  return closest;
}

void FrontBuilder::connect_to_front_vertex(int center, int previous, int w,
                                           const Eigen::MatrixXd& U) {
  const Eigen::Vector2d y_previous =
      space_->tangent_coordinates(U, state_.point(previous) - state_.point(center));
  const Eigen::Vector2d y_w =
      space_->tangent_coordinates(U, state_.point(w) - state_.point(center));
  const bool turns_counterclockwise = y_previous(0) * y_w(1) - y_previous(1) * y_w(0) > 0;
  if (!turns_counterclockwise || !state_.can_add_edge(previous, w) ||
      !state_.can_add_edge(w, center)) {
    std::ostringstream message;
    message << "the front meets itself near " << describe_point(state_.point(w), *space_)
            << ": frontal vertex " << center << " " << describe_point(state_.point(center), *space_)
            << " reaches vertex " << w
            << ", a non-adjacent part of the front, in a way that cannot be glued without "
               "folding the mesh";
    throw StopRun{CoveringTermination::FrontCollision, message.str()};
  }
  add_triangle(center, previous, w);
  ++connections_;
}

void FrontBuilder::require_fit(const Triangle& t, const Eigen::MatrixXd& U) {
  if (state_.triangle_fits(t, U)) {
    return;
  }
  std::ostringstream message;
  message << "the front overlaps itself near frontal vertex " << t[0] << " "
          << describe_point(state_.point(t[0]), *space_) << ": the triangle with corners "
          << describe_point(state_.point(t[0]), *space_) << ", "
          << describe_point(state_.point(t[1]), *space_)
          << ", " << describe_point(state_.point(t[2]), *space_)
          << " would overlap the triangles already there";
  throw StopRun{CoveringTermination::FrontCollision, message.str()};
}

void FrontBuilder::add_closing_triangle(int center, int last, int first, const Eigen::MatrixXd& U) {
  // The new edge last→first must be free on this side, and the triangle must not overlap the
  // triangles already at last and first, else the mesh would fold.
  if (!state_.can_add_edge(last, first) || !state_.triangle_fits({center, last, first}, U)) {
    std::ostringstream message;
    message << "cannot close the gap at frontal vertex " << center << " "
            << describe_point(state_.point(center), *space_) << ": the edge from "
            << describe_point(state_.point(last), *space_) << " to "
            << describe_point(state_.point(first), *space_)
            << " is taken or the triangle would overlap the mesh there";
    throw StopRun{CoveringTermination::FrontCollision, message.str()};
  }
  add_triangle(center, last, first);
}

bool FrontBuilder::try_merge(int /*center*/, int first, int last, const Linearization& frame) {
  if (first == last || state_.are_adjacent(first, last) || !state_.can_identify(first, last)) {
    return false;
  }
  // Paper's Merge: replace both endpoints by the projection of their average (chord at x_c).
  Eigen::VectorXd average = 0.5 * (state_.point(first) + state_.point(last));
  chord_options_.max_displacement = 0.75 * step_;
  if (!project_chord(problem_, frame, average, chord_options_).is_success()) {
    return false;
  }
  const bool inside =
      domain_.is_unbounded() || domain_.boundary_distance(average).signed_distance > 0;
  if (tangent_cache_.size() > static_cast<std::size_t>(first)) {
    tangent_cache_[first].resize(0, 0);  // it moved
  }
  state_.identify(first, last, average,
                  inside ? std::nullopt : std::optional(VertexType::Exterior));
  layer_[first] = std::min(layer_[first], layer_[last]);
  reopen_bridges(first);
  ++merges_;
  return true;
}

bool FrontBuilder::close_small_loop(int center, const Eigen::MatrixXd& U) {
  // At the end of a closed surface the front shrinks to a small loop; adding new points inside
  // it would only create overlaps, so a loop of at most eight vertices is triangulated directly
  // when a triangulation with all angles above 20° exists (a regular octagon allows 22.5°).
  const auto loop = state_.front_loop(center, kMaxClosedLoop + 1);
  if (loop.size() < 3 || static_cast<int>(loop.size()) > kMaxClosedLoop) {
    return false;
  }
  for (int v : loop) {
    if (state_.type(v) == VertexType::Exterior) {
      return false;  // the loop runs outside the domain: not a hole of M ∩ S
    }
  }
  return state_.triangulate_hole(loop, U, loop.size() <= 3 ? 0.0 : 20.0 * std::numbers::pi / 180);
}

}  // namespace front_detail

CoveringResult triangulate_by_front(const ImplicitProblem& problem, const Eigen::VectorXd& start,
                                    const Domain& domain, const FrontOptions& options) {
  options.validate();
  return run_covering("front", problem, start, domain, options,
                      [&options](CoveringContext& context, CoveringResult& result) {
                        front_detail::FrontBuilder builder(context.problem, context.domain, options);
                        builder.run(context.start.x, context.start.linearization, result.summary);
                        result.mesh = builder.state().take_mesh();
                        context.boundary_edge_length = result.summary.step;
                        context.boundary_snap_fraction = options.boundary_snap_fraction;
                      });
}

}  // namespace tessera
