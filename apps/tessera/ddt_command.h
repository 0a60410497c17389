// SPDX-License-Identifier: MIT
// `tessera ddt`: data-dependent triangulation of scattered data in the plane (Malcolm).
#pragma once

#include <string>

namespace CLI {
class App;
}  // namespace CLI

namespace tessera::app {

struct DdtCommand {
  std::string points;        ///< CSV file with columns x, y[, value]
  std::string function;      ///< F1, F2, F7, F8, F9: sample it and measure the error against it
  std::string value_column;  ///< or take the values from this CSV column
  std::string criterion = "abn";
  std::string norm = "l2";
  std::string test = "global";
  std::string output;  ///< PLY with the value as z and as the vertex property "value"
  int grid = 33;
  bool all_criteria = false;
  int orders = 1;          ///< with --all-criteria: sweep orders tried (index order + random)
  int compare_report = 0;  ///< 33 or 100: print Malcolm's Table 1 or 2 value beside each row
};

/// Registers the subcommand and its options on `app`.
CLI::App* add_ddt_command(CLI::App& app, DdtCommand& command);

/// Runs it; returns the process exit code. \throw InvalidArgument for bad input.
int run_ddt(const DdtCommand& command);

}  // namespace tessera::app
