// SPDX-License-Identifier: MIT
#include "compare_command.h"

#include <cstdio>
#include <iostream>

#include "cli_support.h"
#include "tessera/core/error.h"
#include "tessera/geometry/mesh_quality.h"
#include "tessera/geometry/mesh_validation.h"
#include "tessera/problems/catalogue.h"

namespace tessera::app {

CLI::App* add_compare_command(CLI::App& app, CompareCommand& command) {
  auto* compare = app.add_subcommand(
      "compare", "run every covering method on one problem and print a table side by side");
  compare->add_option("problem", command.problem, "catalogue name or problem file")->required();
  compare
      ->add_option("--step,-s", command.settings.step,
                   "front: edge length; atlas: largest chart radius (defaults as for mesh)")
      ->check(finite_positive());
  compare
      ->add_option("--tolerance,-t", command.settings.tolerance,
                   "distance bound for the adaptive methods (default: step/50)")
      ->check(finite_positive());
  compare
      ->add_option("--placement", command.settings.atlas_placement,
                   "atlas: 'disk' (Henderson, default) or 'hexagonal' (about 30% fewer "
                   "vertices, then smoothed; slower)")
      ->check(CLI::IsMember({"disk", "hexagonal"}));
  compare->add_option("--start", command.start, "start point, comma separated");
  compare->add_option("--box", command.box, "clip to a box: lower,upper for each coordinate");
  compare
      ->add_option("--max-vertices", command.settings.max_vertices,
                   "stop each method after this many vertices")
      ->check(CLI::Range(7, 100'000'000));
  return compare;
}

int run_compare(const CompareCommand& command) {
  std::printf("%-8s %9s %10s %9s %12s %12s %9s %6s %-7s %s\n", "method", "vertices", "triangles",
              "time [s]", "max dist M", "tolerance", "min angle", "chi", "valid", "run");
  bool all_good = true;
  for (const CoveringMethod& method : covering_methods()) {
    ProblemSetup setup = resolve_problem(command.problem);
    apply_start_and_box(setup, command.start, command.box);
    const CoveringResult result = cover(setup, method, command.settings);
    const MeshValidation validation = validate(result.mesh, *setup.problem, setup.domain);
    const MeshQuality quality = measure_quality(result.mesh, *setup.problem);
    // The distance of the mesh to M: the larger of the centroid and edge-midpoint distances,
    // measured by projecting those points (not produced by any method) onto M.
    const double distance = std::max(quality.centroid_distance.max, quality.midpoint_distance.max);
    const std::string tolerance =
        result.summary.tolerance > 0 ? std::to_string(result.summary.tolerance).substr(0, 8) : "-";
    std::printf("%-8s %9d %10d %9.3f %12.3g %12s %9.1f %6d %-7s %s\n", method.name.c_str(),
                validation.referenced_vertex_count, validation.triangle_count,
                result.summary.wall_seconds, distance, tolerance.c_str(), quality.min_angle_degrees,
                validation.euler_characteristic, validation.is_valid() ? "yes" : "NO",
                to_string(result.summary.termination));
    all_good = all_good && validation.is_valid() && result.summary.is_complete();
  }
  ProblemSetup setup = resolve_problem(command.problem);
  apply_start_and_box(setup, command.start, command.box);
  if (setup.expected_euler_characteristic) {
    std::printf("expected Euler characteristic: %d\n", *setup.expected_euler_characteristic);
  }
  return all_good ? 0 : kComputationFailed;
}

}  // namespace tessera::app
