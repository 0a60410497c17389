// SPDX-License-Identifier: MIT
// The advancing front's state written and read (front_checkpoint.h says what and why): the
// builder's part (FrontBuilder) and the growing mesh's (FrontState).
#include "tessera/methods/front/front_checkpoint.h"

#include <cmath>
#include <limits>
#include <utility>
#include <vector>

#include "tessera/core/binary_stream.h"
#include "tessera/core/counted_problem.h"
#include "tessera/core/error.h"
#include "tessera/methods/common/run_fingerprint.h"
#include "tessera/methods/front/front_builder.h"
#include "tessera/methods/front/front_state.h"

namespace tessera {
namespace {

void write_ints(BinaryWriter& out, const std::vector<int>& values) {
  out.u64(values.size());
  for (int v : values) {
    out.i32(v);
  }
}

// A vector of at most `most` ints, each in [low, high).
std::vector<int> read_ints(BinaryReader& in, const char* field, std::size_t most, int low,
                           int high) {
  const std::size_t count = in.count(field, 4);
  if (count > most) {
    in.fail("corrupt: " + std::string(field) + " holds " + std::to_string(count) +
            " entries, more than the " + std::to_string(most) + " vertices");
  }
  std::vector<int> values(count);
  for (int& v : values) {
    v = in.i32(field);
    if (v < low || v >= high) {
      in.fail("corrupt: " + std::string(field) + " holds " + std::to_string(v) + ", outside [" +
              std::to_string(low) + ", " + std::to_string(high) + ")");
    }
  }
  return values;
}

}  // namespace

void FrontState::write_state(BinaryWriter& out) const {
  const int count = static_cast<int>(types_.size());
  out.i32(count);
  out.i32(coordinates_.dimension());
  out.doubles(coordinates_.data(),
              static_cast<std::size_t>(count) * static_cast<std::size_t>(coordinates_.dimension()));
  for (VertexType type : types_) {
    out.u8(static_cast<std::uint8_t>(type));
  }
  // Each vertex's triangles in their order (fans are walked in it).
  for (const std::vector<int>& triangles : incident_) {
    write_ints(out, triangles);
  }
  // Every slot, removed ones ({−1, −1, −1}) included: triangle indices stay as they were.
  out.u64(triangles_.size());
  for (const Triangle& t : triangles_) {
    out.i32(t[0]);
    out.i32(t[1]);
    out.i32(t[2]);
  }
  out.u64(queue_.size());
  for (int v : queue_) {
    out.i32(v);
  }
  // The grid's view was fitted to points that merges have moved since: kept, not refitted.
  out.matrix(grid_.view_directions());
  out.i32(grid_.next_refit());
  out.i32(grid_.size());
  out.i32(live_vertices_);
  out.i32(live_triangles_);
  out.i32(frontal_vertices_);
}

void FrontState::read_state(BinaryReader& in) {
  TESSERA_ASSERT(types_.empty());
  const int count = in.i32("vertex count");
  const int rows = in.i32("vertex rows");
  if (count < 1 || rows != coordinates_.dimension()) {
    in.fail("corrupt: " + std::to_string(count) + " vertices of " + std::to_string(rows) +
            " coordinates (" + std::to_string(coordinates_.dimension()) + " here)");
  }
  if (static_cast<double>(count) * 8.0 * rows > static_cast<double>(in.remaining())) {
    in.fail("truncated: " + std::to_string(count) + " vertices do not fit in what is left");
  }
  coordinates_.resize(count);
  in.doubles("vertices", coordinates_.data(),
             static_cast<std::size_t>(count) * static_cast<std::size_t>(rows));
  types_.resize(static_cast<std::size_t>(count));
  for (VertexType& type : types_) {
    const std::uint8_t value = in.u8("vertex type");
    if (value > static_cast<std::uint8_t>(VertexType::Removed)) {
      in.fail("corrupt: vertex type " + std::to_string(value));
    }
    type = static_cast<VertexType>(value);
  }
  // Triangle indices are checked once the triangles' count is known.
  incident_.resize(static_cast<std::size_t>(count));
  for (std::vector<int>& triangles : incident_) {
    triangles = read_ints(in, "incident triangles", std::numeric_limits<std::size_t>::max(), 0,
                          std::numeric_limits<int>::max());
  }
  const std::size_t triangle_count = in.count("triangles", 12);
  triangles_.resize(triangle_count);
  for (Triangle& t : triangles_) {
    for (int& corner : t) {
      corner = in.i32("triangle corner");
      if (corner < -1 || corner >= count) {
        in.fail("corrupt: a triangle corner " + std::to_string(corner) + " is no vertex");
      }
    }
    if ((t[0] < 0 || t[1] < 0 || t[2] < 0) && !(t[0] < 0 && t[1] < 0 && t[2] < 0)) {
      in.fail("corrupt: a triangle with a corner missing");
    }
  }
  for (const std::vector<int>& triangles : incident_) {
    for (int t : triangles) {
      if (static_cast<std::size_t>(t) >= triangle_count || triangles_[t][0] < 0) {
        in.fail("corrupt: an incident triangle " + std::to_string(t) + " is no triangle");
      }
    }
  }
  for (int v : read_ints(in, "queue", std::numeric_limits<std::size_t>::max(), 0, count)) {
    queue_.push_back(v);
  }
  const Eigen::MatrixXd view = in.matrix("grid view");
  const int next_refit = in.i32("grid refit");
  const int grid_size = in.i32("grid size");
  if (view.size() > 0 && (view.rows() != rows || view.cols() != 3)) {
    in.fail("corrupt: the grid's view is " + std::to_string(view.rows()) + "×" +
            std::to_string(view.cols()));
  }
  // The cells: every vertex not removed, at its point (queries sort what they find, so the
  // order of a cell's ids does not matter).
  grid_.reset(view, next_refit);
  for (int v = 0; v < count; ++v) {
    if (types_[v] != VertexType::Removed) {
      grid_.insert(v, point(v));
    }
  }
  if (grid_.size() != grid_size) {
    in.fail("corrupt: the grid held " + std::to_string(grid_size) + " vertices, " +
            std::to_string(grid_.size()) + " are not removed");
  }
  live_vertices_ = in.i32("live vertices");
  live_triangles_ = in.i32("live triangles");
  frontal_vertices_ = in.i32("frontal vertices");
  type_log_.clear();
}

namespace front_detail {
namespace {

// The options that decide the front, by name (max_vertices and the callbacks do not).
detail::DecisiveOptions decisive_options(const FrontOptions& o) {
  return {{"tolerance", o.tolerance},
          {"step", o.step},
          {"max_start_distance", o.max_start_distance},
          {"min_gap_angle", o.min_gap_angle},
          {"max_valence", o.max_valence},
          {"min_step_fraction", o.min_step_fraction},
          {"collision_distance_fraction", o.collision_distance_fraction},
          {"boundary_snap_fraction", o.boundary_snap_fraction},
          {"order", static_cast<double>(o.order)}};
}

}  // namespace

detail::RunIdentity FrontBuilder::identity() const {
  return {problem_, *space_, start_, domain_, decisive_options(options_), "FrontOptions", "front",
          /*domain_may_grow=*/false};
}

double FrontBuilder::checkpoint_bytes() const {
  // The points and the cached bases of the front are most of it.
  double held = 0.0;
  for (const Eigen::MatrixXd& basis : tangent_cache_) {
    held += static_cast<double>(basis.size());
  }
  const double vertices = static_cast<double>(state_.points().cols());
  return vertices * (8.0 * static_cast<double>(space_->local_rows()) + 120.0) + 8.0 * held +
         65536.0;
}

void FrontBuilder::save_checkpoint() {
  BinaryWriter out;
  out.reserve(static_cast<std::size_t>(checkpoint_bytes()));
  write_state(out);
  options_.checkpoint.save(out.take());
}

void FrontBuilder::save_checkpoint_at_stop(CoveringSummary& summary) {
  const FrontCheckpointing& checkpoints = options_.checkpoint;
  if (!checkpoints.save) {
    return;
  }
  if (checkpoint_bytes() <= checkpoints.max_bytes_at_stop) {
    save_checkpoint();
    return;
  }
  summary.notes.push_back("no checkpoint was written at the stop: its " +
                          std::to_string(std::lround(checkpoint_bytes() / 1e6)) +
                          " MB would have delayed the mesh (max_bytes_at_stop); the last "
                          "periodic checkpoint stands");
}

void FrontBuilder::write_state(BinaryWriter& out) const {
  out.u32(kFrontStateVersion);
  detail::write_run_fingerprint(out, identity());
  // The work done, over all runs (this one and those it continued).
  detail::write_work_done(out, state_.live_vertex_count(),
                          seconds_before_ + std::chrono::duration<double>(
                                                std::chrono::steady_clock::now() - build_start_)
                                                .count(),
                          counts_before_, problem_);
  // The builder: the step (halved at the start if needed), the counters, the order's state.
  out.f64(step_);
  out.f64(chord_options_.max_displacement);
  out.i32(merges_);
  out.i32(step_reductions_);
  out.i32(connections_);
  out.i32(deferred_steps_);
  out.i32(processed_);
  out.u8(bridged_ ? 1 : 0);
  out.i32(new_vertex_layer_);
  write_ints(out, deferrals_);
  write_ints(out, layer_);
  out.u64(gap_key_.size());
  out.doubles(gap_key_.data(), gap_key_.size());
  out.u64(by_gap_.size());
  for (const auto& [key, v] : by_gap_) {
    out.f64(key);
    out.i32(v);
  }
  out.u64(tangent_cache_.size());
  for (const Eigen::MatrixXd& basis : tangent_cache_) {
    out.u8(basis.size() > 0 ? 1 : 0);
    if (basis.size() > 0) {
      out.doubles(basis.data(), static_cast<std::size_t>(basis.size()));
    }
  }
  // The reused factorisations are a cache; what borders their next one is not.
  out.matrix(center_frame_.border_guide());
  out.matrix(gap_frame_.border_guide());
  state_.write_state(out);
}

void FrontBuilder::read_state(BinaryReader& in, CoveringSummary& summary) {
  const std::uint32_t version = in.u32("version");
  if (version != kFrontStateVersion) {
    in.fail("the front's state has format version " + std::to_string(version) +
            "; this tessera reads version " + std::to_string(kFrontStateVersion));
  }
  // The fingerprint: the same problem, start, domain and options, or nothing is continued.
  detail::check_run_fingerprint(in, identity());
  const detail::WorkDone done = detail::read_work_done(in, "vertices");
  CoveringSummary::ResumedFrom resumed;
  resumed.vertices = done.count;
  resumed.build_seconds = done.build_seconds;
  resumed.counts = done.counts;
  seconds_before_ = done.build_seconds;
  counts_before_ = done.counts;

  step_ = in.f64("step");
  chord_options_.max_displacement = in.f64("chord displacement");
  if (!(step_ > 0) || !(chord_options_.max_displacement > 0)) {
    in.fail("corrupt: step " + detail::exact_number(step_));
  }
  merges_ = in.i32("merges");
  step_reductions_ = in.i32("step reductions");
  connections_ = in.i32("connections");
  deferred_steps_ = in.i32("deferred steps");
  processed_ = in.i32("processed");
  bridged_ = in.u8("bridged") != 0;
  new_vertex_layer_ = in.i32("layer of new vertices");
  // The per-vertex vectors are checked against the vertex count below, once it is read.
  constexpr int kAny = std::numeric_limits<int>::max();
  deferrals_ = read_ints(in, "deferrals", kAny, 0, kAny);
  layer_ = read_ints(in, "layers", kAny, 0, kAny);
  gap_key_.resize(in.count("gap keys", 8));
  in.doubles("gap keys", gap_key_.data(), gap_key_.size());
  const std::size_t keyed = in.count("smallest-gap order", 12);
  std::vector<std::pair<double, int>> order(keyed);
  for (auto& [key, v] : order) {
    key = in.f64("gap key");
    v = in.i32("keyed vertex");
  }
  const int rows = space_->local_rows();
  tangent_cache_.resize(in.count("tangent bases", 1));
  for (Eigen::MatrixXd& basis : tangent_cache_) {
    if (in.u8("tangent held") != 0) {
      basis.resize(rows, 2);
      in.doubles("tangent", basis.data(), static_cast<std::size_t>(basis.size()));
    }
  }
  const auto guide = [&](Linearization& frame, const char* field) {
    const Eigen::MatrixXd basis = in.matrix(field);
    if (basis.size() > 0 && (basis.rows() != rows || basis.cols() != 2)) {
      in.fail("corrupt: a border guide is " + std::to_string(basis.rows()) + "×" +
              std::to_string(basis.cols()));
    }
    if (basis.size() > 0) {
      frame.set_border_guide(problem_, basis);
    }
  };
  guide(center_frame_, "centre frame guide");
  guide(gap_frame_, "gap frame guide");
  state_.read_state(in);
  if (in.remaining() != 0) {
    in.fail("corrupt: " + std::to_string(in.remaining()) + " bytes after the front's state");
  }
  // Per-vertex vectors never outgrow the vertices; keyed vertices are vertices.
  const std::size_t count = static_cast<std::size_t>(state_.points().cols());
  if (deferrals_.size() > count || layer_.size() > count || gap_key_.size() > count ||
      tangent_cache_.size() > count) {
    in.fail("corrupt: per-vertex data for more than the " + std::to_string(count) + " vertices");
  }
  for (const auto& entry : order) {
    if (entry.second < 0 || static_cast<std::size_t>(entry.second) >= gap_key_.size()) {
      in.fail("corrupt: the smallest-gap order holds vertex " + std::to_string(entry.second));
    }
    by_gap_.insert(entry);
  }
  summary.resumed_from = resumed;
}

}  // namespace front_detail
}  // namespace tessera
