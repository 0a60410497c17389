// SPDX-License-Identifier: MIT
// The one seam of the covering methods: the options every method shares and the run skeleton
// every method passes through (input checks, evaluation counts, start projection, the method's
// build, clipping to the domain, refinement to the tolerance, geometric validation with local
// repair, the summary). A method is a build step plugged into run_covering().
#pragma once

#include <Eigen/Core>
#include <functional>
#include <string>

#include "tessera/core/corrector.h"
#include "tessera/methods/covering_result.h"
#include "tessera/methods/stop_grace.h"

namespace tessera {

class CountedProblem;
class Domain;
class ImplicitProblem;
struct StartPoint;

/// What every method's options hold (each method's Options derive from this block).
struct CoveringOptions {
  /// ε ≥ 0, in ambient units. With ε > 0 every triangle of the output is checked after it is
  /// built and clipped: its centroid, edge midpoints and (when inside) circumcentre are
  /// projected onto M, and triangles with a sample farther than ε are bisected on M until none
  /// is (refine_to_tolerance). The summary reports the largest sampled distance. The adaptive
  /// methods (atlas, bezier) also size their steps by ε. 0: no bound is imposed.
  double tolerance = 0.0;
  /// The method's length scale in ambient units: the front's edge length h, the atlas's
  /// largest chart radius, the bezier method's initial step.
  double step = 0.1;
  int max_vertices = 2'000'000;  ///< hard stop; CoveringTermination::VertexLimit
  /// The start must project onto M within this distance (ambient units); 0: ten steps.
  double max_start_distance = 0.0;
  /// The corrector of the start projection, clipping and refinement (and of the method's own
  /// projections where it uses the shared corrector).
  CorrectorOptions corrector;
  ProgressCallback progress;   ///< when set: see CoveringProgress and ProgressSchedule
  StopRequest stop_requested;  ///< polled about once per vertex when set (see StopRequest)
  /// After a stop request, the final checks (the geometric validation, the check for holes
  /// covered over: a factorisation per projection, a second each at n = 10⁵) go on this long
  /// and are then cut short, saying what they did not judge; the mesh is written within a
  /// batch system's grace period either way (docs/stopping.md). 0: cut short at once.
  double check_seconds_after_stop = kCheckSecondsAfterStop;

  /// \throw InvalidArgument naming the first shared option that is out of range; `owner` names
  ///        the method's options struct in the message, e.g. "AtlasOptions".
  void validate_common(const char* owner) const;
};

/// What the skeleton hands to a method's build step.
struct CoveringContext {
  const CountedProblem& problem;  ///< counts every evaluation of F and DF
  const Domain& domain;
  const StartPoint& start;  ///< the start projected onto M inside the domain, factorised
  /// 0 on the first build; 1 when the skeleton builds again because clipping refused the first
  /// mesh and the method asked for a retry (see retry_if_clipping_fails).
  int attempt = 0;

  // Set by the build step for the skeleton:
  /// Edge length near ∂S, in ambient units: vertices within boundary_snap_fraction of it from a
  /// face are snapped onto M ∩ face (so that cutting leaves no needles) and boundary edges
  /// shorter than 0.2 of it are collapsed. 0: the method puts its boundary on ∂S itself and the
  /// skeleton does not clip.
  double boundary_edge_length = 0.0;
  double boundary_snap_fraction = 0.35;
  /// Delaunay-type edge swaps in the tangent planes after clipping (angles at ∂S).
  bool swap_after_clipping = false;
  /// Build once more (attempt 1) if clipping refuses the mesh of attempt 0.
  bool retry_if_clipping_fails = false;
};

/// A method's build: covers M from context.start and fills result.mesh, result.summary's
/// method-specific fields and termination (and result.patches for a method with a cubic
/// surface). It must leave a combinatorially valid mesh whatever the termination.
using CoveringBuild = std::function<void(CoveringContext& context, CoveringResult& result)>;

/// The run skeleton shared by all methods, a pipeline of stages (covering_stages.h has each
/// one's contract, docs/architecture.md the pipeline):
///  1. checks the shared options and the domain's dimension;
///  2. wraps the problem to count evaluations of F and DF (per step: work_by_phase);
///  3. projects `start` onto M inside the domain (failure: termination StartFailed, empty mesh);
///  4. runs `build`;
///  5. clips the mesh to the domain (when bounded and the build asked for it), closes notches
///     in the clipped boundary and swaps edges at it (when the build asked for that);
///  6. refines it until sampled points lie within options.tolerance of M (when > 0);
///  7. validates it geometrically against M and the domain; flipped or overlapping triangles
///     and vertices outside the domain are removed (the run then fails with a message giving
///     their coordinates and the valid rest is returned), never returned as a success;
///  8. checks that a completed run left no hole, and rebuilds the cubic patches of a method
///     that has them for the final triangles;
///  9. finishes the summary (counts, evaluations, wall time, measured distance).
/// After a stop request (options.stop_requested) the stages after the one it ended skip their
/// work or run in a form that does not project (clipping) or check (the tolerance), and the
/// partial mesh is still validated.
/// \return a valid mesh whatever the termination; summary.message says where and why a run
///         that is not Completed stopped.
/// \throw InvalidArgument for bad options or sizes.
///
/// A distributed problem (SPMD, docs/cluster.md) runs on this rank's rows: `start` holds them
/// (problem.space()->local_rows()), `domain` is given in R^n or already cut to them
/// (Domain::distributed), the mesh returned holds them (TriangleMesh::set_space), and every
/// rank calls this alike. Such a problem presents its metric's coordinates itself
/// (petsc::ScaledPetscProblem): one with a metric left is refused, not scaled a second time.
/// Cubic patches are not built for it (a note says so).
CoveringResult run_covering(const std::string& method, const ImplicitProblem& problem,
                            const Eigen::VectorXd& start, const Domain& domain,
                            const CoveringOptions& options, const CoveringBuild& build);

}  // namespace tessera
