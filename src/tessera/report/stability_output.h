// SPDX-License-Identifier: MIT
// `tessera mesh --stability / --hopf`: the stability at the finished mesh's vertices as point
// data and a report, the Hopf curves written in the mesh's view (and the parameters, and ω).
#pragma once

#include <string>
#include <vector>

#include "tessera/io/polylines.h"
#include "tessera/io/vertex_data.h"
#include "tessera/methods/stability/hopf_curves.h"
#include "tessera/methods/stability/vertex_stability.h"
#include "tessera/problems/problem_setup.h"
#include "tessera/problems/view.h"
#include "tessera/report/mesh_report.h"

namespace tessera {

struct StabilityOutput {
  StabilityResult result;
  StabilityReport report;
  /// unstable_count (−1 where the eigenvalues failed), leading_real_part (NaN there) and
  /// stability_certain (1/0): the point data of the mesh file (docs/mesh-files.md).
  std::vector<VertexScalars> vertex_data;
};

/// The stability of every vertex of `mesh` and its report.
/// \throw InvalidArgument if the problem declares no dynamics (the message says how).
StabilityOutput compute_stability_output(const ProblemSetup& setup, const TriangleMesh& mesh,
                                         const StabilityOptions& options);

/// The report and point data of a stability computed elsewhere (the PETSc backend's,
/// petsc/petsc_stability.h), one VertexStability per vertex of the mesh, as
/// compute_stability_output makes them. `problem` names the parameters.
/// 	hrow InvalidArgument if the problem declares no dynamics.
StabilityOutput make_stability_output(const ImplicitProblem& problem, StabilityResult result,
                                      const StabilityOptions& options);

/// The Hopf file beside the mesh when --hopf-output is not given: "out.ply" → "out.hopf.ply";
/// meshes in formats without lines (.obj) get "out.hopf.csv".
std::string default_hopf_file(const std::string& mesh_path);

struct HopfOutput {
  HopfReport report;
  std::vector<Polyline> curves_in_view;  ///< the view's columns only, for a picture
  /// The curves as written: the view's columns, the parameters not among them, then omega;
  /// kind "hopf", marker "bogdanov_takens" (for the bifurcation diagram).
  PolylineFile file;
  /// The neutral saddle curves likewise (their last column kappa, kind "neutral_saddle").
  std::vector<Polyline> neutral_saddle_curves_in_view;
  PolylineFile neutral_saddle_file;
  /// Fold–Hopf points as one-point polylines, marked (marker "zero_hopf"): drawn as special
  /// points; in the view's columns (`*_in_view`) and in the written ones.
  std::vector<Polyline> zero_hopf_points_in_view;
  PolylineFile zero_hopf_points;
};

/// Where the neutral saddles go beside the Hopf file: "out.hopf.ply" → "out.neutral_saddles.ply".
std::string neutral_saddle_file_beside(const std::string& hopf_path);

/// Finds the Hopf curves of `mesh` from its stability, writes them to `path` (unless empty), the
/// neutral saddle curves (when there are any) beside it, and reports them.
HopfOutput compute_hopf_output(const ProblemSetup& setup, const TriangleMesh& mesh,
                               const StabilityResult& stability, const View& view,
                               const std::string& path, const std::vector<std::string>& comments);

}  // namespace tessera
