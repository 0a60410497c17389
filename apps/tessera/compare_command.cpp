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

int run_compare(const CompareCommand& command) {
  const auto make_setup = [&command] {
    ProblemSetup setup = resolve_problem(command.problem);
    apply_start_and_box(setup, command.start, command.box);
    return setup;
  };
  // Every method runs to the same tolerance, or their rows would not be comparable (front and
  // bezier have no bound of their own): it heads the table.
  MethodSettings settings = command.settings;
  if (settings.tolerance <= 0) {
    settings.tolerance = default_tolerance(make_setup());
  }
  std::printf("every method to tolerance %g (the distance of every triangle to M%s)\n",
              settings.tolerance, command.settings.tolerance > 0 ? "" : "; the default, step/50");
  std::printf("%-8s %9s %10s %9s %12s %9s %6s %-7s %s\n", "method", "vertices", "triangles",
              "time [s]", "max dist M", "min angle", "chi", "valid", "run");
  const auto print_row = [](const CompareRow& row) {
    std::printf("%-8s %9d %10d %9.3f %12.3g %9.1f %6d %-7s %s\n", row.method.c_str(),
                row.vertex_count, row.triangle_count, row.run.wall_seconds, row.max_distance,
                row.min_angle_degrees, row.euler_characteristic, row.valid ? "yes" : "NO",
                to_string(row.run.termination));
    std::fflush(stdout);
  };
  const CompareReport report = compare_methods(make_setup, settings, print_row);
  if (report.expected_euler_characteristic) {
    std::printf("expected Euler characteristic: %d\n", *report.expected_euler_characteristic);
  }
  return report.passes() ? 0 : kComputationFailed;
}

}  // namespace tessera::app
