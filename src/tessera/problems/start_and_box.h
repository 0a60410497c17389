// SPDX-License-Identifier: MIT
// The start point and the box of a run, from the text a user gives (`--start 0,0,1`,
// `--box -1,1,-1,1,-1,1` or `--box lambda=5:20`): the CLI's options and the bindings' keywords.
#pragma once

#include <string>
#include <vector>

#include "tessera/problems/problem_setup.h"

namespace tessera {

/// Parses "0,0,1". \throw InvalidArgument naming `option` and the item that is not a number.
std::vector<double> parse_numbers(const std::string& text, const std::string& option);

/// Sets setup.start from "--start" text and intersects setup.domain with "--box" text (either
/// may be empty): lower,upper for each coordinate, or name=lower:upper,… on named coordinates
/// (either side may be empty: unbounded). A box makes the catalogue's expected topology and
/// area void.
/// \throw InvalidArgument for a wrong number of values, an unknown name or an empty box.
void apply_start_and_box(ProblemSetup& setup, const std::string& start, const std::string& box);

}  // namespace tessera
