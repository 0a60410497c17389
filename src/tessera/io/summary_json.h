// SPDX-License-Identifier: MIT
// The JSON run summary: counts, topology, distances to M, angles, area, time, evaluations.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "tessera/core/counted_problem.h"
#include "tessera/core/implicit_problem.h"

#include "tessera/geometry/mesh_quality.h"
#include "tessera/geometry/mesh_validation.h"
#include "tessera/methods/covering_result.h"

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

/// The fold curves of M over a parameter plane (`tessera mesh --folds`, methods/folds), with
/// their points in the mesh file's view.
struct FoldReport {
  std::string plane;                 ///< ParameterPlane::specification(): "lambda, epsilon"
  std::vector<std::string> plane_names;  ///< the plane's two column names
  std::string file;                  ///< the polylines file (empty: not written)
  std::vector<std::string> columns;  ///< names of the view coordinates of the points below
  struct Curve {
    bool is_closed = false;
    std::vector<std::vector<double>> points;  ///< in the view, in order along the curve
  };
  std::vector<Curve> curves;
  struct Cusp {
    std::vector<double> point;  ///< in the view
    double plane[2] = {0.0, 0.0};
    bool is_refined = true;     ///< false: bracketed only (FoldCurves::unrefined_cusp_count)
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

/// What one report is made of; `run` is absent for `tessera check` of an existing mesh.
struct MeshReport {
  std::string problem;
  int ambient_dimension = 0;
  std::optional<ViewReport> view;      ///< absent for `tessera check`
  std::optional<BackendReport> backend;  ///< absent for `tessera check`
  std::optional<StatesReport> states;  ///< present when the states were written
  std::optional<FoldReport> folds;     ///< present when fold curves were asked for
  std::optional<CoveringSummary> run;
  MeshValidation validation;
  MeshQuality quality;
  std::optional<int> expected_euler_characteristic;
  std::optional<double> exact_area;
};

/// The report as a JSON document (documented in docs/summary-json.md), pretty-printed.
std::string to_json(const MeshReport& report);

/// Writes to_json(report) to `path`. \throw InvalidArgument if the file cannot be written.
void write_summary_json(const std::string& path, const MeshReport& report);

/// A short human-readable report (a dozen lines) for the terminal.
std::string to_text(const MeshReport& report);

}  // namespace tessera
