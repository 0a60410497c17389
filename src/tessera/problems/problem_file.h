// SPDX-License-Identifier: MIT
// User-defined problems from a text file: variables, parameters, equations, start, domain.
// The format is documented in docs/problem-files.md.
#pragma once

#include <map>
#include <string>

#include "tessera/problems/problem_setup.h"

namespace tessera {

/// Parses problem-file text. `source_name` is used in messages ("myproblem.tsr:7: ...").
/// \throw InvalidArgument naming the line and what is wrong.
ProblemSetup parse_problem(const std::string& text, const std::string& source_name = "<input>");

/// Reads and parses a problem file. \throw InvalidArgument if it cannot be read or parsed.
ProblemSetup load_problem_file(const std::string& path);

/// As above, with parameter values that replace the file's, by name: {{"r", 2.0}} turns
/// `parameter r = 1` into r = 2, and later parameters defined from r see the new value.
/// \throw InvalidArgument also for an override that names no parameter of the file (the
///        message lists the file's parameters) or that is not finite.
ProblemSetup parse_problem(const std::string& text, const std::string& source_name,
                           const std::map<std::string, double>& parameter_overrides);
ProblemSetup load_problem_file(const std::string& path,
                               const std::map<std::string, double>& parameter_overrides);

}  // namespace tessera
