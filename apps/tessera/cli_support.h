// SPDX-License-Identifier: MIT
// Small pieces shared by the subcommands: exit codes and validators of the command line. What
// the bindings share with the CLI is in the library (report/, problems/start_and_box.h,
// io/output_checks.h).
#pragma once

#include <CLI/CLI.hpp>

namespace tessera::app {

constexpr int kComputationFailed = 1;
constexpr int kUsageError = 2;

/// CLI11's PositiveNumber lets NaN through; a step of NaN must be a usage error.
const CLI::Validator& finite_positive();

}  // namespace tessera::app
