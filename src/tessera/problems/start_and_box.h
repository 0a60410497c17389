// SPDX-License-Identifier: MIT
// The start point and the box of a run, from the text a user gives (`--start 0,0,1`,
// `--box -1,1,-1,1,-1,1` or `--box lambda=5:20`): the CLI's options and the bindings' keywords.
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "tessera/problems/problem_setup.h"

namespace tessera {

/// Parses "0,0,1". \throw InvalidArgument naming `option`, the item that is not a number and
/// `expected`, what the option takes (empty: "a comma-separated list such as 0,0,1").
std::vector<double> parse_numbers(const std::string& text, const std::string& option,
                                  const std::string& expected = "");

/// What `--box` takes, for messages: "lower,upper for each of the 3 coordinates, e.g.
/// '-1,1,-1,1,-1,1', or bounds on named coordinates only, … e.g. 'x=-1:1,z=0:'", with examples
/// in `problem`'s coordinate names that apply_start_and_box accepts.
std::string box_syntax(const ImplicitProblem& problem);

/// Parses the start points of `--start` given once or more ("0,0,1" each).
/// \throw InvalidArgument naming the start (its position when there are several) for an item
///        that is not a number or a wrong number of values.
std::vector<Eigen::VectorXd> parse_starts(const std::vector<std::string>& starts,
                                          const ImplicitProblem& problem);

/// Sets setup.start from "--start" text and intersects setup.domain with "--box" text (either
/// may be empty): lower,upper for each coordinate, or name=lower:upper,… on named coordinates
/// (either side may be empty: unbounded). A box makes the catalogue's expected topology and
/// area void.
/// \throw InvalidArgument for a wrong number of values, an unknown name or an empty box.
void apply_start_and_box(ProblemSetup& setup, const std::string& start, const std::string& box);

}  // namespace tessera
