// SPDX-License-Identifier: MIT
#include "tessera/picture/run_diagram.h"

#include <algorithm>

#include "tessera/picture/bifurcation_diagram.h"

namespace tessera {

std::string write_run_diagram(const std::string& path, const std::string& problem_name,
                          const MeshReport& report, const std::vector<Polyline>& fold_curves,
                          const HopfOutput& hopf, const View& view) {
  const std::string& p1 = hopf.report.plane_names[0];
  const std::string& p2 = hopf.report.plane_names[1];
  BifurcationDiagramScene scene;
  scene.parameter_names = {p1, p2};
  std::string note;
  if (report.folds) {
    const auto& columns = report.folds->columns;
    const bool has_plane = std::find(columns.begin(), columns.end(), p1) != columns.end() &&
                           std::find(columns.begin(), columns.end(), p2) != columns.end();
    if (has_plane) {
      PolylineFileOptions fold_options;
      fold_options.names = columns;
      fold_options.kind = "fold";
      add_to_diagram(scene, fold_curves, fold_options, p1, p2);
    } else {
      note = "the fold curves are not in the diagram: the view (" + view.specification() +
             ") does not hold " + p1 + " and " + p2;
    }
  }
  add_to_diagram(scene, hopf.file.polylines, hopf.file.options, p1, p2);
  add_to_diagram(scene, hopf.neutral_saddle_file.polylines, hopf.neutral_saddle_file.options, p1,
                 p2);
  add_to_diagram(scene, hopf.zero_hopf_points.polylines, hopf.zero_hopf_points.options, p1, p2);
  BifurcationDiagramOptions options;
  options.title = problem_name + ": folds and Hopf curves over (" + p1 + ", " + p2 + ")";
  write_bifurcation_diagram(path, scene, options);
  return note;
}

}  // namespace tessera
