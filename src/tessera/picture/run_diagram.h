// SPDX-License-Identifier: MIT
// The two-parameter bifurcation diagram of one run (`tessera mesh --diagram`, Python's
// diagram=): its fold curves and its Hopf and neutral saddle curves over the dynamics' parameters.
#pragma once

#include <string>
#include <vector>

#include "tessera/io/polylines.h"
#include "tessera/problems/view.h"
#include "tessera/report/mesh_report.h"
#include "tessera/report/stability_output.h"

namespace tessera {

/// Draws the diagram to `path` (.png or .svg). The fold curves (`report.folds`, in the view's
/// columns `fold_curves`) are drawn when the view holds both parameters.
/// \return a note for the user when something was left out (empty otherwise).
/// \throw InvalidArgument as write_bifurcation_diagram.
std::string write_run_diagram(const std::string& path, const std::string& problem_name,
                              const MeshReport& report, const std::vector<Polyline>& fold_curves,
                              const HopfOutput& hopf, const View& view);

}  // namespace tessera
