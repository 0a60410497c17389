// SPDX-License-Identifier: MIT
// Small pieces shared by the subcommands: exit codes and validators of the command line, and the
// messages for mistakes CLI11 finds. What the bindings share with the CLI is in the library
// (report/, problems/start_and_box.h, io/output_checks.h).
#pragma once

#include <optional>
#include <string>
#include <vector>

namespace CLI {
class App;
class ParseError;
class Validator;
}  // namespace CLI

namespace tessera::app {

constexpr int kComputationFailed = 1;
constexpr int kUsageError = 2;

/// CLI11's PositiveNumber lets NaN through; a step of NaN must be a usage error.
const CLI::Validator& finite_positive();

/// Damerau–Levenshtein distance (optimal string alignment: insertions, deletions, substitutions
/// and transpositions of neighbours, each 1) between `a` and `b`.
int edit_distance(const std::string& a, const std::string& b);

/// The names in `candidates` that `typed` is most likely a misspelling of, as git suggests
/// commands: those at the smallest edit distance, if it is at most a third of typed's length
/// (at least 1), else those that `typed` (3 characters or more) begins; empty if none, and for
/// a single letter ("-x"). Leading dashes are compared too, so that "--tolerence" finds
/// "--tolerance" and not "-t".
std::vector<std::string> nearest_names(const std::string& typed,
                                       const std::vector<std::string>& candidates);

/// For the mistakes CLI11 reports without saying what to do (an argument that no option takes,
/// a command that does not exist), after `app.parse` threw `error`: the message to print after
/// "tessera: error: ", naming the argument and the nearest option or command ("unknown option
/// '--tolerence' for 'tessera mesh'; did you mean '--tolerance'?"). Empty for other errors,
/// which CLI11's own message describes.
std::optional<std::string> explain_parse_error(const CLI::App& app, const CLI::ParseError& error);

}  // namespace tessera::app
