// SPDX-License-Identifier: MIT
#include "tessera/methods/atlas/atlas_builder.h"

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <sstream>

#include "tessera/core/binary_stream.h"
#include "tessera/core/corrector.h"
#include "tessera/core/describe.h"
#include "tessera/core/error.h"
#include "tessera/core/point_storage.h"
#include "tessera/core/process_memory.h"
#include "tessera/core/sparse_lu.h"

namespace tessera::detail {
namespace {

// The initial polygon is a square of this half-width (in radii): it contains the disk, and its
// corners (at 1.7 R) are exterior until neighbours cut them.
constexpr double kInitialHalfWidth = 1.2;
// A chart is processed until its polygon has no exterior vertex; more children than this (times
// R/r for children of radius r: about 2πR/r of them go round its rim) means the cuts do not
// remove the vertices they should (rounding, or charts on other sheets). The bound was once
// (R/r)², the children's area: at r = R/28 that let one chart place 50 000 children without
// progress before failing (bratu2d:N=10 at step 0.7; at 0.6, 16 000 in 21 s; hours at
// n = 10⁵).
constexpr int kMaxChildrenPerChart = 64;
// Below this dimension the orientation det([J; Tᵀ]) is cheap enough to watch for singular
// crossings at every step (dense problems only; see docs/algorithms/atlas.md).
constexpr int kMaxCrossingTestDimension = 200;
// A chart whose own disk boundary cannot be reached by pointOnDisk is shrunk by this factor.
constexpr double kShrinkFactor = 0.7;
// A child centre farther than this many radii from its parent's centre, in the parent's tangent
// plane, is no child: the parent's disk need not reach it (see the children's loop).
constexpr double kMaxRimOvershoot = 1.02;
// Children in a row that leave their corner open before the chart is shrunk instead.
constexpr int kMaxRepeatedTargets = 3;
// Every so many charts the resident memory is sampled and, from kReleaseHeapDimension on, the
// heap's free pages go back to the system (release_free_heap).
constexpr int kReleaseHeapCharts = 64;

}  // namespace

AtlasBuilder::AtlasBuilder(const ImplicitProblem& problem, const Domain& domain,
                           const AtlasOptions& options)
    : problem_(problem),
      domain_(domain),
      options_(options),
      n_(problem.ambient_dimension()),
      space_(problem.space()),
      rows_(space_->local_rows()),
      index_(space_),
      watch_crossings_(!problem.has_sparse_jacobian() &&
                       problem.ambient_dimension() <= kMaxCrossingTestDimension),
      first_step_probes_(problem.has_sparse_jacobian()),
      share_factorisations_(options.share_factorisations && problem.has_sparse_jacobian() &&
                            !options.checkpoint.save && !options.checkpoint.resume_from),
      centers_(rows_),
      frame_view_(space_) {}

void AtlasBuilder::evaluate_jacobian(const Eigen::VectorXd& x) {
  jacobian_.resize(n_ - 2, n_);
  problem_.jacobian(x, jacobian_);
}

// σ_min(J) of the last evaluate_jacobian: how far the point is from the singular points of F
// (for codimension 1, |∇F|).
double AtlasBuilder::jacobian_scale() const {
  const int m = n_ - 2;
  const Eigen::MatrixXd& J = jacobian_;
  if (m == 1) {
    return J.norm();
  }
  const Eigen::MatrixXd gram = J * J.transpose();
  return std::sqrt(
      std::max(0.0, Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(gram, Eigen::EigenvaluesOnly)
                        .eigenvalues()(0)));
}

signed char AtlasBuilder::orientation_sign(const Eigen::Ref<const Eigen::MatrixXd>& T) const {
  // sign det([J; Tᵀ]) with J of the last evaluate_jacobian: along one sheet it keeps its sign
  // as long as T stays transversal to ker J; it changes where J loses rank between two
  // points, i.e. at a singular curve.
  const int m = n_ - 2;
  const Eigen::MatrixXd& J = jacobian_;
  double det = 0.0;
  if (n_ == 3) {
    const Eigen::Vector3d t0 = T.col(0);
    const Eigen::Vector3d t1 = T.col(1);
    det = J.row(0).transpose().dot(Eigen::Vector3d(t0.cross(t1)));
  } else {
    Eigen::MatrixXd bordered(n_, n_);
    bordered.topRows(m) = J;
    bordered.bottomRows(2) = T.transpose();
    det = bordered.partialPivLu().determinant();
  }
  return det > 0 ? 1 : (det < 0 ? -1 : 0);
}

int AtlasBuilder::add_chart(const Eigen::VectorXd& x, int parent, Linearization& linearization,
                            const Linearization* near) {
  Eigen::MatrixXd& parent_tangent = parent_tangent_;
  if (parent >= 0) {
    parent_tangent = tangent(parent);
  }
  // The parent's factorisation (its own, or the one it borrowed) serves this chart too where
  // the tangent iteration from it converges (borrow_factorisation); else the nearest of the last
  // charts' own factorisations within two of the parent's radii (farther ones measured smaller
  // radii: bratu2d:N=100 at four radii had 4.6 % more vertices); otherwise the chart factors
  // its own, and lends it to the charts after it.
  bool borrowed = share_factorisations_ && near != nullptr &&
                  borrow_factorisation(problem_, *near, x, linearization);
  if (!borrowed && share_factorisations_ && parent >= 0 &&
      lenders_.borrow(problem_, x, 0.5 * charts_[parent].radius, linearization)) {
    borrowed = true;
  }
  if (!borrowed) {
    if (!linearization.factor(problem_, x, parent >= 0 ? &parent_tangent : nullptr)) {
      return -1;  // DF lost rank: a singular point; the caller moves the centre
    }
    if (share_factorisations_) {
      lenders_.lend(problem_, linearization);
    }
  }
  if (parent >= 0 &&
      std::abs(space_->products(parent_tangent, linearization.tangent_basis()).determinant()) <
          options_.min_sheet_cosine) {
    return -1;  // the projection jumped to another sheet; the caller tries another point
  }
  // The radii are graded: R ≤ R_j + (radius_growth − 1)·‖x − c_j‖ for every chart j whose disk
  // the new one may overlap (for the parent, at distance R_j, this is R ≤ radius_growth·R_j).
  // A radius function with Lipschitz constant below 1 never lets a disk contain a neighbour's,
  // whose power cell would then be empty or a sliver that the charts' slightly different
  // tangent planes see differently (holes, inconsistent triangles); it also keeps the triangles
  // between charts of different sizes well shaped.
  double trial = options_.step;
  if (parent >= 0) {
    const double slope = options_.radius_growth - 1.0;
    trial = std::min(trial, options_.radius_growth * charts_[parent].radius);
    index_.candidates(x, trial, candidates_);
    for (int m : candidates_) {
      const double distance = space_->distance(center(m), x);
      if (distance < trial + charts_[m].radius) {
        trial = std::min(trial, charts_[m].radius + slope * distance);
      }
    }
  }
  // Where M ∩ S is a band narrower than two radii (bratu2d's lower sheet between ε = 0 and 0.3,
  // at steps of 0.6 and more), charts spanning it cover it from both faces at once and the
  // atlas fell apart there; the disk is held to half the band's width (not below a quarter of
  // the step, which keeps a wedge's tip from asking for ever smaller charts).
  bool band_capped = false;
  if (!domain_.is_unbounded()) {
    const double band = std::max(
        0.25 * options_.step,
        0.5 * domain_.band_width(x, linearization.tangent_basis(), 2.0 * options_.step));
    band_capped = band < trial;
    trial = std::min(trial, band);
  }
  double radius = 0.0;
  RadiusCap cap = RadiusCap::None;
  const double expected = parent >= 0 ? charts_[parent].radius : 0.0;
  // (A borrowed factorisation that cannot measure the disk gives way to the chart's own.)
  if (!choose_radius(linearization, trial, expected, radius, cap) &&
      !(factor_own(linearization) && choose_radius(linearization, trial, expected, radius, cap))) {
    return -2;
  }
  if (band_capped && cap == RadiusCap::Grading) {
    cap = RadiusCap::Band;
  }
  // The reach: another part of M (a chart whose centre lies far from this tangent plane, not a
  // transversal crossing) within the disks means M comes back within their distance d, so
  // disks of radius above d/2 would overlap across the gap and glue or double the two parts.
  // Both are capped at d/2 (the older one shrunk, its polygon and its neighbours' rebuilt).
  index_.candidates(x, radius, candidates_);
  std::vector<int> too_close;
  for (int m : candidates_) {
    const Eigen::VectorXd offset = center(m) - x;
    const double distance = space_->norm(offset);
    if (m == parent || distance >= radius + charts_[m].radius || distance == 0.0) {
      continue;
    }
    const Eigen::Matrix2d cosines = space_->products(tangent(m), linearization.tangent_basis());
    if (std::abs(cosines.determinant()) < options_.min_sheet_cosine) {
      continue;  // a transversal crossing (section 8), kept apart by the sheet test
    }
    const Eigen::Vector2d along = space_->tangent_coordinates(linearization.tangent_basis(), offset);
    const double normal_part =
        std::sqrt(std::max(0.0, space_->squared_norm(offset) - along.squaredNorm()));
    if (normal_part > 0.5 * along.norm()) {
      if (0.5 * distance < radius) {
        radius = 0.5 * distance;
        cap = RadiusCap::Reach;
      }
      too_close.push_back(m);
    }
  }
  if (radius < min_radius_) {
    return -2;
  }
  ++capped_[static_cast<int>(cap)];
  borrowed_charts_ += linearization.solves_from_elsewhere() ? 1 : 0;
  const int k = chart_count();
  Chart chart;
  chart.radius = radius;
  chart.polygon = ChartPolygon(kInitialHalfWidth * radius);
  chart.parent = parent;
  if (watch_crossings_) {
    // J at x was evaluated by the caller (the crossing checks); the first chart's here.
    if (parent < 0) {
      evaluate_jacobian(x);
    }
    chart.orientation = orientation_sign(linearization.tangent_basis());
    chart.jacobian_scale = static_cast<float>(jacobian_scale());
  }
  charts_.push_back(std::move(chart));
  centers_.push_back(x);
  const Eigen::MatrixXd& T = linearization.tangent_basis();
  tangents_.push_back(T);
  ++held_tangents_;
  note_boundary_bytes();
  frames_.push_back(frame_signature(T));
  connect_neighbours(k);
  index_.insert(k, x, radius);
  if (index_.refit_due()) {
    index_.refit(centers_.matrix());
  }
  for (int m : too_close) {
    const double half = 0.5 * space_->distance(center(m), center(k));
    if (charts_[m].radius > half && half >= min_radius_) {
      shrink_radius(m, half);
    }
  }
  return k;
}

PointStorage AtlasBuilder::take_centers(const std::vector<bool>& keep) {
  int kept = 0;
  for (int c = 0; c < centers_.size(); ++c) {
    if (keep[c]) {
      centers_.move_column(c, kept++);
    }
  }
  centers_.resize(kept);
  return std::move(centers_);
}

bool AtlasBuilder::same_sheet(int a, int b, const Eigen::VectorXd& offset) const {
  // Charts on one sheet have nearly parallel tangent planes and each centre lies close to the
  // other's tangent plane; charts of two sheets that cross (section 8) fail the first test,
  // charts of two nearby parallel sheets the second.
  const Eigen::Matrix2d cosines = space_->products(tangent(a), tangent(b));
  if (std::abs(cosines.determinant()) < options_.min_sheet_cosine) {
    return false;
  }
  const Eigen::Vector2d along = space_->tangent_coordinates(tangent(a), offset);
  const double normal_part =
      std::sqrt(std::max(0.0, space_->squared_norm(offset) - along.squaredNorm()));
  return normal_part <= 0.5 * along.norm();
}

void AtlasBuilder::connect_neighbours(int k) {
  const auto ck = center(k);
  const double rk = charts_[k].radius;
  index_.candidates(ck, rk, candidates_);
  Eigen::VectorXd& offset = offset_;
  std::sort(candidates_.begin(), candidates_.end());  // deterministic cut order
  for (int m : candidates_) {
    const double rm = charts_[m].radius;
    offset = center(m) - ck;
    const double distance = space_->norm(offset);
    if (distance >= rk + rm || distance == 0.0) {
      continue;
    }
    if (!same_sheet(k, m, offset) && m != charts_[k].parent) {
      ++sheet_rejections_;
      continue;
    }
    // Power bisector in each chart's own tangent coordinates: |p|² − R_k² ≤ |p − p_m|² − R_m².
    const Eigen::Vector2d pk = space_->tangent_coordinates(tangent(k), offset);
    const Eigen::Vector2d pm = space_->tangent_coordinates(tangent(m), -offset);
    if (pk.norm() > 0) {
      charts_[k].polygon.cut(pk(0) / pk.norm(), pk(1) / pk.norm(),
                             (pk.squaredNorm() + rk * rk - rm * rm) / (2.0 * pk.norm()), m);
    }
    if (pm.norm() > 0 &&
        charts_[m].polygon.cut(pm(0) / pm.norm(), pm(1) / pm.norm(),
                               (pm.squaredNorm() + rm * rm - rk * rk) / (2.0 * pm.norm()), k) &&
        !charts_[m].queued && next_open_vertex(m) >= 0) {
      // (Cuts only shrink a polygon; this re-queues a chart whose corner a cut moved, which
      // matters only for charts that were skipped while the queue held them.)
      enqueue(m);
    }
  }
}

// The polygon of chart k from scratch: its square, cut by every overlapping chart of its sheet.
void AtlasBuilder::rebuild_polygon(int k) {
  const auto ck = center(k);
  const double rk = charts_[k].radius;
  charts_[k].polygon = ChartPolygon(kInitialHalfWidth * rk);
  std::vector<int> candidates;
  index_.candidates(ck, rk, candidates);
  std::sort(candidates.begin(), candidates.end());
  Eigen::VectorXd offset;
  for (int m : candidates) {
    const double rm = charts_[m].radius;
    offset = center(m) - ck;
    const double distance = space_->norm(offset);
    if (m == k || distance >= rk + rm || distance == 0.0) {
      continue;
    }
    if (!same_sheet(k, m, offset) && m != charts_[k].parent && charts_[m].parent != k) {
      continue;
    }
    const Eigen::Vector2d pk = space_->tangent_coordinates(tangent(k), offset);
    if (pk.norm() > 0) {
      charts_[k].polygon.cut(pk(0) / pk.norm(), pk(1) / pk.norm(),
                             (pk.squaredNorm() + rk * rk - rm * rm) / (2.0 * pk.norm()), m);
    }
  }
}

// A smaller radius moves every power bisector of chart c towards c: its polygon shrinks and its
// neighbours' grow, so all of them are rebuilt, and the neighbours re-queued if a corner of
// theirs is now uncovered.
void AtlasBuilder::shrink_radius(int c, double radius) {
  const double old_radius = charts_[c].radius;
  charts_[c].radius = radius;
  charts_[c].eligible = -1;  // the margin is measured in radii
  ++shrunk_charts_;
  rebuild_polygon(c);
  std::vector<int> neighbours;
  index_.candidates(center(c), old_radius, neighbours);
  for (int m : neighbours) {
    if (m == c || space_->distance(center(m), center(c)) >= old_radius + charts_[m].radius) {
      continue;
    }
    rebuild_polygon(m);
    if (!charts_[m].queued && next_open_vertex(m) >= 0) {
      enqueue(m);
    }
  }
}

bool AtlasBuilder::is_eligible(int c) const {
  // Charts up to domain_margin radii outside S are completed too, so that every chart whose
  // star can reach into S has all its triangles; the outer ones are cut away by the clipping.
  // The margin is measured along M: a face at distance d meets the chart's tangent plane at
  // distance d/‖Tᵀb‖ from its centre, much farther than d where the face cuts M at a shallow
  // angle (seen on bvp, whose ε = 0 face does), and charts there would all be wasted.
  if (domain_.is_unbounded()) {
    return true;
  }
  if (charts_[c].eligible >= 0) {
    return charts_[c].eligible != 0;
  }
  charts_[c].eligible = 0;
  const double margin = options_.domain_margin * charts_[c].radius;
  const auto x = center(c);
  for (int k = 0; k < static_cast<int>(domain_.half_spaces().size()); ++k) {
    const double d = domain_.signed_distance(k, x);
    const Eigen::VectorXd& normal = domain_.half_spaces()[k].normal;
    // (The tangent plane only where it matters: a retired chart's is recomputed.)
    if (d < -margin ||
        (d < 0 && d < -margin * space_->tangent_coordinates(tangent(c), normal).norm())) {
      return false;
    }
  }
  charts_[c].eligible = 1;
  return true;
}

int AtlasBuilder::next_open_vertex(int c) const {
  return is_eligible(c) ? charts_[c].polygon.farthest_exterior_vertex(charts_[c].radius) : -1;
}

void AtlasBuilder::run(const Eigen::VectorXd& start, CoveringSummary& summary) {
  const bool saves = static_cast<bool>(options_.checkpoint.save);
  // With checkpoints, a factorisation must depend on its matrix alone, not on the object's
  // history (KLU's refactorisation reuses the last pivots): a resumed build makes its
  // factorisations in new objects (atlas_checkpoint.h). Only then: full factorisations cost a
  // run with KLU 5–10 % of its factorisation time (bench/RESULTS.md, "Checkpoints"), and a run
  // without checkpoints need not pay it. So a run with --checkpoint repeats any other run with
  // --checkpoint bit for bit, and one without it up to the rounding of the pivots.
  std::optional<FullPivotingScope> full_pivoting;
  if (saves || options_.checkpoint.resume_from) {
    full_pivoting.emplace();
  }
  min_radius_ = options_.step * options_.min_radius_fraction;
  start_ = start;
  build_start_ = std::chrono::steady_clock::now();
  if (options_.checkpoint.resume_from) {
    BinaryReader in(*options_.checkpoint.resume_from, "atlas checkpoint");
    read_state(in, summary);
    if (options_.checkpoint.extend) {
      reopen_for_extension(summary);
    }
  } else {
    Linearization linearization;
    const int first = add_chart(start, -1, linearization);
    if (first < 0) {
      fail(summary, CoveringTermination::StartFailed,
           "no chart can be centred at the start point " + describe_point(start, *space_) +
               (first == -1 ? ": DF is singular there"
                            : ": the corrector does not converge even at radius " +
                                  std::to_string(min_radius_)));
      return;
    }
    // Sharing pays where a factorisation costs many solves: the fill of its LU says so, from the
    // pattern alone (so the choice, and the mesh, are the same run to run).
    share_factorisations_ = share_factorisations_ && worth_sharing(linearization);
    enqueue(first);
    keep_factorisation(first, std::move(linearization), Eigen::MatrixXd());
  }
  ProgressSchedule progress_schedule;
  int next_heap_release = kReleaseHeapCharts;
  while ((!open_.empty() || work_.chart >= 0) && !stopped_) {
    Linearization at_center;
    int c = work_.chart;
    if (c >= 0) {
      // Resumed between two children of chart c: its factorisation is made again as before.
      at_center.factor(problem_, center(c),
                       center_reference_.size() > 0 ? &center_reference_ : nullptr);
    } else {
      c = open_.front();
      open_.pop_front();
      charts_[c].queued = false;
      if (next_open_vertex(c) < 0) {
        // Closed (or out of the margin) before its turn came: the neighbours placed since cut
        // its corners away. Nothing to place, so no factorisation (re-queued charts have none
        // kept: 15 % of the charts on bratu2d were factored again here only to find nothing).
        if (auto found = factored_.find(c); found != factored_.end()) {
          forget_kept(found);
          if (found->second.linearization.is_factored()) {
            give_back(std::move(found->second.linearization));
          }
          factored_.erase(found);
        }
        retire_finished_charts(c);
        continue;
      }
      take_center_factorisation(c, at_center);
      work_ = ChartWork{c, 0, Eigen::Vector2d(std::nan(""), std::nan("")), 0, charts_[c].radius};
    }
    place_children(c, at_center, summary);
    work_.chart = -1;
    give_back(std::move(at_center));
    retire_finished_charts(c);
    if (chart_count() >= next_heap_release) {
      // The resident memory against the boundary's (before the free heap is returned, so that
      // what glibc keeps counts), then the bases of retired charts and the factorisations used
      // go to the system, so that it follows what the atlas holds (bvp:points=10000: peak 673
      // → 569 MB).
      next_heap_release = chart_count() + kReleaseHeapCharts;
      summary.note_resident_memory(boundary_bytes());
      if (n_ >= kReleaseHeapDimension) {
        release_free_heap();
      }
    }
    if (options_.progress && progress_schedule.is_due(chart_count())) {
      options_.progress({chart_count(), 0, static_cast<int>(open_.size())});
    }
  }
  if (saves && !stopped_) {
    save_checkpoint();  // the complete build: a run killed after it need not build again
  }
  report(summary);
}

// Places children on the rim of chart c until its polygon has no exterior vertex left (or the
// run stops). work_ holds the counts that decide the next child.
void AtlasBuilder::place_children(int c, Linearization& at_center, CoveringSummary& summary) {
  const Eigen::MatrixXd Tc = tangent(c);
  const Eigen::VectorXd xc = center(c);
  Eigen::VectorXd y(rows_);
  for (int vertex = next_open_vertex(c); vertex >= 0 && !stopped_; vertex = next_open_vertex(c)) {
    if (chart_count() >= options_.max_vertices) {
      fail(summary, CoveringTermination::VertexLimit,
           "stopped at " + std::to_string(chart_count()) + " charts (max_vertices)");
      break;
    }
    if (options_.stop_requested && options_.stop_requested()) {
      if (options_.checkpoint.save && checkpoint_bytes() <= options_.checkpoint.max_bytes_at_stop) {
        save_checkpoint();
      } else if (options_.checkpoint.save) {
        summary.notes.push_back("no checkpoint was written at the stop: its " +
                                std::to_string(std::lround(checkpoint_bytes() / 1e6)) +
                                " MB would have delayed the mesh (max_bytes_at_stop); the last "
                                "periodic checkpoint stands");
      }
      fail(summary, CoveringTermination::Interrupted,
           "interrupted at " + std::to_string(chart_count()) + " charts");
      break;
    }
    if (options_.checkpoint.save && options_.checkpoint.is_due && options_.checkpoint.is_due()) {
      save_checkpoint();
    }
    int& children = work_.children;
    int& repeats = work_.repeats;
    Eigen::Vector2d& last_target = work_.last_target;
    double& smallest_child = work_.smallest_child;
    // A chart next to much smaller ones needs about 2πR/r of them around its rim.
    if (++children > kMaxChildrenPerChart * std::max(1.0, charts_[c].radius / smallest_child)) {
      fail(summary, CoveringTermination::ProjectionFailed,
           "the chart at " + describe_point(xc, *space_) +
               " could not be closed: its neighbours do not "
               "cut away the uncovered corners of its polygon");
      break;
    }
    const auto& v = charts_[c].polygon.vertices()[vertex];
    const Eigen::Vector2d direction = Eigen::Vector2d(v.s, v.t).normalized();
    // If the last child did not remove its corner (snapping moved it away), the next one is
    // placed where the corner asks, unsnapped.
    const bool target_repeated = Eigen::Vector2d(v.s, v.t).isApprox(last_target, 1e-12);
    last_target = Eigen::Vector2d(v.s, v.t);
    repeats = target_repeated ? repeats + 1 : 0;
    if (repeats >= kMaxRepeatedTargets && charts_[c].radius > 4.0 * min_radius_) {
      // Neither the child aimed at the corner nor Henderson's on the rim removed it: the
      // rim there is out of reach (bratu2d:N=32 at step 0.7: a chart of radius 0.7 at the
      // ignition fold, whose rim child lies on another sheet, placed the same inner child
      // 746 times before failing). Henderson's cap "where the mapping exists": shrink.
      shrink_radius(c, kShrinkFactor * charts_[c].radius);
      smallest_child = std::min(smallest_child, charts_[c].radius);
      repeats = 0;
      last_target = Eigen::Vector2d(std::nan(""), std::nan(""));
      continue;
    }
    // The new centre goes on the disk boundary towards the uncovered corner (pointOnDisk:
    // projected orthogonally to this chart's tangent plane). Where that fails, or lands on a
    // singular point, nearer and farther points are tried.
    int child = -1;
    Linearization at_child = take_spare();
    // A corner the last child did not remove gets Henderson's placement, which always does.
    const Eigen::Vector2d target =
        target_repeated ? charts_[c].radius * direction : child_position(c, vertex);
    bool shrunk = false;
    for (double fraction : {1.0, 0.85, 1.1, 0.7, 0.5, 0.35, 0.25}) {
      const Eigen::Vector2d s = fraction * target;
      y = xc + Tc * s;
      // A projection that drifted beyond the disk (Gauss–Newton, where the chord failed,
      // may move along the tangent plane) gives a child that may not overlap this chart, so
      // its cut cannot remove the corner: the same child came back 1800 times on bratu2d:N=10
      // at step 0.7 (0.7503 from a chart of radius 0.7, its own radius 0.025).
      const bool projected = project(at_center, s.norm(), y);
      // Disk placement only: hexagonal placement aims up to 1.9 R on purpose, and its own
      // geometry decides (the rule changed the crossing's hexagonal mesh beyond its bound).
      const bool beyond_disk =
          projected && options_.placement == AtlasPlacement::Disk &&
          space_->tangent_coordinates(Tc, y - xc).norm() > kMaxRimOvershoot * charts_[c].radius;
      if (!projected || beyond_disk) {
        if (fraction == 1.0 && charts_[c].radius > 4.0 * min_radius_ &&
            s.norm() >= 0.99 * charts_[c].radius) {
          // pointOnDisk fails on the chart's own disk: M is no graph over it in this
          // direction or the corrector does not reach its rim, so the radius was too large
          // (its measurement missed this direction). A child placed nearer would not cut
          // the corner away; the chart is shrunk instead (Henderson's cap "where the
          // mapping exists", applied where it was found to fail).
          shrink_radius(c, kShrinkFactor * charts_[c].radius);
          shrunk = true;
          break;
        }
        continue;
      }
      if (watch_crossings_) {
        evaluate_jacobian(y);  // also used by add_chart for the new chart's orientation
      }
      if (watch_crossings_ && charts_[c].orientation != 0) {
        // Never centre a chart at or next to a singular point: its chord iteration would
        // not converge beyond a tiny radius. σ_min falling tenfold in one step means one.
        if (jacobian_scale() < 0.1 * charts_[c].jacobian_scale) {
          continue;
        }
        const signed char across = orientation_sign(Tc);
        if (across == 0) {
          continue;
        }
        if (across != charts_[c].orientation) {
          ++singular_crossings_;
          if (first_crossing_.empty()) {
            first_crossing_ = describe_point(0.5 * (xc + y), *space_);
          }
        }
      }
      if (!target_repeated) {
        snap_to_domain_boundary(y, charts_[c].radius, at_center);
      }
      child = add_chart(y, c, at_child, &at_center);
      if (child >= 0) {
        break;
      }
    }
    if (shrunk) {
      give_back(std::move(at_child));
      smallest_child = std::min(smallest_child, charts_[c].radius);
      continue;
    }
    if (child < 0) {
      fail(summary, CoveringTermination::ProjectionFailed,
           "no chart could be centred beyond " + describe_point(xc, *space_) +
               " in the direction of its uncovered corner: the corrector does not converge "
               "or DF is singular there");
      break;
    }
    smallest_child = std::min(smallest_child, charts_[child].radius);
    enqueue(child);
    keep_factorisation(child, std::move(at_child), Tc);
  }
}

}  // namespace tessera::detail
