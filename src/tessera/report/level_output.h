// SPDX-License-Identifier: MIT
// `tessera mesh --level FUNCTIONAL=VALUE`: the level curves of one functional on the finished
// mesh, written in the mesh's view.
#pragma once

#include <string>
#include <vector>

#include "tessera/io/polylines.h"
#include "tessera/methods/folds/level_curves.h"
#include "tessera/problems/problem_setup.h"
#include "tessera/report/mesh_report.h"

namespace tessera {

/// The level-curve file beside the mesh when no other is given: "out.ply" → "out.level.ply";
/// meshes in formats without lines (.obj) get "out.level.csv".
std::string default_level_file(const std::string& mesh_path);

/// The level set of `--level SPEC` ("x1=0.5", "mean:u=1.5", "r = sqrt(x^2 + y^2) = 1"),
/// checked before any computation.
/// \throw InvalidArgument "--level SPEC: <reason>", the reason naming the item (for an unknown
///        functional the view parser's, listing the coordinates and blocks).
LevelSet parse_level_option(const std::string& specification, const ImplicitProblem& problem);

struct LevelOutput {
  LevelReport report;
  std::vector<Polyline> curves_in_view;  ///< the curves in the view, for a picture
};

/// Finds the level curves of `level` on `mesh`, writes them to `path` in `view` (unless `path`
/// is empty; the 0/1 column `unrefined` marks points kept at the mesh's estimate) and reports
/// them (`tessera mesh --level`). Polyline formats: is_polyline_file(path).
/// \throw InvalidArgument as find_level_curves and write_polylines.
LevelOutput compute_level_curves(const ProblemSetup& setup, const TriangleMesh& mesh,
                                 const LevelSet& level, const View& view, const std::string& path,
                                 const std::vector<std::string>& comments);

}  // namespace tessera
