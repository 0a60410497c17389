// SPDX-License-Identifier: MIT
// Small pieces shared by the subcommands: exit codes, number parsing, validators, reports.
#pragma once

#include <CLI/CLI.hpp>
#include <nlohmann/json_fwd.hpp>
#include <functional>
#include <string>
#include <vector>

#include "tessera/geometry/triangle_mesh.h"
#include "tessera/io/summary_json.h"
#include "tessera/methods/covering_methods.h"
#include "tessera/problems/problem_setup.h"

namespace tessera::app {

constexpr int kComputationFailed = 1;
constexpr int kUsageError = 2;

/// CLI11's PositiveNumber lets NaN through; a step of NaN must be a usage error.
const CLI::Validator& finite_positive();

/// Parses "0,0,1". \throw InvalidArgument naming `option` and the item that is not a number.
std::vector<double> parse_numbers(const std::string& text, const std::string& option);

/// Sets setup.start from "--start" text and intersects setup.domain with "--box" text (either
/// may be empty). A box makes the catalogue's expected topology and area void.
/// \throw InvalidArgument for a wrong number of values.
void apply_start_and_box(ProblemSetup& setup, const std::string& start, const std::string& box);

/// Validation (combinatorial and geometric: orientation along M, overlaps on M, vertices in the
/// setup's domain) and quality of `mesh` against the problem, for printing or JSON.
/// `known`: a validation of exactly this mesh already made (a covering's final check), reused.
/// `samples`: distances measured at this many points of each kind (0: all; −1: all below
/// n = 500, else 300).
/// `measure_distances`: false leaves the distances to M unmeasured (their counts 0 of their
/// populations): the summary `tessera mesh` writes before the measurement, which at large n
/// takes minutes, so that a run killed during it still leaves one.
/// `run_seconds`: how long the covering took. With the default `samples`, the distances get a
/// tenth of that, at least 10 s, and then stop (at least 30 samples of each kind; the report
/// says how many it measured): at n = 10⁵ a sample costs a factorisation.
/// `stop_requested`: polled before every distance sample (Ctrl-C ends the measurement).
MeshReport make_report(const TriangleMesh& mesh, const ProblemSetup& setup,
                       const std::string& problem_argument,
                       const MeshValidation* known = nullptr, int samples = -1,
                       bool measure_distances = true, double run_seconds = 0.0,
                       const std::function<bool()>& stop_requested = {},
                       const std::function<bool(bool)>& decide_together = {});

/// A method's own options given to another method would be ignored silently: refuses them
/// (InvalidArgument naming them), as the command line spells them (`--max-step`) or, with
/// `keyword_names`, as the bindings do (`max_step`).
void refuse_options_of_other_methods(const MethodSettings& given, const std::string& method,
                                     bool keyword_names);

/// The quality and validity of a mesh before or after `improve` (the CLI's --json report and
/// the bindings' tessera.improve): angles, distances to M, area, validity, χ, boundary.
nlohmann::json improvement_quality_json(const MeshQuality& quality,
                                        const MeshValidation& validation);

}  // namespace tessera::app
