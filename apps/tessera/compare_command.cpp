// SPDX-License-Identifier: MIT
#include "compare_command.h"

#include <algorithm>
#include <cstdio>
#include <iostream>

#include "cli_support.h"
#include "tessera/problems/catalogue.h"
#include "tessera/problems/start_and_box.h"
#include "tessera/report/method_comparison.h"

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
  compare->add_option("--box", command.box, "clip to a box: lower,upper for each coordinate, or name=lower:upper,…");
  compare
      ->add_option("--max-vertices", command.settings.max_vertices,
                   "stop each method after this many vertices")
      ->check(CLI::Range(7, 100'000'000));
  return compare;
}

int run_compare(const CompareCommand& command) {
  std::printf("%-8s %9s %10s %9s %12s %12s %9s %6s %-7s %s\n", "method", "vertices", "triangles",
              "time [s]", "max dist M", "tolerance", "min angle", "chi", "valid", "run");
  const auto make_setup = [&command] {
    ProblemSetup setup = resolve_problem(command.problem);
    apply_start_and_box(setup, command.start, command.box);
    return setup;
  };
  const auto print_row = [](const CompareRow& row) {
    const std::string tolerance =
        row.run.tolerance > 0 ? std::to_string(row.run.tolerance).substr(0, 8) : "-";
    std::printf("%-8s %9d %10d %9.3f %12.3g %12s %9.1f %6d %-7s %s\n", row.method.c_str(),
                row.vertex_count, row.triangle_count, row.run.wall_seconds, row.max_distance,
                tolerance.c_str(), row.min_angle_degrees, row.euler_characteristic,
                row.valid ? "yes" : "NO", to_string(row.run.termination));
    std::fflush(stdout);
  };
  const CompareReport report = compare_methods(make_setup, command.settings, print_row);
  if (report.expected_euler_characteristic) {
    std::printf("expected Euler characteristic: %d\n", *report.expected_euler_characteristic);
  }
  return report.passes() ? 0 : kComputationFailed;
}

}  // namespace tessera::app
