// SPDX-License-Identifier: MIT
// Shared helpers for the test suite: running the CLI, measuring convergence orders.
#pragma once

#include <string>
#include <vector>

namespace tessera {
class TriangleMesh;
}  // namespace tessera

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

/// Starts `words` (words[0] the program's path) as a child process without waiting for it:
/// stderr to `stderr_path`, stdout to `stdout_path` (the same file as stderr if equal; empty:
/// /dev/null), stdin from /dev/null. Returns the child's pid (waitpid it).
int spawn(std::vector<std::string> words, const std::string& stderr_path,
          const std::string& stdout_path = "");

/// The bytes of a file (empty if it cannot be read).
std::string read_file_bytes(const std::string& path);

/// Expects the same mesh, bit for bit: the same vertices (every coordinate's bits) and the same
/// triangles (what a resumed run must give). `what` names the comparison in failures.
void expect_identical_meshes(const TriangleMesh& a, const TriangleMesh& b, const std::string& what);

/// A fresh temporary directory for one test; removed at process exit is not guaranteed.
std::string temporary_directory(const std::string& name);

/// Least-squares slope of log(error) against log(h): the observed convergence order.
double observed_order(const std::vector<double>& h, const std::vector<double>& error);

/// Path of a file in the source tree, e.g. source_path("examples/problems/sphere.tsr").
std::string source_path(const std::string& relative);

}  // namespace tessera::testing
