// SPDX-License-Identifier: MIT
// `tessera compare PROBLEM`: every covering method on the same problem, one table row each.
#pragma once

#include <string>

#include "tessera/methods/covering_methods.h"

namespace CLI {
class App;
}  // namespace CLI

namespace tessera::app {

struct CompareCommand {
  std::string problem;
  std::string start;
  std::string box;
  MethodSettings settings;  ///< --step and --tolerance go to the methods that take them
};

CLI::App* add_compare_command(CLI::App& app, CompareCommand& command);

/// Prints the table of compare_methods (report/method_comparison.h); returns 1 if any method
/// failed or gave an invalid mesh, else 0.
int run_compare(const CompareCommand& command);

}  // namespace tessera::app
