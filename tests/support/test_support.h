// SPDX-License-Identifier: MIT
// Shared helpers for the test suite: running the CLI, measuring convergence orders.
#pragma once

#include <string>
#include <vector>

namespace tessera::testing {

/// Result of running the `tessera` command line tool.
struct CommandResult {
  int exit_code = -1;
  std::string output;  ///< stdout and stderr, interleaved
};

/// Runs the built `tessera` binary with `arguments` (a shell-quoted string) and captures output.
CommandResult run_cli(const std::string& arguments);

/// Runs a shell command line (e.g. `mpiexec -n 2 tessera …`, a kill script) and captures its
/// stdout and stderr; stdin is /dev/null.
CommandResult run_shell(const std::string& command);

/// A fresh temporary directory for one test; removed at process exit is not guaranteed.
std::string temporary_directory(const std::string& name);

/// Least-squares slope of log(error) against log(h): the observed convergence order.
double observed_order(const std::vector<double>& h, const std::vector<double>& error);

/// Path of a file in the source tree, e.g. source_path("examples/problems/sphere.tsr").
std::string source_path(const std::string& relative);

}  // namespace tessera::testing
