// SPDX-License-Identifier: MIT
// The fingerprint of a covering run that begins a method's checkpointed state (the atlas's,
// the front's): a state is continued only by the run it was made by (docs/checkpoints.md).
#pragma once

#include <Eigen/Core>
#include <bit>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "tessera/core/ambient_space.h"
#include "tessera/core/domain.h"
#include "tessera/core/counted_problem.h"
#include "tessera/core/implicit_problem.h"

namespace tessera {
class BinaryReader;
class BinaryWriter;
}  // namespace tessera

namespace tessera::detail {

/// The options that decide a method's build, by name, their values as doubles (flags 0 or 1).
using DecisiveOptions = std::vector<std::pair<std::string, double>>;

/// What identifies a run: the problem (its name, n, and F at two fixed points near the start,
/// bit for bit: a changed definition or parameter changes them, whatever the name says), the
/// start, the domain's half-spaces and the options that decide the build.
struct RunIdentity {
  const ImplicitProblem& problem;
  const AmbientSpace& space;
  const Eigen::VectorXd& start;  ///< this process's rows
  const Domain& domain;
  DecisiveOptions options;
  /// How a refusal names an option and what would differ: "AtlasOptions", "atlas".
  std::string options_type;
  std::string product;
  /// The domain may be larger than the fingerprint's if it contains it (the atlas's `extend`):
  /// each face parallel to one of the old domain's and no nearer to it.
  bool domain_may_grow = false;
};

/// A fingerprint read without comparing it (what `tessera extend` needs of a state).
struct RunFingerprint {
  std::string problem;
  int dimension = 0;
  DecisiveOptions options;
};
RunFingerprint read_run_fingerprint(BinaryReader& in);

/// Writes the fingerprint of `run` (the bytes the atlas's state version 1 begins with).
void write_run_fingerprint(BinaryWriter& out, const RunIdentity& run);
/// Reads a fingerprint and compares it with `run`.
/// \throw InvalidArgument (BinaryReader::fail) naming the first thing that differs: the problem,
///        F at a test point, the start, the domain or an option with both values.
void check_run_fingerprint(BinaryReader& in, const RunIdentity& run);

/// The work a state records after its fingerprint, over every run it continues: the method's
/// count (charts, vertices), the build's seconds, and F, DF and factorisations.
struct WorkDone {
  int count = 0;
  double build_seconds = 0.0;
  WorkCounts counts;
};
/// Writes `before` plus what `problem` counted in this run (if it is a CountedProblem).
void write_work_done(BinaryWriter& out, int count, double build_seconds, const WorkCounts& before,
                     const ImplicitProblem& problem);
/// \throw InvalidArgument (BinaryReader::fail) for a count below 1, naming `unit` ("charts").
WorkDone read_work_done(BinaryReader& in, const char* unit);

/// The same bits (NaN payloads and signed zeros included).
inline bool same_bits(double a, double b) {
  return std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b);
}
bool same_bits(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b);
/// `value` with 17 significant digits: two doubles that differ print differently.
std::string exact_number(double value);

}  // namespace tessera::detail
