// SPDX-License-Identifier: MIT
// The report of a mesh of M: its validation and quality against the problem (measured the same
// way for every backend), and what the run that made it was (summary, view, backend, states,
// fold and level curves). `tessera mesh`, `tessera check` and the bindings make it with
// make_report; report/summary_json.h writes it.
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "tessera/core/counted_problem.h"
#include "tessera/core/implicit_problem.h"
#include "tessera/geometry/mesh_quality.h"
#include "tessera/geometry/mesh_validation.h"
#include "tessera/geometry/triangle_mesh.h"
#include "tessera/methods/covering_result.h"
#include "tessera/methods/improvement/improve_mesh.h"
#include "tessera/problems/problem_setup.h"

namespace tessera {

/// The view a mesh file was written in (`tessera mesh --view`, problems/view.h).
struct ViewReport {
  std::string specification;         ///< View::specification(): "lambda, epsilon, max:u", "all"
  std::vector<std::string> columns;  ///< View::names(), the names in the file; empty for "all"
  /// Who chose it: "--view", "--obj-coordinates", "problem file", "default for large n" or
  /// "default" (every coordinate).
  std::string origin;
};

/// Where the linear algebra ran (`tessera mesh --backend`): "serial", or "petsc" on `ranks`
/// MPI ranks.
struct BackendReport {
  std::string name;
  int ranks = 1;
  /// "whole": every rank holds every vertex's n coordinates; "split": each rank its rows.
  std::string states = "whole";
};

/// The states written as NumPy arrays (`tessera mesh --states`, io/npy.h).
struct StatesReport {
  std::string states_file;     ///< shape (vertices, n), '<f8'
  std::string triangles_file;  ///< shape (triangles, 3), '<i8'
  int vertex_count = 0;
  int triangle_count = 0;
  /// The n columns of the states: the problem's coordinate names and blocks (the JSON lists a
  /// block as one entry with its range, so that the summary stays small at n = 10⁵).
  std::vector<std::string> coordinate_names;
  std::vector<CoordinateBlock> blocks;
};

/// How a SIGINT or SIGTERM stopped `tessera mesh` (docs/stopping.md): present only then.
struct StopReport {
  std::string signal;    ///< "SIGTERM" or "SIGINT": the first one received
  int signal_count = 1;  ///< received until the summary was written
  /// The stage the first one came in: "build" (the start's projection included), "clip",
  /// "refine", "validate", "patches" (the covering's last checks) or "report" (after it).
  std::string stage;
  /// What the stop left out that the run would have done, each with what it means, e.g.
  /// "distances to M: not measured". The covering's own (the tolerance, the clipping) are in
  /// run.message and run.notes, a validation cut short in geometry.cut_short too.
  std::vector<std::string> left_out;
};

/// A curve on M as a report lists it: its points in the report's columns, in order along it.
struct ReportedCurve {
  bool is_closed = false;
  std::vector<std::vector<double>> points;
};

/// The fold curves of M over a parameter plane (`tessera mesh --folds`, methods/folds), with
/// their points in the mesh file's view.
struct FoldReport {
  std::string plane;                     ///< ParameterPlane::specification(): "lambda, epsilon"
  std::vector<std::string> plane_names;  ///< the plane's two column names
  std::string file;                      ///< the polylines file (empty: not written)
  std::vector<std::string> columns;      ///< names of the view coordinates of the points below
  using Curve = ReportedCurve;
  std::vector<Curve> curves;
  struct Cusp {
    std::vector<double> point;  ///< in the view
    double plane[2] = {0.0, 0.0};
    bool is_refined = true;  ///< false: bracketed only (FoldCurves::unrefined_cusp_count)
  };
  std::vector<Cusp> cusps;
  int point_count = 0;
  int crossing_count = 0;
  int unrefined_count = 0;
  int singular_triangle_count = 0;
  int newton_iterations = 0;
  int tangent_evaluations = 0;
  double max_residual = 0.0;
  WorkCounts work;
  double seconds = 0.0;
};

/// The level curves of one functional on M (`tessera mesh --level`, methods/folds/level_curves.h),
/// with their points in the mesh file's view.
struct LevelReport {
  std::string level;                 ///< LevelSet::specification(): "x1 = 0.5"
  std::string functional;            ///< the functional's label: "x1", "mean:u", "r = x^2 + y^2"
  std::string functional_name;       ///< its column name: "x1", "mean_u", "r"
  double value = 0.0;                ///< c
  std::string file;                  ///< the polylines file (empty: not written)
  std::vector<std::string> columns;  ///< names of the view coordinates of the points below
  using Curve = ReportedCurve;
  std::vector<Curve> curves;
  int point_count = 0;
  int crossing_count = 0;
  int unrefined_count = 0;
  int undefined_vertex_count = 0;  ///< vertices where the functional is not finite
  int newton_iterations = 0;
  int max_point_iterations = 0;
  double max_residual = 0.0;        ///< largest ‖F‖ over the refined points
  double max_level_residual = 0.0;  ///< largest |f − c| over the refined points
  WorkCounts work;
  double seconds = 0.0;
};

/// The stability of the steady states at the mesh's vertices (`tessera mesh --stability`,
/// methods/stability/vertex_stability.h).
struct StabilityReport {
  std::vector<std::string> parameters;  ///< the dynamics' two parameters, by name
  std::string method;                   ///< StabilityResult::method
  int eigenvalue_count = 0;             ///< k of the sparse methods; 0: all (dense)
  int vertex_count = 0;
  int stable_count = 0;
  std::vector<int> index_counts;  ///< index_counts[i]: vertices with i unstable eigenvalues
  int failed_count = 0;
  int uncertain_count = 0;
  /// What the counts are sure of, in words (docs/algorithms/stability.md).
  std::string certainty;
  struct Failure {
    int vertex = -1;
    std::string message;
  };
  std::vector<Failure> failures;  ///< the first few
  long factorisations = 0;
  long solves = 0;
  long jacobian_evaluations = 0;
  double seconds = 0.0;
};

/// The Hopf curves on M and their Bogdanov–Takens points (`tessera mesh --hopf`,
/// methods/stability/hopf_curves.h), points in the mesh file's view.
struct HopfReport {
  std::string file;                       ///< the polylines file (empty: not written)
  std::vector<std::string> columns;       ///< view, then the parameters not in it, then omega
  std::vector<std::string> plane_names;   ///< the dynamics' two parameters
  using Curve = ReportedCurve;
  std::vector<Curve> curves;
  /// The neutral saddle curves (real pairs ±κ; the column omega holds κ there), written to
  /// neutral_saddle_file: the rest of the bialternate product's zero set, which meets the Hopf
  /// curves at Bogdanov–Takens points.
  std::vector<Curve> neutral_saddle_curves;
  std::string neutral_saddle_file;
  struct SpecialPoint {
    std::string kind;           ///< "bogdanov_takens"
    std::vector<double> point;  ///< in `columns`
    double plane[2] = {0.0, 0.0};
  };
  std::vector<SpecialPoint> special_points;
  int point_count = 0;
  int crossing_count = 0;
  int unrefined_count = 0;
  int hopf_point_count = 0;
  int neutral_saddle_point_count = 0;
  int mixed_crossing_count = 0;  ///< sparse problems: crossings where a real eigenvalue changes too
  int supercritical_count = 0;  ///< Hopf points with l₁ < 0 (dense problems)
  int subcritical_count = 0;    ///< Hopf points with l₁ > 0
  int newton_iterations = 0;
  double max_residual = 0.0;
  double max_condition_residual = 0.0;
  WorkCounts work;
  double seconds = 0.0;
};

/// What `tessera mesh --improve` (the bindings' improve=True) did to the covering's mesh
/// (report/improvement_report.h, improve_covering).
struct ImprovementReport {
  std::string criterion;     ///< to_string(ImprovementCriterion): "angle"
  int smoothing_passes = 0;  ///< passes asked for
  /// The swaps (both rounds; min angle and angles below 30° before the first round and after
  /// the last, in R^n as measure_shape) and the smoothing between them.
  MeshImprovement result;
};

/// What one report is made of; `run` is absent for `tessera check` of an existing mesh.
struct MeshReport {
  std::string problem;
  int ambient_dimension = 0;
  std::optional<ViewReport> view;        ///< absent for `tessera check`
  std::optional<BackendReport> backend;  ///< absent for `tessera check`
  std::optional<StatesReport> states;    ///< present when the states were written
  std::optional<FoldReport> folds;       ///< present when fold curves were asked for
  std::optional<LevelReport> level;      ///< present when level curves were asked for
  std::optional<StabilityReport> stability;  ///< present when stability was asked for
  std::optional<HopfReport> hopf;            ///< present when Hopf curves were asked for
  std::optional<CoveringSummary> run;
  std::optional<ImprovementReport> improvement;  ///< present after `mesh --improve`
  std::optional<StopReport> stop;                ///< present when a signal stopped the run
  MeshValidation validation;
  MeshQuality quality;
  std::optional<int> expected_euler_characteristic;
  std::optional<double> exact_area;
};

/// How make_report measures.
struct ReportOptions {
  /// Distances measured at this many points of each kind (0: all; −1: all below n = 500, else
  /// 300 within a time budget: see run_seconds).
  int samples = -1;
  /// false leaves the distances to M unmeasured (their counts 0 of their populations): the
  /// summary `tessera mesh` writes before the measurement, which at large n takes minutes, so
  /// that a run killed during it still leaves one.
  bool measure_distances = true;
  /// How long the covering took. With the default `samples` from n = 500 on, the distances get
  /// a tenth of that, at least 10 s, and then stop (at least 30 samples of each kind; the report
  /// says how many it measured): at n = 10⁵ a sample costs a factorisation.
  double run_seconds = 0.0;
  /// Polled before every distance sample (Ctrl-C ends the measurement).
  std::function<bool()> stop_requested;
  /// A distributed run's decision to stop the measurement, taken together by every rank
  /// (QualityOptions::decide_together); empty: this process decides.
  std::function<bool(bool)> decide_together;
  /// For the validation of a mesh whose validation is not `known`: e.g. a stop request that
  /// cuts its geometric checks short (ValidationOptions::stop_requested).
  ValidationOptions validation;
};

/// Validation (combinatorial and geometric: orientation along M, overlaps on M, vertices in the
/// setup's domain) and quality of `mesh` against setup's problem, in the problem's metric, for
/// printing or JSON. One code path for every backend: a split mesh (each rank its rows of the
/// points, on a distributed problem) gets the serial report of the same mesh.
/// `problem_argument`: the problem as the user spelled it, e.g. "torus:R=2".
/// `known`: a validation of exactly this mesh already made (a covering's final check), reused.
/// \throw InvalidArgument if the mesh and the problem live in different dimensions.
MeshReport make_report(const TriangleMesh& mesh, const ProblemSetup& setup,
                       const std::string& problem_argument, const MeshValidation* known = nullptr,
                       const ReportOptions& options = {});

}  // namespace tessera
