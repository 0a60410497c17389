// SPDX-License-Identifier: MIT
// `tessera mesh --folds`: the fold curves of the finished mesh, written in the mesh's view.
#pragma once

#include <string>
#include <vector>

#include "tessera/io/polylines.h"
#include "tessera/methods/folds/parameter_plane.h"
#include "tessera/problems/problem_setup.h"
#include "tessera/report/mesh_report.h"

namespace tessera {

/// The fold file beside the mesh when --folds-output is not given: "out.ply" → "out.folds.ply";
/// meshes in formats without lines (.obj) get "out.folds.csv".
std::string default_fold_file(const std::string& mesh_path);

/// The parameter plane of `--folds SPEC`, checked before any computation.
/// \throw InvalidArgument naming the option and the item.
ParameterPlane parse_folds_option(const std::string& specification, const ImplicitProblem& problem);

struct FoldOutput {
  FoldReport report;
  std::vector<Polyline> curves_in_view;  ///< the curves in the view, for a picture
};

/// Finds the fold curves of `mesh` over `plane`, writes them to `path` in `view` (unless `path`
/// is empty) and reports them (`tessera mesh --folds` and the bindings' folds=).
FoldOutput compute_folds(const ProblemSetup& setup, const TriangleMesh& mesh,
                         const ParameterPlane& plane, const View& view, const std::string& path,
                         const std::vector<std::string>& comments);

}  // namespace tessera
