// SPDX-License-Identifier: MIT
// The atlas builder's state written and read (atlas_checkpoint.h says what and why).
#include "tessera/methods/atlas/atlas_checkpoint.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <sstream>
#include <utility>
#include <vector>

#include "tessera/core/binary_stream.h"
#include "tessera/core/counted_problem.h"
#include "tessera/core/describe.h"
#include "tessera/core/error.h"
#include "tessera/methods/atlas/atlas_builder.h"

namespace tessera::detail {
namespace {

// F is evaluated at two points start + 0.125·(sin(0.618·(i+1)·(k+1)))_i, k = 0, 1: a changed
// definition or parameter of the problem changes these values, whatever its name says.
constexpr int kFingerprintPoints = 2;

Eigen::VectorXd fingerprint_point(const Eigen::VectorXd& start, int k) {
  Eigen::VectorXd x = start;
  for (Eigen::Index i = 0; i < x.size(); ++i) {
    x(i) += 0.125 * std::sin(0.618 * static_cast<double>(i + 1) * (k + 1));
  }
  return x;
}

// The options that decide the atlas, by name (max_vertices and the callbacks do not).
std::vector<std::pair<std::string, double>> decisive_options(const AtlasOptions& o) {
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

bool same_bits(double a, double b) {
  return std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b);
}

bool same_bits(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
  if (a.rows() != b.rows() || a.cols() != b.cols()) {
    return false;
  }
  for (Eigen::Index k = 0; k < a.size(); ++k) {
    if (!same_bits(a.data()[k], b.data()[k])) {
      return false;
    }
  }
  return true;
}

// Empty if the domain {x : b_k·(x − p_k) ≥ 0 for all k} contains the old one; else which of
// its faces does not. A sufficient test, exact for boxes: each face must be parallel to one of
// the old domain's, with the old face on its inner side (the old domain may be bounded in
// directions the new one is not). In one process (the checkpoint's domain is whole).
std::string face_not_containing(const Domain& domain, const std::vector<HalfSpace>& old_faces) {
  for (std::size_t k = 0; k < domain.half_spaces().size(); ++k) {
    const HalfSpace& face = domain.half_spaces()[k];
    bool inside = false;
    for (const HalfSpace& old : old_faces) {
      const bool parallel = old.normal.size() == face.normal.size() &&
                            (old.normal - face.normal).lpNorm<Eigen::Infinity>() <= 1e-12;
      if (parallel && face.normal.dot(old.point - face.point) >= 0) {
        inside = true;
        break;
      }
    }
    if (!inside) {
      return "its face " + (face.label.empty() ? std::to_string(k) : "'" + face.label + "'") +
             " cuts into the old domain or bounds a direction the old one did not";
    }
  }
  return "";
}

std::string number(double value) {
  std::ostringstream text;
  text.precision(17);
  text << value;
  return text.str();
}

}  // namespace

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
  // The fingerprint of the run.
  out.string(problem_.name());
  out.i32(n_);
  out.i32(rows_);
  out.matrix(start_);
  for (int k = 0; k < kFingerprintPoints; ++k) {
    Eigen::VectorXd F(n_ - 2);
    bool evaluated = true;
    try {
      problem_.evaluate(fingerprint_point(start_, k), F);
    } catch (const std::exception&) {
      evaluated = false;
    }
    out.u8(evaluated ? 1 : 0);
    out.matrix(evaluated ? F : Eigen::VectorXd());
  }
  out.u64(domain_.half_spaces().size());
  for (const HalfSpace& h : domain_.half_spaces()) {
    out.matrix(h.normal);
    out.matrix(h.point);
  }
  const auto options = decisive_options(options_);
  out.u64(options.size());
  for (const auto& [name, value] : options) {
    out.string(name);
    out.f64(value);
  }
  // The work done, over all runs (this one and those it continued).
  out.i32(chart_count());
  out.f64(seconds_before_ +
          std::chrono::duration<double>(std::chrono::steady_clock::now() - build_start_).count());
  WorkCounts counts = counts_before_;
  if (const auto* counted = dynamic_cast<const CountedProblem*>(&problem_)) {
    counts += counted->counts();
  }
  out.i64(counts.function_evaluations);
  out.i64(counts.jacobian_evaluations);
  out.i64(counts.factorisations);

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
  const std::string name = in.string("problem name");
  const int n = in.i32("n");
  const int rows = in.i32("rows");
  if (name != problem_.name() || n != n_ || rows != rows_) {
    in.fail("it was made for problem '" + name + "' in R^" + std::to_string(n) + ", not for '" +
            problem_.name() + "' in R^" + std::to_string(n_));
  }
  const Eigen::MatrixXd start = in.matrix("start", rows_, 1);
  for (int k = 0; k < kFingerprintPoints; ++k) {
    const bool evaluated = in.u8("fingerprint") != 0;
    const Eigen::MatrixXd saved = in.matrix("fingerprint");
    Eigen::VectorXd F(n_ - 2);
    bool here = true;
    try {
      // At the checkpoint's points (near its start): F decides before the start does.
      problem_.evaluate(fingerprint_point(start.col(0), k), F);
    } catch (const std::exception&) {
      here = false;
    }
    if (evaluated != here || (here && !same_bits(saved, Eigen::MatrixXd(F)))) {
      std::ostringstream where;
      Eigen::Index i = 0;
      while (here && evaluated && i + 1 < F.size() && saved.size() == F.size() &&
             same_bits(saved(i), F(i))) {
        ++i;
      }
      where << (here && evaluated && saved.size() == F.size()
                    ? ": F_" + std::to_string(i) + " = " + number(F(i)) + " here, " +
                          number(saved(i)) + " in the checkpoint"
                    : "");
      in.fail("F of problem '" + name + "' differs from the checkpoint's at a fixed test point" +
              where.str() + ": the problem's definition, parameters or file changed since");
    }
  }
  if (!same_bits(start, Eigen::MatrixXd(start_))) {
    in.fail("its start point differs from this run's (" + describe_point(start.col(0), *space_) +
            " there, " + describe_point(start_, *space_) + " here): give the same --start");
  }
  const std::size_t faces = in.count("domain", 16);
  std::vector<HalfSpace> old_faces(faces);
  bool same_domain = faces == domain_.half_spaces().size();
  for (std::size_t k = 0; k < faces; ++k) {
    old_faces[k].normal = in.matrix("domain normal", rows_, 1);
    old_faces[k].point = in.matrix("domain point", rows_, 1);
    same_domain = same_domain &&
                  same_bits(Eigen::MatrixXd(old_faces[k].normal),
                            Eigen::MatrixXd(domain_.half_spaces()[k].normal)) &&
                  same_bits(Eigen::MatrixXd(old_faces[k].point),
                            Eigen::MatrixXd(domain_.half_spaces()[k].point));
  }
  if (options_.checkpoint.extend) {
    const std::string outside = face_not_containing(domain_, old_faces);
    if (!outside.empty()) {
      in.fail("this run's domain (" + domain_.describe() +
              ") does not contain the checkpoint's: " + outside +
              "; `extend` continues an atlas into a larger region only");
    }
  } else if (!same_domain) {
    in.fail("its domain (--box) differs from this run's (" + domain_.describe() + ")");
  }
  const auto options = decisive_options(options_);
  const std::size_t option_count = in.count("options", 9);
  if (option_count != options.size()) {
    in.fail("it holds " + std::to_string(option_count) + " options, this tessera " +
            std::to_string(options.size()));
  }
  for (const auto& [option, value] : options) {
    const std::string saved_name = in.string("option name");
    const double saved = in.f64("option value");
    if (saved_name != option || !same_bits(saved, value)) {
      in.fail("AtlasOptions::" + option + " = " + number(value) + " here, but " + saved_name +
              " = " + number(saved) + " in the checkpoint: the continued atlas would differ");
    }
  }
  {
    CoveringSummary::ResumedFrom resumed;
    resumed.charts = in.i32("chart count");
    resumed.build_seconds = in.f64("build seconds");
    resumed.counts.function_evaluations = in.i64("work");
    resumed.counts.jacobian_evaluations = in.i64("work");
    resumed.counts.factorisations = in.i64("work");
    if (resumed.charts < 1) {
      in.fail("corrupt: " + std::to_string(resumed.charts) + " charts");
    }
    seconds_before_ = resumed.build_seconds;
    counts_before_ = resumed.counts;
    summary.resumed_from = resumed;
  }
  const int count = summary.resumed_from->charts;
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
              std::to_string(chart.parent) + " and radius " + number(chart.radius));
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
  AtlasStateHeader header;
  header.problem = in.string("problem name");
  header.dimension = in.i32("n");
  const int rows = in.i32("rows");
  in.matrix("start", rows, 1);
  for (int k = 0; k < detail::kFingerprintPoints; ++k) {
    in.u8("fingerprint");
    in.matrix("fingerprint");
  }
  const std::size_t faces = in.count("domain", 16);
  for (std::size_t k = 0; k < faces; ++k) {
    in.matrix("domain normal", rows, 1);
    in.matrix("domain point", rows, 1);
  }
  const std::size_t options = in.count("options", 9);
  for (std::size_t k = 0; k < options; ++k) {
    const std::string name = in.string("option name");
    const double value = in.f64("option value");
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
