// SPDX-License-Identifier: MIT
// What every covering method returns: the mesh and a summary (Options in, Result out).
#pragma once

#include <Eigen/Core>
#include <chrono>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "tessera/core/counted_problem.h"
#include "tessera/geometry/bezier_patch.h"
#include "tessera/geometry/mesh_validation.h"
#include "tessera/geometry/triangle_mesh.h"

namespace tessera {

enum class CoveringTermination {
  Completed,            ///< the method covered M ∩ S as asked
  VertexLimit,          ///< stopped at options.max_vertices; the mesh is valid but partial
  FrontCollision,       ///< the front met itself in a way the method cannot close
  ProjectionFailed,     ///< the corrector failed even at the smallest step
  StartFailed,          ///< the start point could not be projected onto M inside the domain
  TriangulationFailed,  ///< the charts were computed but no valid mesh could be made of them
  Interrupted,          ///< stopped because options.stop_requested said so; valid but partial
};

const char* to_string(CoveringTermination termination);

/// The work of one step of the covering pipeline (start, build, clip, refine, validate, patches).
struct PhaseWork {
  std::string phase;
  WorkCounts counts;
  double wall_seconds = 0.0;
};

/// The note of a covering of one start's component (the atlas's; a run of several components
/// replaces it with its own).
inline constexpr std::string_view kStartComponentNote =
    "covered the component of M that contains the start point; other components, if any, need "
    "their own start points (or --components all)";

/// One component of a run that covers several (`--components all`, several `--start`s;
/// methods/components/cover_components.h): where it came from and what its mesh is.
struct ComponentRecord {
  /// What started it: "start K" (the K-th start given, from 1) or "seed K" (the K-th seed of
  /// the search over the region, from 1).
  std::string origin;
  Eigen::VectorXd start;  ///< the point on M its covering started from (problem coordinates)
  int first_vertex = 0;   ///< its vertices are first_vertex … first_vertex + vertex_count − 1
  int vertex_count = 0;
  int first_triangle = 0;  ///< its triangles likewise
  int triangle_count = 0;
  int euler_characteristic = 0;
  int boundary_loop_count = 0;
  int genus = -1;  ///< of a closed orientable component; −1 otherwise (MeshValidation::genus)
  CoveringTermination termination = CoveringTermination::Completed;
  std::string message;  ///< its run's message when not Completed
};

/// What became of one start a user gave (`--start` given more than once).
struct StartRecord {
  Eigen::VectorXd guess;        ///< the start as given
  Eigen::VectorXd on_manifold;  ///< its projection onto M; empty if the projection failed
  /// The component (index into CoveringSummary::components) it started or already lay on;
  /// −1 if its projection failed.
  int component = -1;
  bool started_component = false;  ///< false: it landed on a component covered before it
  std::string message;             ///< why the projection failed (component −1)
};

/// The search for components over the region (`--components all`).
struct ComponentSearchRecord {
  int seed_count = 0;         ///< seeds spread over the region
  double seed_spacing = 0.0;  ///< (volume / seeds)^(1/d) of the seeded box, metric units
  std::vector<std::string> seeded_coordinates;  ///< the d coordinates the seeds vary
  int seeds_not_projected = 0;  ///< the corrector failed, or M was reached outside the region
  int seeds_on_covered = 0;     ///< landed on a component covered before
  int seeds_started = 0;        ///< started a component
  int seeds_not_tried = 0;      ///< left when the search stopped (a failure, the vertex limit)
};

/// Counters and timings of one covering run. Wall time is informational (benchmarks measure).
struct CoveringSummary {
  std::string method;
  CoveringTermination termination = CoveringTermination::Completed;
  std::string message;  ///< empty when Completed; otherwise where and why it stopped
  int vertex_count = 0;
  int triangle_count = 0;
  long function_evaluations = 0;
  long jacobian_evaluations = 0;
  long factorisations = 0;  ///< numerical factorisations of DF (or of [DF; border])
  /// Right-hand sides solved with factorisations, own or borrowed (WorkCounts::solves). A run
  /// resumed from a checkpoint counts them from the resumption (the checkpoint keeps F, DF and
  /// factorisation counts only).
  long solves = 0;
  /// Wall time spent in them (with the DF evaluations and analyses they needed): the run's
  /// own measure of one factorisation, factorisation_seconds / factorisations.
  double factorisation_seconds = 0.0;
  double wall_seconds = 0.0;
  /// The threads the data-parallel steps ran on (threads_for: 1 for a problem that is not
  /// thread-safe or has a sparse Jacobian). How it ran, like the times: the mesh and the other
  /// counts are the same whatever it is.
  int threads = 1;
  /// The same work split by pipeline step, in the order the steps ran.
  std::vector<PhaseWork> work_by_phase;
  double step = 0.0;            ///< the step (edge length) actually used
  int merges = 0;               ///< open edges identified (front method)
  int step_reductions = 0;      ///< projections that needed step halving
  int front_connections = 0;    ///< front glued to a non-adjacent part of itself (front method)
  int clipped_half_spaces = 0;  ///< domain faces the mesh was clipped to
  double tolerance = 0.0;       ///< the distance bound asked for (0: none)
  // Atlas method (0 for the others).
  int charts = 0;  ///< charts computed (before clipping to the domain)
  /// Charts whose radius is below the tolerance's sqrt(2·tolerance/curvature) (at most the
  /// step), by what held it there (methods/atlas/atlas_builder.h, RadiusCap): such charts cost
  /// vertices that the tolerance alone would not ask for. Always in the JSON summary; a note
  /// says so only where they are a noticeable part of the atlas.
  struct RadiusCaps {
    int curvature = 0;      ///< M turns within the disk (radius ≤ max_turning_angle/curvature)
    int not_a_graph = 0;    ///< M is no graph over the larger disk, or the corrector misses it
    int grading = 0;        ///< next to smaller charts (radius_growth)
    int reach = 0;          ///< another part of M within the disk
    int band = 0;           ///< half the width of a band of M ∩ S narrower than two radii
    int reduced_later = 0;  ///< radii reduced after the chart was made (not in total())
    int total() const { return curvature + not_a_graph + grading + reach + band; }
  };
  RadiusCaps radius_caps;
  /// Where the atlas centred its charts: "disk" (Henderson's) or "hexagonal" (AtlasPlacement).
  std::string placement;
  double min_chart_radius = 0.0;
  double max_chart_radius = 0.0;
  int singular_crossings = 0;  ///< continuation steps that crossed a singular curve of M
  int sheet_rejections = 0;    ///< overlapping charts kept apart because they lie on other sheets
  int filled_holes = 0;        ///< places where the charts' polygons disagreed, closed afterwards
  /// Charts that solved with their parent's factorisation instead of factoring their own
  /// (AtlasOptions::share_factorisations).
  int borrowed_factorisations = 0;
  /// The largest memory the atlas's open boundary held at once: the factorisations kept for
  /// queued charts and the tangent bases of charts not yet retired (bytes; the vertices' own
  /// coordinates are not counted). What issue 9's memory bound calls "what the active boundary
  /// needs".
  double boundary_peak_bytes = 0.0;
  /// The process's resident memory, sampled between the stages of the run, every 64 charts
  /// of the atlas's build and (n ≥ 1000) every 64 vertices of the front's (bytes; 0 where the
  /// system does not tell): its largest sample, and the largest sample less what the open
  /// boundary held at that moment, the atlas's kept factorisations and tangent bases or the
  /// front's tangent bases (issue 9 bounds the latter by 1.5 × 8n bytes per vertex). Per rank
  /// on a distributed run.
  double resident_peak_bytes = 0.0;
  double resident_beyond_boundary_peak_bytes = 0.0;
  int refined_edges = 0;  ///< edges bisected on M to keep the distance bound
  /// Largest distance to M of the points sampled by the tolerance check (centroids, edge
  /// midpoints, circumcentres) after refinement; −1 if no check was made (tolerance 0).
  double max_sampled_distance = -1.0;
  /// Triangles removed by the final geometric validation (flipped, overlapping, outside S, and
  /// the fans around them when the place was repaired).
  int removed_triangles = 0;
  int repaired_holes = 0;  ///< places where removed triangles were replaced by a new triangulation
  std::vector<std::string> notes;  ///< remarks for the user, e.g. where a crossing was met
  /// A build continued from a checkpoint (AtlasCheckpointing or FrontCheckpointing::
  /// resume_from): what the run had done when the checkpoint was written. The counts above
  /// include its work.
  struct ResumedFrom {
    int charts = 0;              ///< charts of the atlas in the checkpoint (0 for the front)
    int vertices = 0;            ///< the front's vertices in the checkpoint (0 for the atlas)
    double build_seconds = 0.0;  ///< wall time of the build until then, over all earlier runs
    WorkCounts counts;           ///< F, DF and factorisations until then (in the counts above)
  };
  std::optional<ResumedFrom> resumed_from;
  /// A run of several components (cover_components): each one, in the order of their vertices,
  /// and what became of each start given. Empty for a run of one start's component.
  std::vector<ComponentRecord> components;
  std::vector<StartRecord> starts;
  std::optional<ComponentSearchRecord> component_search;  ///< with `--components all`
  bool is_complete() const { return termination == CoveringTermination::Completed; }
  /// A failure found by a step of the run: the first ends the run's status (termination and
  /// message), later ones are kept as notes.
  void record_failure(CoveringTermination why, const std::string& what);
  /// Samples the process's resident memory into the two peaks above, the second less
  /// `boundary_bytes`, what the method's open boundary holds at this moment.
  void note_resident_memory(double boundary_bytes);
};

struct CoveringResult {
  TriangleMesh mesh;
  CoveringSummary summary;
  /// A piecewise cubic surface through the mesh, one patch per triangle in the triangle's
  /// vertex order, when the method builds one (method `bezier`); empty otherwise.
  std::vector<CubicBezierPatch> patches;
  /// l_ij/‖y_j − y_i‖ of the patches' edge curves (Hohmann eq. 3.4), so that the patches of
  /// triangles made after the build (refinement, repair) are built as the method built its own.
  double patch_edge_length_factor = 1.0;
  /// The build changed triangles after making `patches` (bezier's shape repair): the skeleton
  /// builds them again for the final triangles.
  bool patches_need_rebuild = false;
  /// The final geometric check of `mesh` when it passed (validate() in the problem's metric),
  /// so that a caller's report need not repeat it; empty if the check removed triangles.
  std::optional<MeshValidation> validation;
};

/// Progress of a long run, reported to an optional callback (the CLI draws a status line, the
/// bindings hand it to Python). Every method reports its build on a ProgressSchedule; the run
/// skeleton reports the start of each later stage with the mesh's counts at that moment.
struct CoveringProgress {
  int vertex_count = 0;    ///< the atlas: charts
  int triangle_count = 0;  ///< 0 during the atlas's build (it triangulates at the end)
  int front_size = 0;      ///< the open boundary of the build (front, open charts); 0 after it
  /// "build", then "clip", "refine", "validate", "patches" (covering.cpp's steps); a literal.
  std::string_view stage = "build";
};
using ProgressCallback = std::function<void(const CoveringProgress&)>;

/// When a build reports its progress: every 1000 vertices (charts) or once a second since the
/// last report, whichever comes first, so that a build at large n, where 1000 vertices take
/// minutes, still says what it does. One clock read per call (tens of nanoseconds, against a
/// vertex's projection).
class ProgressSchedule {
 public:
  /// True if a report is due at `count` vertices; the next one is then scheduled.
  bool is_due(int count) {
    const auto now = std::chrono::steady_clock::now();
    if (count < next_count_ && now < next_time_) {
      return false;
    }
    next_count_ = count + kCountInterval;
    next_time_ = now + kInterval;
    return true;
  }

 private:
  static constexpr int kCountInterval = 1000;
  static constexpr std::chrono::seconds kInterval{1};
  int next_count_ = kCountInterval;
  std::chrono::steady_clock::time_point next_time_ = std::chrono::steady_clock::now() + kInterval;
};
/// Polled about once per vertex (or chart) by every method; returning true stops the run as
/// CoveringTermination::Interrupted with the valid partial mesh (the bindings' Ctrl-C). It must
/// be cheap: the bindings' version reads an atomic flag that a signal handler sets.
using StopRequest = std::function<bool()>;

}  // namespace tessera
