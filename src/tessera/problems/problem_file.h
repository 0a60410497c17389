// SPDX-License-Identifier: MIT
// User-defined problems from a text file: variables, parameters, equations, start, domain.
// The format is documented in docs/problem-files.md.
#pragma once

#include <string>

#include "tessera/problems/problem_setup.h"

namespace tessera {

/// Parses problem-file text. `source_name` is used in messages ("myproblem.tsr:7: ...").
/// \throw InvalidArgument naming the line and what is wrong.
ProblemSetup parse_problem(const std::string& text, const std::string& source_name = "<input>");

/// Reads and parses a problem file. \throw InvalidArgument if it cannot be read or parsed.
ProblemSetup load_problem_file(const std::string& path);

}  // namespace tessera
