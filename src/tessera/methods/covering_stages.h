// SPDX-License-Identifier: MIT
// The stages of run_covering (covering.cpp), in the order it runs them: each a function with one
// contract over the run's shared state. The counting, the timing, the choice of a stage's form
// after a stop request and the release of memory between stages are the pipeline's, not theirs.
#pragma once

#include <Eigen/Core>
#include <optional>
#include <string>
#include <utility>

#include "tessera/geometry/triangle_mesh.h"
#include "tessera/methods/covering.h"
#include "tessera/methods/covering_result.h"
#include "tessera/methods/start_point.h"
#include "tessera/methods/stop_grace.h"

namespace tessera::detail {

/// What the stages of one run share: its inputs, in the coordinates the stages work in (the
/// metric's y = W x; this rank's rows of a distributed problem), the result they build, and
/// what a stage finds for the later ones.
struct CoveringRun {
  /// The result starts as `empty_mesh`.
  CoveringRun(const std::string& method, const CoveringOptions& options, const CoveringBuild& build,
              const CountedProblem& problem, const Domain& domain, const Eigen::VectorXd& start,
              TriangleMesh empty_mesh)
      : method(method),
        options(options),
        build(build),
        problem(problem),
        domain(domain),
        start(start),
        empty_mesh(std::move(empty_mesh)) {
    result.mesh = this->empty_mesh;
  }

  const std::string& method;
  const CoveringOptions& options;
  const CoveringBuild& build;
  const CountedProblem& problem;  ///< counts every evaluation of F and DF
  const Domain& domain;
  const Eigen::VectorXd& start;   ///< the start as given, not yet on M
  const TriangleMesh empty_mesh;  ///< no vertex; this rank's rows for a distributed problem
  CoveringResult result;

  // Set by a stage for the later ones.
  std::optional<StartPoint> start_point;   ///< start: the start on M inside S
  std::optional<CoveringContext> context;  ///< build: the method's settings for the skeleton
  bool is_clipped = false;                 ///< clip: the mesh was clipped to S
  std::string clip_refusal;  ///< clip: why the clipping refused the mesh; empty if it did not
  int triangles_before_refinement = 0;  ///< refine: the triangles of the build, clipped
  bool is_refinement_stopped = false;   ///< refine: a stop request ended the refinement
  int repaired_triangles = 0;  ///< validate: the last ones of the mesh were made by a repair
  /// What the final checks (validation, holes covered over) poll: the stop request with the
  /// grace options.check_seconds_after_stop (after_grace), so that after a stop they finish if
  /// they can within it and are cut short if they cannot. One clock for all of them; made by
  /// the first check (a run stopped before then does not ask the request again).
  const StopRequest& checks_stop() {
    if (!checks_stop_) {
      // Each check on M costs about a factorisation (its mean so far).
      const long factorisations = problem.factorisations();
      const double item_seconds =
          factorisations > 0 ? problem.factorisation_seconds() / static_cast<double>(factorisations)
                             : 0.0;
      checks_stop_ =
          after_grace(is_stopped() ? StopRequest([] { return true; }) : options.stop_requested,
                      grace_before_items(options.check_seconds_after_stop, item_seconds));
      if (!checks_stop_) {
        checks_stop_ = [] { return false; };  // no request: never stopped
      }
    }
    return checks_stop_;
  }

  /// Whether a stop request ended a stage before: the termination is Interrupted, or the
  /// refinement was stopped in a run that had failed before (which keeps its first termination;
  /// the stop is then a note).
  bool is_stopped() const {
    return result.summary.termination == CoveringTermination::Interrupted || is_refinement_stopped;
  }

 private:
  StopRequest checks_stop_;
};

/// A stage of the run. \return whether it did its work: false if it had nothing to do (then it
/// evaluated nothing, and its step is not accounted for it) or, for the start, failed.
using CoveringStage = bool (*)(CoveringRun& run);

namespace stage {

/// Projects the start onto M inside S. A failure is an outcome (termination StartFailed, with
/// the corrector's message), not an exception, so that callers always get a summary.
bool start(CoveringRun& run);

/// Runs the method's build from the start on M (CoveringContext::attempt 0).
bool build(CoveringRun& run);

/// Clips the mesh to S when S is bounded, the build gave a boundary edge length and there are
/// triangles (then is_clipped): vertices near a face are snapped onto M ∩ face, the triangles
/// are cut, short boundary edges collapsed (clip_to_domain). A stop request ends it with a valid
/// mesh inside S, ragged where it did not get to (termination Interrupted). If the clipping
/// refuses the mesh and the method asked for it, the build runs again (attempt 1) and is
/// clipped once more; a refusal left is the run's failure (ProjectionFailed).
bool clip(CoveringRun& run);
/// clip after a stop request: the triangles outside S are removed without any projection (and
/// the request is not polled again).
bool clip_after_stop(CoveringRun& run);

/// Closes notches in the clipped boundary (close_boundary_notches): a boundary vertex inside S
/// between two boundary neighbours means M ∩ S uncovered next to it. Not after a refusal.
bool close_notches(CoveringRun& run);

/// Delaunay-type edge swaps in M's tangent planes after clipping, when the method asked for them
/// (the angles at ∂S). A stop request ends them (the mesh is valid after every swap).
bool swap(CoveringRun& run);

/// With a tolerance, checks every triangle and bisects on M until every sample lies within it
/// (refine_to_tolerance); what stays farther is the run's failure (ProjectionFailed). A stop
/// request ends it (termination Interrupted, the largest distance unknown: −1).
bool refine(CoveringRun& run);
/// refine after a stop request: nothing is checked (at large n the bisection costs minutes of
/// factorisations); a note says that the tolerance was not enforced.
bool note_tolerance_not_enforced(CoveringRun& run);

/// Validates the mesh geometrically against M and S (validate). Flipped and overlapping
/// triangles are repaired locally (removed with their fans, the hole triangulated again in M's
/// tangent plane) and the mesh validated again; what cannot be repaired so, and triangles with
/// a vertex outside S, are removed (with the fans that removal pinches) and the run fails with
/// their places: the rest is a valid partial mesh. A defect is never returned as a success.
/// Sets repaired_triangles. Always does its work (an empty mesh is valid).
/// After a stop request (before or during it) the geometric checks poll checks_stop: cut
/// short, the run is Interrupted and says what was not judged (MeshValidation::
/// checks_cut_short); defects found are removed without a repair (which projects), and the
/// mesh left is validated again, as far as the grace allows, into result.validation.
bool validate_and_repair(CoveringRun& run);

/// With a tolerance, holds the triangles made by a repair to it as refine does, and validates
/// (and repairs) what the bisection made. Not after a stop request.
bool refine_repaired(CoveringRun& run);

/// The checks of a completed run: no hole (the boundary lies on ∂S) and no hole of M ∩ S
/// covered over by a triangle (covering_checks.h); each found is the run's failure, with its
/// place. Always does its work (a run that did not complete has nothing checked). The second
/// polls checks_stop and, cut short, makes the run Interrupted.
bool check_coverage(CoveringRun& run);

/// The cubic patches of a method that has them, rebuilt for the final triangles when anything
/// changed them since the build (a distributed problem has none; a note says so).
bool patches(CoveringRun& run);

/// Does nothing: the form of a stage that is skipped after a stop request.
bool skip(CoveringRun& run);

}  // namespace stage

}  // namespace tessera::detail
