// SPDX-License-Identifier: MIT
// The advancing front's builder (PITMAN), internal to the front method: its state and steps.
// Defined in advancing_front.cpp (the front's steps) and front_bands.cpp (bands of M ∩ S
// narrower than the step).
#pragma once

#include <Eigen/Core>
#include <chrono>
#include <memory>
#include <numbers>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "tessera/core/counted_problem.h"
#include "tessera/core/domain.h"
#include "tessera/core/implicit_problem.h"
#include "tessera/core/linearization.h"
#include "tessera/methods/covering.h"
#include "tessera/methods/front/advancing_front.h"
#include "tessera/methods/front/front_state.h"
#include "tessera/methods/common/run_fingerprint.h"

namespace tessera {
class BinaryReader;
class BinaryWriter;
}  // namespace tessera

namespace tessera::front_detail {

constexpr double kTwoPi = 2.0 * std::numbers::pi;
// Front loops up to this length are closed by a triangulation of the loop itself.
constexpr int kMaxClosedLoop = 6;
// Edges longer than this multiple of h are avoided where a choice exists.
constexpr double kMaxEdgeRatio = 1.5;
// Radians added to a frontal vertex's priority key per layer (generation) it is away from the
// start; see FrontBuilder::priority.
constexpr double kLayerWeight = 0.05;
// A frontal vertex whose step runs into the mesh is undone and tried again later, at most this
// many times, its priority key raised by kDeferralWeight radians each time (see defer).
constexpr int kMaxDeferrals = 3;
constexpr double kDeferralWeight = 0.5;

// Thrown inside the builder to stop the run; caught in triangulate_by_front, which keeps the
// mesh built so far (it is valid: every step leaves a consistent partial mesh).
struct StopRun {
  CoveringTermination termination;
  std::string message;
};

// A gap in the neighbourhood of a frontal vertex: counterclockwise from open edge (x_c, last)
// to open edge (x_c, first), `angle` radians wide in the tangent plane.
struct Gap {
  int last;
  int first;
  double angle;
};

class FrontBuilder {
 public:
  FrontBuilder(const ImplicitProblem& problem, const Domain& domain, const FrontOptions& options)
      : problem_(problem),
        domain_(domain),
        options_(options),
        space_(problem.space()),
        state_(space_, options.step * options.collision_distance_fraction) {}

  /// Builds from the start (or continues options.checkpoint.resume_from; then the start must
  /// be the checkpointed run's). \throw InvalidArgument if that state is corrupt or another
  /// run's.
  void run(const Eigen::VectorXd& start_point, const Linearization& start_frame,
           CoveringSummary& summary);
  FrontState& state() { return state_; }

 private:
  void build_initial_hexagon(const Eigen::VectorXd& center, const Linearization& frame);
  void process(int center);
  /// After `process(center)` stopped with a front collision: undoes its triangles and vertices
  /// back to `checkpoint` and puts center back in the front with a later turn, so that its
  /// neighbours change the front there first. False (nothing undone) if center was deferred
  /// kMaxDeferrals times already, or the step merged vertices (a merge is not undone).
  bool defer(int center, const FrontState::Checkpoint& checkpoint, int merges_before,
             const StopRun& stop);
  std::vector<Gap> find_gaps(int center, const std::vector<FanChain>& chains,
                             const Eigen::MatrixXd& U) const;
  void close_gap(int center, const Linearization& frame, const Eigen::MatrixXd& U, const Gap& gap);
  std::optional<int> colliding_front_vertex(int center, int previous, const Eigen::VectorXd& x,
                                            const Eigen::MatrixXd& U);
  void connect_to_front_vertex(int center, int previous, int w, const Eigen::MatrixXd& U);
  bool try_merge(int center, int first, int last, const Linearization& frame);
  void add_closing_triangle(int center, int last, int first, const Eigen::MatrixXd& U);
  void require_fit(const Triangle& t, const Eigen::MatrixXd& U);
  /// Projects x_c + h·U·direction onto M (chord, with step-halving continuation on failure).
  Eigen::VectorXd new_point(int center, const Linearization& frame, const Eigen::MatrixXd& U,
                            double angle);
  int add_point(const Eigen::VectorXd& x);
  /// Adds the triangle, then reopens the bridges its corners now have.
  void add_triangle(int a, int b, int c);
  /// Makes v and an exterior neighbour frontal again where the open edge between them runs
  /// through S: M ∩ S beyond that edge is not covered yet (see the definition).
  void reopen_bridges(int v);
  /// True if v has exterior neighbours beyond two opposite faces of S (normals more than 120°
  /// apart): v lies in a band of M ∩ S narrower than about 2h.
  bool is_in_band(int v);
  /// Closes a gap below α_min at an exterior vertex z by one triangle, as if z were frontal;
  /// leaves it if the triangle does not fit. U: the tangent frame of a vertex near z.
  void close_small_gap_outside(int z, const Eigen::MatrixXd& U);
  /// Caches the tangent basis at a new frontal vertex v from its creator's factorisation.
  void remember_tangent(int v, const Linearization& frame);
  bool close_small_loop(int center, const Eigen::MatrixXd& U);
  /// The next frontal vertex in the order of options.order; nullopt when the front is empty.
  std::optional<int> next_frontal();
  /// Re-keys v in the smallest-gap-first order (removes it if it is no longer frontal).
  void refresh_priority(int v);
  /// The smallest gap angle at v, in v's own tangent plane (cached per vertex).
  double smallest_gap(int v);
  /// The key of v in the smallest-gap-first order: the smallest gap, plus kLayerWeight per
  /// layer for gaps that need no merge (see docs/algorithms/front.md, *Order*).
  double priority(int v);
  double deferral_penalty(int v) const {
    return static_cast<std::size_t>(v) < deferrals_.size() ? kDeferralWeight * deferrals_[v]
                                                           : 0.0;
  }
  /// The process's resident memory, and less the tangent bases the front holds (its open
  /// boundary), into the summary's peaks; then the free heap goes back to the system. Every
  /// kMemorySampleVertices processed vertices from kReleaseHeapDimension on: the front's peak
  /// is inside its build, which the covering's samples between stages miss.
  void sample_memory(CoveringSummary& summary) const;
  static constexpr int kMemorySampleVertices = 64;
  /// Frees v's cached tangent basis (2n doubles) once v is finished: the cache then holds
  /// only the front, not the whole mesh.
  void release_tangent(int v) {
    if (static_cast<std::size_t>(v) < tangent_cache_.size()) {
      tangent_cache_[v] = Eigen::MatrixXd();
    }
  }
  /// The cached tangent basis of v, or else of one of its neighbours; null if none is known.
  const Eigen::MatrixXd* cached_tangent_near(int v) const;
  /// U oriented so that v's triangles turn counterclockwise.
  Eigen::MatrixXd oriented_frame(int v, const Eigen::MatrixXd& basis,
                                 const std::vector<FanChain>& chains) const;

  // Checkpoints (front_checkpoint.cpp, front_checkpoint.h).
  double checkpoint_bytes() const;  // about what save_checkpoint writes
  void save_checkpoint();
  /// At a stop: saves unless the state is over max_bytes_at_stop (then a note says so).
  void save_checkpoint_at_stop(CoveringSummary& summary);
  void write_state(BinaryWriter& out) const;
  void read_state(BinaryReader& in, CoveringSummary& summary);
  detail::RunIdentity identity() const;
  Eigen::VectorXd start_;  // the start point, for the fingerprint
  std::chrono::steady_clock::time_point build_start_;
  double seconds_before_ = 0.0;  // build time of the runs before a resumed checkpoint
  WorkCounts counts_before_;     // and their work
  int processed_ = 0;            // frontal vertices processed (the memory samples' cadence)

  const ImplicitProblem& problem_;
  const Domain& domain_;
  const FrontOptions& options_;
  // The rows of R^n this process holds (all n in one process): points and tangent bases are
  // rows of it, and every inner product between them is reduced through space_ (SPMD: the
  // same calls on every rank; docs/cluster.md).
  const std::shared_ptr<const AmbientSpace> space_;
  FrontState state_;
  CorrectorOptions chord_options_;
  double step_ = 0.0;
  int merges_ = 0;
  int step_reductions_ = 0;
  int connections_ = 0;
  int deferred_steps_ = 0;
  std::vector<int> deferrals_;  // per vertex: how often its step was undone and deferred
  // Set once reopen_bridges has reopened a vertex: only then are small gaps at exterior
  // vertices closed (close_small_gap_outside), so runs without a band are as before.
  bool bridged_ = false;
  std::set<std::pair<double, int>> by_gap_;     // (gap angle, vertex), smallest first
  std::vector<double> gap_key_;                 // key of each vertex in by_gap_, NaN if absent
  std::vector<Eigen::MatrixXd> tangent_cache_;  // n×2 tangent basis per vertex, empty if unknown
  std::vector<int> layer_;      // per vertex: 0 for the start, 1 + its creator's layer otherwise
  int new_vertex_layer_ = 1;    // the layer of the vertices the current step creates
  Linearization center_frame_;  // at the vertex being processed
  Linearization gap_frame_;     // for the gap angles of the priority order
  // normal_k·normal_l of the domain's faces (K×K), computed once: is_in_band's test of
  // opposite faces (on split states one reduction instead of one per pair and call).
  Eigen::MatrixXd face_cosines_;
};

}  // namespace tessera::front_detail
