// SPDX-License-Identifier: MIT
// The continuation of method `atlas`: charts are created on M, cut each other's polygons, and
// are added where a polygon has an uncovered corner, until none is left (Henderson's section 5).
// Internal to the method: atlas.cpp turns the charts into a mesh.
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <deque>
#include <string>
#include <unordered_map>
#include <vector>

#include "tessera/core/domain.h"
#include "tessera/core/factorisation_cache.h"
#include "tessera/core/implicit_problem.h"
#include "tessera/core/linearization.h"
#include "tessera/core/point_storage.h"
#include "tessera/core/process_memory.h"
#include "tessera/geometry/principal_view.h"
#include "tessera/methods/atlas/atlas.h"
#include "tessera/methods/atlas/atlas_triangulation.h"
#include "tessera/methods/atlas/chart_index.h"
#include "tessera/methods/atlas/chart_polygon.h"
#include "tessera/methods/common/run_fingerprint.h"
#include "tessera/methods/covering_result.h"

namespace tessera {
class BinaryReader;
class BinaryWriter;
}  // namespace tessera

namespace tessera::detail {

// Why a chart's radius is smaller than the tolerance asks for (sqrt(2ε/κ), at most max_radius).
enum class RadiusCap : signed char {
  None,
  Curvature,  // κR ≤ max_turning_angle: M turns within the disk (its local feature size)
  NotAGraph,  // the disk of the tolerance's radius reaches past a turn of M or onto another
              // part of it (not a graph of slope ≤ 1), or beyond the corrector's convergence
  Grading,    // a neighbouring chart is much smaller (radii change by at most radius_growth − 1
              // per unit length)
  Reach,      // another part of M (not a transversal crossing) lies within the disk
  Band,       // M ∩ S is a band narrower than two radii here (Domain::band_width)
};

struct Chart {
  double radius = 0.0;
  ChartPolygon polygon;
  int parent = -1;
  signed char orientation = 0;  // sign of det([J; Tᵀ]) at the centre; 0: not watched
  float jacobian_scale = 0.0f;  // σ_min(J) at the centre (only where crossings are watched)
  bool queued = false;
  // is_eligible, once known (−1: not yet): it depends on the centre, tangent plane and radius
  // only, and costs O(n) per face of the domain, for every corner the chart is asked about.
  mutable signed char eligible = -1;
};

class AtlasBuilder {
 public:
  AtlasBuilder(const ImplicitProblem& problem, const Domain& domain, const AtlasOptions& options);

  /// Builds the atlas from `start` (or continues options.checkpoint.resume_from, then `start`
  /// must be the start of the checkpointed run).
  /// \throw InvalidArgument if the state to resume from is corrupt or from another problem,
  ///        start, domain or options (the message names what differs).
  void run(const Eigen::VectorXd& start, CoveringSummary& summary);

  int chart_count() const { return static_cast<int>(charts_.size()); }
  Eigen::Map<const Eigen::VectorXd> center(int c) const { return centers_.column(c); }
  /// The split of R^n the centres and bases are rows of (R^n itself in one process).
  const std::shared_ptr<const AmbientSpace>& space() const { return space_; }
  /// The centres of the charts `keep` marks, in chart order, handed over without a copy (they
  /// become the mesh's vertices). The builder's centres are gone afterwards.
  PointStorage take_centers(const std::vector<bool>& keep);
  /// The chart's tangent basis (n×2), the frame its polygon lives in. Retired charts (closed,
  /// among closed neighbours) do not keep it; it is recomputed if they are touched again.
  /// The reference stays valid until the next chart is added.
  const Eigen::MatrixXd& tangent(int c) const {
    if (tangents_[c].size() == 0) {
      restore_tangent(c);
    }
    return tangents_[c];
  }
  const Chart& chart(int c) const { return charts_[c]; }
  /// Read access to the charts for triangulate_atlas (centres copied; set take_centers to hand
  /// them over instead). Valid while the builder lives.
  AtlasCells cells() const {
    AtlasCells cells;
    cells.ambient_dimension = space_->local_rows();
    cells.space = space_;
    cells.chart_count = chart_count();
    cells.center = [this](int c) { return Eigen::VectorXd(center(c)); };
    cells.tangent = [this](int c) { return Eigen::MatrixXd(tangent(c)); };
    cells.polygon = [this](int c) -> const ChartPolygon& { return charts_[c].polygon; };
    cells.radius = [this](int c) { return charts_[c].radius; };
    cells.is_closed = [this](int c) { return is_closed(c); };
    return cells;
  }
  bool is_closed(int c) const {
    const Chart& ch = charts_[c];
    if (ch.polygon.is_empty()) {
      return false;
    }
    for (const auto& v : ch.polygon.vertices()) {
      if (v.edge_label == ChartPolygon::kNoNeighbour) {
        return false;
      }
    }
    return ch.polygon.farthest_exterior_vertex(ch.radius) < 0;
  }

 private:
  // `expected`: the radius the chart will likely get (its parent's), 0 if unknown.
  bool choose_radius(Linearization& at_center, double trial, double expected,
                     double& radius, RadiusCap& cap);
  bool project(Linearization& at_center, double distance, Eigen::VectorXd& y);
  // A borrowed linearisation whose chord failed gets its own factorisation at its point (its
  // tangent basis kept, so that the chart's frame does not move). \return false if it has one.
  bool factor_own(Linearization& at_center);
  bool probe(Linearization& at_center, double distance, Eigen::VectorXd& y,
             double known_contraction = -1.0, double offset = -1.0,
             double* contraction = nullptr);
  void evaluate_jacobian(const Eigen::VectorXd& x);
  double jacobian_scale() const;
  // `near`: the parent's linearisation, whose factorisation the chart may borrow (may be null).
  int add_chart(const Eigen::VectorXd& x, int parent, Linearization& linearization,
                const Linearization* near = nullptr);
  void connect_neighbours(int k);
  void rebuild_polygon(int k);
  void shrink_radius(int c, double radius);
  int next_open_vertex(int c) const;
  Eigen::Vector2d child_position(int c, int vertex) const;
  // `near`: the factorisation of the chart the point was projected from (chord first).
  void snap_to_domain_boundary(Eigen::VectorXd& y, double radius, const Linearization& near);
  bool is_eligible(int c) const;
  bool same_sheet(int a, int b, const Eigen::VectorXd& offset) const;
  signed char orientation_sign(const Eigen::Ref<const Eigen::MatrixXd>& T) const;
  void enqueue(int c);
  // The chart whose children are being placed, with what decides its next child: a checkpoint
  // taken between two children holds it, and a resumed build continues it.
  struct ChartWork {
    int chart = -1;  // −1: none (between charts)
    int children = 0;
    Eigen::Vector2d last_target{std::nan(""), std::nan("")};
    int repeats = 0;  // children in a row that did not remove their corner
    double smallest_child = 0.0;
  };
  ChartWork work_;
  // The tangent basis that guided the factorisation of work_.chart's centre (empty: none), so
  // that a resumed build factors it again to the same bits (the border of a sparse problem's
  // bordered matrix is chosen from it).
  Eigen::MatrixXd center_reference_;
  void take_center_factorisation(int c, Linearization& at_center);
  void place_children(int c, Linearization& at_center, CoveringSummary& summary);
  void report(CoveringSummary& summary);
  // Checkpoints (atlas_checkpoint.cpp).
  void save_checkpoint();
  double checkpoint_bytes() const;  // about what save_checkpoint writes
  void write_state(BinaryWriter& out);
  void read_state(BinaryReader& in, CoveringSummary& summary);
  detail::RunIdentity identity() const;  // what a state's fingerprint holds
  void reopen_for_extension(CoveringSummary& summary);  // AtlasCheckpointing::extend
  Eigen::VectorXd start_;
  std::chrono::steady_clock::time_point build_start_;
  double seconds_before_ = 0.0;  // build time of the runs before a resumed checkpoint
  WorkCounts counts_before_;     // and their work
  void fail(CoveringSummary& summary, CoveringTermination why, const std::string& message) {
    summary.termination = why;
    summary.message = message;
    stopped_ = true;
  }

  const ImplicitProblem& problem_;
  const Domain& domain_;
  const AtlasOptions& options_;
  const int n_;
  // The rows of R^n this process holds (all n in one process): every n-vector below is sized by
  // rows_, and every inner product between them is reduced through space_ (SPMD: the same
  // calls on every rank; docs/cluster.md).
  const std::shared_ptr<const AmbientSpace> space_;
  const int rows_;
  ChartIndex index_;
  const bool watch_crossings_;
  // Radius probes by the chord's first step only (sparse problems, where solves are the cost).
  const bool first_step_probes_;
  // Charts borrow their parent's factorisation where it reaches (AtlasOptions::
  // share_factorisations, sparse problems, no checkpoints); how many did.
  bool share_factorisations_;
  int borrowed_charts_ = 0;
  // The last charts' own factorisations (views that share their factors): a chart whose
  // parent's does not reach it tries the nearest of these before factoring. They may outlive
  // the charts' own copies: at most four, and beyond the newest two 256 MB, on top of
  // max_factorisation_bytes.
  FactorisationLenders lenders_{4, std::size_t{256} << 20};
  PointStorage centers_;  // n per chart
  // n×2 per chart while it may still be cut; empty once retired (memory that grows like n per
  // vertex, not 3n). Mutable: a retired chart's basis is restored on demand (a cache).
  mutable std::vector<Eigen::MatrixXd> tangents_;
  // (P·T)ᵀ for a fixed orthonormal P: R^n → R³ (frame_view_): fixes the frame of a restored
  // basis (any basis of the plane, turned onto the old one), so the chart's polygon stays valid.
  std::vector<Eigen::Matrix<double, 2, 3>> frames_;
  const PrincipalView frame_view_;
  Eigen::Matrix<double, 2, 3> frame_signature(const Eigen::MatrixXd& T) const;
  void restore_tangent(int c) const;
  void retire_finished_charts(int c);
  std::vector<Chart> charts_;
  std::deque<int> open_;  // charts that may have eligible exterior vertices
  // Factorisations of queued charts, at most options_.max_factorisation_bytes of them.
  // After a resume the factorisations are not there (a cache, not saved): they are made again
  // when the chart's turn comes, guided by the same reference basis as the first time, which
  // gives the same bits (the same border, the same LU).
  struct KeptFactorisation {
    Linearization linearization;
    std::size_t bytes = 0;
    Eigen::MatrixXd reference;  // the basis that guided it (the parent's); empty: none
  };
  std::unordered_map<int, KeptFactorisation> factored_;
  std::size_t kept_bytes_ = 0;
  // Kept entries per shared factorisation (Linearization::factorisation_identity) and the bytes
  // of its factors, counted once in kept_bytes_ however many charts borrowed it.
  struct SharedFactors {
    int holders = 0;
    std::size_t bytes = 0;
  };
  std::unordered_map<const void*, SharedFactors> shared_factors_;
  void forget_kept(std::unordered_map<int, KeptFactorisation>::iterator found);
  // Tangent bases held (charts not retired) and the boundary's largest bytes so far.
  mutable int held_tangents_ = 0;  // restore_tangent (const) brings one back
  double boundary_peak_bytes_ = 0.0;
  double boundary_bytes() const {
    return static_cast<double>(kept_bytes_) + 16.0 * static_cast<double>(rows_) * held_tangents_;
  }
  void note_boundary_bytes() {
    boundary_peak_bytes_ = std::max(boundary_peak_bytes_, boundary_bytes());
  }
  int refactored_charts_ = 0;  // charts whose factorisation was dropped (over the budget)
  void keep_factorisation(int c, Linearization&& linearization, const Eigen::MatrixXd& reference);
  // A few factorisations of processed charts, reused (fewer allocations at small n).
  std::vector<Linearization> spare_;
  void give_back(Linearization&& linearization) {
    // (Not a borrowed one: a spare would keep another chart's factors alive, uncounted.)
    if (spare_.size() < kMaxSpares && !linearization.is_borrowed()) {
      spare_.push_back(std::move(linearization));
    }
  }
  static constexpr std::size_t kMaxSpares = 2;
  Linearization take_spare() {
    if (spare_.empty()) {
      return Linearization();
    }
    Linearization spare = std::move(spare_.back());
    spare_.pop_back();
    return spare;
  }
  std::vector<int> candidates_;     // scratch
  std::vector<int> retire_around_;  // scratch of retire_finished_charts
  std::vector<int> retire_closed_;  // scratch of retire_finished_charts
  std::vector<int> retire_open_;    // scratch of retire_finished_charts
  Eigen::VectorXd offset_;          // scratch
  Eigen::VectorXd predicted_;       // scratch
  Eigen::MatrixXd jacobian_;        // J at the last point checked for singularity
  Eigen::VectorXd probe_;           // scratch
  Eigen::VectorXd probe_residual_;  // scratch: F at a probe
  Eigen::VectorXd probe_step_;      // scratch: its chord step
  Eigen::VectorXd probe_start_;     // scratch: its predicted point
  Eigen::MatrixXd quadratic_;       // scratch: n×12, the offsets a(θ_i) of choose_radius
  Eigen::MatrixXd probe_residuals_; // scratch: (n−2)×6, −F at the first-step probes
  Eigen::MatrixXd probe_steps_;     // scratch: n×6, their chord steps
  Eigen::MatrixXd parent_tangent_;  // scratch
  Linearization scratch_;           // workspace of full Gauss–Newton
  bool stopped_ = false;
  int singular_crossings_ = 0;
  int sheet_rejections_ = 0;
  std::string first_crossing_;
  double min_radius_ = 0.0;
  std::array<int, 6> capped_ = {0, 0, 0, 0, 0, 0};  // charts by RadiusCap
  int shrunk_charts_ = 0;  // radii reduced after the chart was made (shrink_radius)
};

}  // namespace tessera::detail
