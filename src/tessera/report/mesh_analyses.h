// SPDX-License-Identifier: MIT
// What `tessera mesh` and Python's mesh() compute on a finished mesh besides its report: fold
// curves, stability, Hopf curves and level curves, each written to its file when asked, all in
// the mesh's view. One place, so that the command line and the bindings cannot drift apart.
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "tessera/io/polylines.h"
#include "tessera/methods/folds/level_curves.h"
#include "tessera/methods/folds/parameter_plane.h"
#include "tessera/report/fold_output.h"
#include "tessera/report/level_output.h"
#include "tessera/report/stability_output.h"

namespace tessera {

struct AnalysisRequest {
  std::optional<ParameterPlane> fold_plane;   ///< fold curves over this plane
  std::optional<StabilityOptions> stability;  ///< stability at every vertex
  bool hopf = false;                          ///< Hopf curves (needs `stability`)
  std::optional<LevelSet> level;              ///< a level curve
  /// The curves' files; empty: not written (the curves are still in the report).
  std::string fold_file;
  std::string hopf_file;
  std::string level_file;
  std::vector<std::string> comments;  ///< written into every curve file
  /// Computes the stability in place of compute_stability_output (the PETSc backend's, on split
  /// states); empty: compute_stability_output.
  std::function<StabilityOutput(const ProblemSetup&, const TriangleMesh&, const StabilityOptions&)>
      compute_stability;
};

struct MeshAnalyses {
  std::vector<Polyline> fold_curves;  ///< in the view
  std::optional<StabilityOutput> stability;
  std::optional<HopfOutput> hopf;
  std::optional<LevelOutput> level;
  std::vector<std::string> written;   ///< the files written, in order
  /// What the user should hear about (points left unrefined, failed eigenvalues), one line each.
  std::vector<std::string> warnings;

  /// Every curve with its kind and marks, in the view's columns `names`: for pictures.
  std::vector<PolylineFile> curves_in_view(const std::vector<std::string>& names) const;
};

/// Computes what `request` asks for on `mesh` (in the problem's coordinates), writes the curve
/// files named in it and fills report.folds, .stability, .hopf and .level.
/// \throw InvalidArgument if stability or Hopf curves are asked of a problem without dynamics,
///        or Hopf curves without stability.
MeshAnalyses analyse_mesh(const ProblemSetup& setup, const TriangleMesh& mesh, const View& view,
                          const AnalysisRequest& request, MeshReport& report);

}  // namespace tessera
