// SPDX-License-Identifier: MIT
// run_covering: the pipeline of stages every covering method passes through (the stages are in
// covering_stages.cpp, the checks of a completed covering in covering_checks.cpp), the wrapper
// that presents a distributed or metric-scaled problem to them, and the stage runner that
// counts, times, chooses the form after a stop request and releases memory around each stage.
#include "tessera/methods/covering.h"

#include <chrono>
#include <cmath>
#include <memory>
#include <new>
#include <optional>
#include <string_view>
#include <utility>
#include <vector>

#include "tessera/core/counted_problem.h"
#include "tessera/core/domain.h"
#include "tessera/core/error.h"
#include "tessera/core/face_projection.h"
#include "tessera/core/parallel_for.h"
#include "tessera/core/process_memory.h"
#include "tessera/core/scaled_problem.h"
#include "tessera/geometry/bezier_patch.h"
#include "tessera/methods/covering_stages.h"

namespace tessera {

void CoveringOptions::validate_common(const char* owner) const {
  TESSERA_CHECK(std::isfinite(tolerance) && tolerance >= 0,
                owner << "::tolerance = " << tolerance << " must be a finite number >= 0");
  TESSERA_CHECK(std::isfinite(step) && step > 0,
                owner << "::step = " << step << " must be a finite number > 0");
  TESSERA_CHECK(max_vertices >= 3,
                owner << "::max_vertices = " << max_vertices << " must be at least 3");
  TESSERA_CHECK(
      std::isfinite(max_start_distance) && max_start_distance >= 0,
      owner << "::max_start_distance = " << max_start_distance << " must be a finite number >= 0");
  TESSERA_CHECK(std::isfinite(check_seconds_after_stop) && check_seconds_after_stop >= 0,
                owner << "::check_seconds_after_stop = " << check_seconds_after_stop
                      << " must be a finite number >= 0");
}

namespace {

// The problem, the start and the domain in the coordinates the stages work in, and the result
// taken back from them: the stages never see the two special cases.
//  - A distributed problem (SPMD, docs/cluster.md) runs on this rank's rows: the start and the
//    mesh hold them, a domain given in R^n is cut to them, and every rank runs the stages alike.
//    Its metric is its own business (petsc::ScaledPetscProblem presents the metric's
//    coordinates): ScaledProblem cannot scale rows it does not hold.
//  - A problem with a metric (CoordinateBlock) is covered as M̃ = W M in y = W x (ScaledProblem,
//    scale_domain), so that steps, radii, the tolerance and every distance are lengths in the
//    metric; the result's points go back to x.
// Every evaluation of F and DF is counted (CountedProblem).
class CoveringCoordinates {
 public:
  /// \throw InvalidArgument if the start's or the domain's size does not fit the problem (this
  ///        rank's rows of a distributed one, or R^n for its domain), or a distributed problem
  ///        has a metric.
  CoveringCoordinates(const ImplicitProblem& problem, const Eigen::VectorXd& start,
                      const Domain& domain)
      : n_(problem.ambient_dimension()), space_(problem.space()), rows_(space_->local_rows()) {
    check_sizes(problem, start, domain);
    weights_ = space_->is_distributed() ? Eigen::VectorXd() : metric_weights(problem);
    const bool is_weighted = weights_.size() > 0;
    if (is_weighted) {
      scaled_.emplace(problem, weights_);
    }
    // A distributed problem's domain given in R^n is cut to this rank's rows.
    const bool cuts_domain =
        space_->is_distributed() && !domain.is_unbounded() && !domain.is_distributed();
    if (is_weighted) {
      converted_domain_ = scale_domain(domain, weights_);
    } else if (cuts_domain) {
      converted_domain_ = domain.distributed(space_);
    }
    domain_ = is_weighted || cuts_domain ? &converted_domain_ : &domain;
    original_domain_ = &domain;
    if (is_weighted) {
      start_ = weights_.cwiseProduct(start);
    } else {
      start_ = start;
    }
    problem_.emplace(is_weighted ? static_cast<const ImplicitProblem&>(*scaled_) : problem);
  }
  CoveringCoordinates(const CoveringCoordinates&) = delete;
  CoveringCoordinates& operator=(const CoveringCoordinates&) = delete;

  const CountedProblem& problem() const { return *problem_; }
  const Domain& domain() const { return *domain_; }
  const Eigen::VectorXd& start() const { return start_; }
  int ambient_dimension() const { return n_; }
  int rows() const { return rows_; }

  /// A mesh without vertices in these coordinates: of this rank's rows for a distributed problem.
  TriangleMesh empty_mesh() const {
    TriangleMesh mesh(rows_);
    if (space_->is_distributed()) {
      mesh.set_space(space_);
    }
    return mesh;
  }

  /// The result's points and patches back in the problem's own coordinates x = W⁻¹ y.
  void to_problem_coordinates(CoveringResult& result) const {
    if (weights_.size() == 0) {
      return;
    }
    TriangleMesh& mesh = result.mesh;
    for (int v = 0; v < mesh.vertex_count(); ++v) {
      mesh.mutable_point(v).array() /= weights_.array();
    }
    put_back_on_faces(mesh);
    for (CubicBezierPatch& patch : result.patches) {
      patch = CubicBezierPatch(weights_.cwiseInverse().asDiagonal() * patch.control_points());
    }
  }

 private:
  // A vertex on a face in y = W x is on it exactly (place_on_faces), but y/w rounds: the bound
  // u ≤ 20 of bvp:points=16 becomes y ≤ 20·w, and (20·w)/w = 20 + 3.6e-15. Vertices across a
  // face of S by no more than kOnFaceTolerance are put back on it exactly, so that none lies
  // outside S, not even by rounding (issue 34). Coordinate faces (a box's) cost O(1) a vertex.
  void put_back_on_faces(TriangleMesh& mesh) const {
    const Domain& domain = *original_domain_;
    const int faces = static_cast<int>(domain.half_spaces().size());
    std::vector<int> axis(static_cast<std::size_t>(faces), -1);  // -1: not a coordinate face
    for (int k = 0; k < faces; ++k) {
      const Eigen::VectorXd& normal = domain.half_spaces()[k].normal;
      if ((normal.array() != 0.0).count() == 1) {
        normal.cwiseAbs().maxCoeff(&axis[k]);
      }
    }
    std::vector<int> across;
    for (int v = 0; v < mesh.vertex_count(); ++v) {
      const auto x = mesh.point(v);
      across.clear();
      for (int k = 0; k < faces; ++k) {
        const HalfSpace& h = domain.half_spaces()[k];
        const double d = axis[k] >= 0 ? h.normal(axis[k]) * (x(axis[k]) - h.point(axis[k]))
                                      : domain.signed_distance(k, x);
        if (d < 0) {
          across.push_back(k);
        }
      }
      if (across.empty()) {
        continue;
      }
      Eigen::VectorXd placed = x;
      place_on_faces(domain, across, placed);
      if ((placed - x).norm() <= kOnFaceTolerance * (1.0 + x.norm())) {
        mesh.mutable_point(v) = placed;
      }
    }
  }

  void check_sizes(const ImplicitProblem& problem, const Eigen::VectorXd& start,
                   const Domain& domain) const {
    if (space_->is_distributed()) {
      TESSERA_CHECK(
          domain.is_unbounded() || (domain.is_distributed() ? domain.ambient_dimension() == rows_
                                                            : domain.ambient_dimension() == n_),
          "domain has " << domain.ambient_dimension() << " rows, but the problem '"
                        << problem.name() << "' is distributed: give its domain in R^" << n_
                        << " or this rank's " << rows_ << " rows of it "
                        << "(Domain::distributed)");
      TESSERA_CHECK(start.size() == rows_, "start point has "
                                               << start.size() << " rows here, but the problem '"
                                               << problem.name() << "' is distributed and holds "
                                               << rows_ << " of its n = " << n_ << " on this rank");
      TESSERA_CHECK(metric_weights(problem).size() == 0,
                    "the distributed problem '"
                        << problem.name()
                        << "' has a metric; work in the metric's coordinates "
                           "(petsc::ScaledPetscProblem) and give the start and the domain in them");
    } else {
      TESSERA_CHECK(
          domain.is_unbounded() || domain.ambient_dimension() == n_,
          "domain is in R^" << domain.ambient_dimension() << " but the problem is in R^" << n_);
      TESSERA_CHECK(start.size() == n_,
                    "start point has " << start.size() << " coordinates, the problem n = " << n_);
    }
  }

  int n_;
  std::shared_ptr<const AmbientSpace> space_;
  int rows_;
  Eigen::VectorXd weights_;  ///< W's diagonal; empty when the problem has no metric
  std::optional<ScaledProblem> scaled_;
  Domain converted_domain_;  ///< W S, or S cut to this rank's rows, when the domain changes
  const Domain* domain_ = nullptr;
  const Domain* original_domain_ = nullptr;  ///< S in the problem's own coordinates
  Eigen::VectorXd start_;
  std::optional<CountedProblem> problem_;
};

// Runs the stages and does, once for every stage, what the stages leave to it:
//  - the form: a stage's own, or its form after a stop request (SIGINT, a batch system's
//    SIGTERM) that ended an earlier stage; the stages poll the request themselves;
//  - the accounting: the evaluations of F and DF, factorisations and time of the stages of one
//    step (the summary's work_by_phase, printed "by step") are counted when the next step
//    begins. A stage that does nothing opens no step; a stage that fails or throws leaves its
//    work to the next step accounted (the start's, when it fails, to "finish");
//  - the memory: what a step freed (factorisations, bases, the atlas's charts) goes back to the
//    system at large n, then the resident memory is sampled.
class StageRunner {
 public:
  StageRunner(const CoveringCoordinates& coordinates, detail::CoveringRun& run)
      : coordinates_(coordinates),
        run_(run),
        releases_heap_(coordinates.ambient_dimension() >= kReleaseHeapDimension) {
    // Blocks of one and a half states or more (tangent bases, factors) come from the system and
    // go back when freed; single states, the most frequent, are reused from the heap.
    if (releases_heap_) {
      map_large_blocks(sizeof(double) * static_cast<std::size_t>(coordinates.rows()) * 3 / 2);
    }
  }

  /// Runs `stage`, or `after_stop` if the run was stopped before (CoveringRun::is_stopped).
  /// Stages in a row of the same step are accounted together.
  /// \return what the stage returned: whether it did its work.
  bool run(std::string_view step, detail::CoveringStage stage, detail::CoveringStage after_stop) {
    report_progress(step);
    if (!open_step_.empty() && open_step_ != step) {
      close_step(open_step_);
      open_step_ = {};
    }
    const std::string_view open_before = open_step_;
    open_step_ = {};  // what a throwing stage did goes to the next step accounted
    const bool did_work = (run_.is_stopped() ? after_stop : stage)(run_);
    open_step_ = did_work ? step : open_before;
    return did_work;
  }
  /// The same for a stage that runs alike after a stop request.
  bool run(std::string_view step, detail::CoveringStage stage) { return run(step, stage, stage); }

  /// Calls `run_stages`; running out of memory there is the run's failure, not an exception:
  /// whatever the stages held is gone, the mesh is empty, and the summary says what happened.
  template <class RunStages>
  void catch_out_of_memory(const RunStages& run_stages) {
    try {
      run_stages();
    } catch (const std::bad_alloc&) {
      run_.result.mesh = run_.empty_mesh;
      run_.result.patches.clear();
      run_.result.summary.record_failure(
          CoveringTermination::ProjectionFailed,
          "out of memory (n = " + std::to_string(coordinates_.ambient_dimension()) +
              "): the problem's Jacobian factorisation or the mesh did not fit; try a coarser "
              "tolerance or step, or fewer unknowns");
    }
  }

  /// Accounts the last step and "finish", takes the result back to the problem's coordinates
  /// and completes the summary (counts, evaluations, wall time).
  CoveringResult finish() {
    if (!open_step_.empty()) {
      close_step(open_step_);
    }
    close_step("finish");
    coordinates_.to_problem_coordinates(run_.result);
    const CountedProblem& problem = run_.problem;
    CoveringSummary& summary = run_.result.summary;
    summary.method = run_.method;
    summary.tolerance = run_.options.tolerance;
    summary.vertex_count = run_.result.mesh.vertex_count();
    summary.triangle_count = run_.result.mesh.triangle_count();
    summary.function_evaluations = problem.function_evaluations();
    summary.jacobian_evaluations = problem.jacobian_evaluations();
    summary.factorisations = problem.factorisations();
    summary.solves = problem.solves();
    summary.factorisation_seconds = problem.factorisation_seconds();
    if (summary.resumed_from) {
      // The work of the runs before the checkpoint this one continued.
      summary.function_evaluations += summary.resumed_from->counts.function_evaluations;
      summary.jacobian_evaluations += summary.resumed_from->counts.jacobian_evaluations;
      summary.factorisations += summary.resumed_from->counts.factorisations;
    }
    summary.work_by_phase = steps_;
    summary.wall_seconds = seconds_since(clock_start_);
    summary.threads = threads_for(problem);
    return std::move(run_.result);
  }

 private:
  using Clock = std::chrono::steady_clock;

  static double seconds_since(Clock::time_point start) {
    return std::chrono::duration<double>(Clock::now() - start).count();
  }

  // A step's work is the counters' growth since the last step was accounted.
  void close_step(std::string_view step) {
    const auto now = Clock::now();
    const WorkCounts counts = run_.problem.counts();
    if (counts.function_evaluations > counted_so_far_.function_evaluations ||
        counts.jacobian_evaluations > counted_so_far_.jacobian_evaluations) {
      steps_.push_back({std::string(step), counts - counted_so_far_,
                        std::chrono::duration<double>(now - step_start_).count()});
    }
    counted_so_far_ = counts;
    step_start_ = now;
    // Then all that is resident counts, nothing of the atlas's boundary being held.
    if (releases_heap_) {
      release_free_heap();
    }
    run_.result.summary.note_resident_memory(0.0);
  }

  const CoveringCoordinates& coordinates_;
  detail::CoveringRun& run_;
  const bool releases_heap_;
  const Clock::time_point clock_start_ = Clock::now();
  Clock::time_point step_start_ = clock_start_;
  std::string_view open_step_;      ///< the step of the stages last run, not yet accounted
  std::string_view reported_step_;  ///< the step whose start the progress callback last heard

  // The start of each step after the build, with the mesh's counts then: the build reports
  // itself (ProgressSchedule), and the clipping, refinement and validation at large n take
  // minutes of their own.
  void report_progress(std::string_view step) {
    const ProgressCallback& progress = run_.options.progress;
    if (!progress || step == reported_step_ || step == "start" || step == "build") {
      return;
    }
    reported_step_ = step;
    CoveringProgress report;
    report.vertex_count = run_.result.mesh.vertex_count();
    report.triangle_count = run_.result.mesh.triangle_count();
    report.stage = step;
    progress(report);
  }
  WorkCounts counted_so_far_;
  std::vector<PhaseWork> steps_;
};

}  // namespace

CoveringResult run_covering(const std::string& method, const ImplicitProblem& problem,
                            const Eigen::VectorXd& start, const Domain& domain,
                            const CoveringOptions& options, const CoveringBuild& build) {
  options.validate_common(method.c_str());
  const CoveringCoordinates coordinates(problem, start, domain);
  detail::CoveringRun run(method, options, build, coordinates.problem(), coordinates.domain(),
                          coordinates.start(), coordinates.empty_mesh());
  StageRunner stages(coordinates, run);
  namespace stage = detail::stage;
  // Each line: the step that counts the stage's work, the stage, and its form after a stop
  // request ended an earlier stage where that differs (covering_stages.h has the contracts).
  if (!stages.run("start", stage::start)) {
    return stages.finish();  // StartFailed
  }
  // Running out of memory in the build or the clipping (the most the run holds) is a failure.
  stages.catch_out_of_memory([&] {
    stages.run("build", stage::build);
    stages.run("clip", stage::clip, stage::clip_after_stop);
    stages.run("clip", stage::close_notches, stage::skip);
    stages.run("clip", stage::swap, stage::skip);
  });
  stages.run("refine", stage::refine, stage::note_tolerance_not_enforced);
  stages.run("validate", stage::validate_and_repair);
  stages.run("patches", stage::refine_repaired, stage::skip);
  stages.run("patches", stage::check_coverage);
  stages.run("patches", stage::patches);
  return stages.finish();
}

}  // namespace tessera
