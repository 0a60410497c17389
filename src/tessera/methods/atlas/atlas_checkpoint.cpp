// SPDX-License-Identifier: MIT
// The atlas builder's state written and read (atlas_checkpoint.h says what and why).
#include "tessera/methods/atlas/atlas_checkpoint.h"

#include <algorithm>
#include <utility>
#include <vector>

#include "tessera/core/binary_stream.h"
#include "tessera/core/counted_problem.h"
#include "tessera/core/describe.h"
#include "tessera/core/error.h"
#include "tessera/methods/atlas/atlas_builder.h"
#include "tessera/methods/common/run_fingerprint.h"

namespace tessera::detail {
namespace {

// The options that decide the atlas, by name (max_vertices and the callbacks do not).
DecisiveOptions decisive_options(const AtlasOptions& o) {
  return {{"tolerance", o.tolerance},
          {"step", o.step},
          {"max_start_distance", o.max_start_distance},
          {"corrector.tolerance", o.corrector.tolerance},
          {"corrector.residual_tolerance", o.corrector.residual_tolerance},
          {"corrector.max_iterations", o.corrector.max_iterations},
          {"corrector.max_contraction", o.corrector.max_contraction},
          {"corrector.max_displacement", o.corrector.max_displacement},
          {"placement", static_cast<double>(o.placement)},
          {"hexagonal_side", o.hexagonal_side},
          {"radius_growth", o.radius_growth},
          {"max_turning_angle", o.max_turning_angle},
          {"min_sheet_cosine", o.min_sheet_cosine},
          {"domain_margin", o.domain_margin},
          {"boundary_snap", o.boundary_snap},
          {"min_radius_fraction", o.min_radius_fraction},
          {"swap_edges", o.swap_edges ? 1.0 : 0.0},
          {"max_factorisation_bytes", o.max_factorisation_bytes}};
}

}  // namespace

RunIdentity AtlasBuilder::identity() const {
  return {problem_,      *space_, start_, domain_, decisive_options(options_), "AtlasOptions",
          "atlas",       options_.checkpoint.extend};
}

double AtlasBuilder::checkpoint_bytes() const {
  // The centres and the held bases are most of it (at n = 10⁴, 80 kB a chart).
  return static_cast<double>(chart_count()) * (8.0 * rows_ + 160.0) +
         static_cast<double>(held_tangents_) * 16.0 * rows_ + 65536.0;
}

void AtlasBuilder::save_checkpoint() {
  BinaryWriter out;
  out.reserve(static_cast<std::size_t>(checkpoint_bytes()));
  write_state(out);
  options_.checkpoint.save(out.take());
}

void AtlasBuilder::write_state(BinaryWriter& out) {
  out.u32(kAtlasStateVersion);
  write_run_fingerprint(out, identity());
  // The work done, over all runs (this one and those it continued).
  write_work_done(out, chart_count(),
                  seconds_before_ + std::chrono::duration<double>(
                                        std::chrono::steady_clock::now() - build_start_)
                                        .count(),
                  counts_before_, problem_);

  // The charts.
  const int count = chart_count();
  const auto& inserted = index_.inserted();
  TESSERA_ASSERT(static_cast<int>(inserted.size()) == count);
  for (int c = 0; c < count; ++c) {
    const Chart& chart = charts_[c];
    out.f64(chart.radius);
    out.f64(inserted[c].second);
    out.i32(chart.parent);
    out.u8(static_cast<std::uint8_t>(chart.orientation));
    out.f32(chart.jacobian_scale);
    out.u8(chart.queued ? 1 : 0);
    out.u8(static_cast<std::uint8_t>(chart.eligible));
    out.u64(chart.polygon.vertices().size());
    for (const auto& v : chart.polygon.vertices()) {
      out.f64(v.s);
      out.f64(v.t);
      out.i32(v.edge_label);
    }
    out.u8(tangents_[c].size() > 0 ? 1 : 0);
    if (tangents_[c].size() > 0) {
      out.doubles(tangents_[c].data(), static_cast<std::size_t>(tangents_[c].size()));
    }
    out.doubles(frames_[c].data(), 6);
  }
  out.doubles(centers_.data(), static_cast<std::size_t>(count) * static_cast<std::size_t>(rows_));
  // The queue, the kept factorisations (their guides) and the chart being worked on.
  out.u64(open_.size());
  for (int c : open_) {
    out.i32(c);
  }
  std::vector<int> kept;
  for (const auto& entry : factored_) {
    kept.push_back(entry.first);
  }
  std::sort(kept.begin(), kept.end());
  out.u64(kept.size());
  for (int c : kept) {
    const KeptFactorisation& k = factored_.at(c);
    out.i32(c);
    out.u64(k.bytes);
    out.matrix(k.reference);
  }
  out.i32(work_.chart);
  out.i32(work_.children);
  out.f64(work_.last_target(0));
  out.f64(work_.last_target(1));
  out.i32(work_.repeats);
  out.f64(work_.smallest_child);
  out.matrix(work_.chart >= 0 ? center_reference_ : Eigen::MatrixXd());
  // The counters that decide or are reported.
  out.f64(min_radius_);
  out.u64(kept_bytes_);
  out.i32(held_tangents_);
  out.f64(boundary_peak_bytes_);
  out.i32(refactored_charts_);
  out.i32(singular_crossings_);
  out.i32(sheet_rejections_);
  out.string(first_crossing_);
  for (int k : capped_) {
    out.i32(k);
  }
  out.i32(shrunk_charts_);
}

void AtlasBuilder::read_state(BinaryReader& in, CoveringSummary& summary) {
  const std::uint32_t version = in.u32("version");
  if (version != kAtlasStateVersion) {
    in.fail("the atlas's state has format version " + std::to_string(version) +
            "; this tessera reads version " + std::to_string(kAtlasStateVersion));
  }
  // The fingerprint: the same problem, start, domain and options, or nothing is continued.
  check_run_fingerprint(in, identity());
  const WorkDone done = read_work_done(in, "charts");
  seconds_before_ = done.build_seconds;
  counts_before_ = done.counts;
  summary.resumed_from = CoveringSummary::ResumedFrom{};
  summary.resumed_from->charts = done.count;
  summary.resumed_from->build_seconds = done.build_seconds;
  summary.resumed_from->counts = done.counts;
  const int count = done.count;
  // The charts.
  std::vector<double> indexed_radius(static_cast<std::size_t>(count));
  charts_.reserve(static_cast<std::size_t>(count));
  tangents_.reserve(static_cast<std::size_t>(count));
  frames_.reserve(static_cast<std::size_t>(count));
  held_tangents_ = 0;
  for (int c = 0; c < count; ++c) {
    Chart chart;
    chart.radius = in.f64("chart radius");
    indexed_radius[static_cast<std::size_t>(c)] = in.f64("chart radius");
    chart.parent = in.i32("chart parent");
    chart.orientation = static_cast<signed char>(in.u8("chart orientation"));
    chart.jacobian_scale = in.f32("chart jacobian_scale");
    chart.queued = in.u8("chart queued") != 0;
    chart.eligible = static_cast<signed char>(in.u8("chart eligible"));
    if (chart.parent < -1 || chart.parent >= count || !(chart.radius > 0)) {
      in.fail("corrupt: chart " + std::to_string(c) + " has parent " +
              std::to_string(chart.parent) + " and radius " + exact_number(chart.radius));
    }
    std::vector<ChartPolygon::Vertex> vertices(in.count("polygon", 20));
    for (auto& v : vertices) {
      v.s = in.f64("polygon vertex");
      v.t = in.f64("polygon vertex");
      v.edge_label = in.i32("polygon edge label");
      if (v.edge_label < ChartPolygon::kNoNeighbour || v.edge_label >= count) {
        in.fail("corrupt: chart " + std::to_string(c) + " has an edge labelled " +
                std::to_string(v.edge_label));
      }
    }
    chart.polygon = ChartPolygon::from_vertices(std::move(vertices));
    charts_.push_back(std::move(chart));
    Eigen::MatrixXd tangent;
    if (in.u8("tangent held") != 0) {
      tangent.resize(rows_, 2);
      in.doubles("tangent", tangent.data(), static_cast<std::size_t>(tangent.size()));
      ++held_tangents_;
    }
    tangents_.push_back(std::move(tangent));
    Eigen::Matrix<double, 2, 3> frame;
    in.doubles("frame", frame.data(), 6);
    frames_.push_back(frame);
  }
  centers_.resize(count);
  in.doubles("centres", centers_.data(),
             static_cast<std::size_t>(count) * static_cast<std::size_t>(rows_));
  // The index, rebuilt as it was built: the same inserts and refits in the same order.
  for (int c = 0; c < count; ++c) {
    index_.insert(c, center(c), indexed_radius[static_cast<std::size_t>(c)]);
    if (index_.refit_due()) {
      index_.refit(centers_.matrix());
    }
  }
  const auto chart_index = [&](const char* field) {
    const int c = in.i32(field);
    if (c < 0 || c >= count) {
      in.fail("corrupt: " + std::string(field) + " " + std::to_string(c) + " is no chart");
    }
    return c;
  };
  const std::size_t queued = in.count("queue", 4);
  for (std::size_t k = 0; k < queued; ++k) {
    open_.push_back(chart_index("queued chart"));
  }
  const std::size_t kept = in.count("kept factorisations", 12);
  for (std::size_t k = 0; k < kept; ++k) {
    const int c = chart_index("kept factorisation");
    KeptFactorisation entry;
    entry.bytes = static_cast<std::size_t>(in.u64("kept bytes"));
    entry.reference = in.matrix("kept reference");
    if (entry.reference.size() > 0 &&
        (entry.reference.rows() != rows_ || entry.reference.cols() != 2)) {
      in.fail("corrupt: a reference basis is " + std::to_string(entry.reference.rows()) + "×" +
              std::to_string(entry.reference.cols()));
    }
    factored_.emplace(c, std::move(entry));
  }
  work_.chart = in.i32("chart in progress");
  if (work_.chart < -1 || work_.chart >= count) {
    in.fail("corrupt: the chart in progress " + std::to_string(work_.chart) + " is no chart");
  }
  work_.children = in.i32("children");
  work_.last_target(0) = in.f64("last target");
  work_.last_target(1) = in.f64("last target");
  work_.repeats = in.i32("repeats");
  work_.smallest_child = in.f64("smallest child");
  center_reference_ = in.matrix("centre reference");
  min_radius_ = in.f64("min_radius");
  kept_bytes_ = static_cast<std::size_t>(in.u64("kept_bytes"));
  const int held = in.i32("held tangents");
  if (held != held_tangents_) {
    in.fail("corrupt: " + std::to_string(held) + " tangent bases counted, " +
            std::to_string(held_tangents_) + " stored");
  }
  boundary_peak_bytes_ = in.f64("boundary peak");
  refactored_charts_ = in.i32("refactored charts");
  singular_crossings_ = in.i32("singular crossings");
  sheet_rejections_ = in.i32("sheet rejections");
  first_crossing_ = in.string("first crossing");
  for (int& k : capped_) {
    k = in.i32("radius caps");
  }
  shrunk_charts_ = in.i32("shrunk charts");
  if (in.remaining() != 0) {
    in.fail("corrupt: " + std::to_string(in.remaining()) + " bytes after the atlas's state");
  }
}

// A finished (or stopped) build continued into a larger domain: the eligibility of every chart
// is judged again against the new domain, and each chart with a corner still uncovered is
// queued, in chart order (deterministic). Closed charts stay as they are.
void AtlasBuilder::reopen_for_extension(CoveringSummary& summary) {
  int reopened = 0;
  for (int c = 0; c < chart_count(); ++c) {
    charts_[c].eligible = -1;
  }
  for (int c = 0; c < chart_count(); ++c) {
    if (!charts_[c].queued && c != work_.chart && next_open_vertex(c) >= 0) {
      enqueue(c);
      ++reopened;
    }
  }
  summary.notes.push_back("extended the checkpoint's atlas of " + std::to_string(chart_count()) +
                          " charts into " + domain_.describe() + ": " +
                          std::to_string(reopened) +
                          " of its charts had corners left open and were continued");
}

}  // namespace tessera::detail

namespace tessera {

AtlasStateHeader read_atlas_state_header(const std::string& state) {
  BinaryReader in(state, "atlas checkpoint");
  const std::uint32_t version = in.u32("version");
  if (version != kAtlasStateVersion) {
    in.fail("the atlas's state has format version " + std::to_string(version) +
            "; this tessera reads version " + std::to_string(kAtlasStateVersion));
  }
  const detail::RunFingerprint fingerprint = detail::read_run_fingerprint(in);
  AtlasStateHeader header;
  header.problem = fingerprint.problem;
  header.dimension = fingerprint.dimension;
  for (const auto& [name, value] : fingerprint.options) {
    if (name == "tolerance") {
      header.tolerance = value;
    } else if (name == "step") {
      header.step = value;
    }
  }
  header.charts = in.i32("chart count");
  return header;
}

}  // namespace tessera
