// SPDX-License-Identifier: MIT
// The problem a mesh file was computed for, recorded in the file's comments, so that `tessera
// check FILE` finds it without --problem and refuses a problem file that is gone or has changed.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "tessera/problems/problem_setup.h"

namespace tessera {

/// The comments that record `specification` (a catalogue name with parameters, or a problem file
/// with parameters, as resolve_problem takes it) in the files of a run:
///   "problem: SPEC"                  SPEC with a problem file named by its absolute path, so
///                                    that a check from another folder finds it;
///   "problem file fnv1a64: HHHH…"    for a problem file only: the 64-bit FNV-1a hash of its
///                                    bytes (16 hexadecimal digits), so that a check can tell
///                                    that the file has changed since;
///   "box: BOX"                       the --box the mesh was clipped to, if not empty (the
///                                    domain, and an Euler characteristic no longer known).
/// \throw InvalidArgument if a problem file named by `specification` cannot be read.
std::vector<std::string> problem_record_comments(const std::string& specification,
                                                 const std::string& box = "");

/// A problem recorded in a file's comments.
struct RecordedProblem {
  std::string specification;  ///< as resolve_problem takes it
  std::string file_hash;      ///< 16 hexadecimal digits, or empty: not recorded
  std::string comment;        ///< the comment it was read from, for messages
  std::string box;            ///< the --box of apply_start_and_box, or empty
};

/// The problem recorded in `comments` (read_mesh_comments, io/mesh_io.h): "problem: SPEC" (with
/// "problem file fnv1a64: H" and "box: BOX"), else, in the files of earlier versions, the SPEC of
/// "tessera mesh SPEC, method M" or of "tessera improve MESH --problem SPEC --criterion C" (also
/// with "- -" for
/// "--", as in VTU comments). nullopt if the comments record none.
std::optional<RecordedProblem> find_recorded_problem(const std::vector<std::string>& comments);

/// resolve_problem(recorded.specification) clipped to recorded.box (apply_start_and_box), after
/// checking that a recorded problem file still exists and, where its hash was recorded, has not
/// changed.
/// \throw InvalidArgument naming `mesh_path`, the recorded problem and what is wrong (the problem
///        file is gone, has changed, or the specification cannot be resolved here) and saying to
///        pass --problem.
ProblemSetup resolve_recorded_problem(const RecordedProblem& recorded,
                                      const std::string& mesh_path);

/// The 64-bit FNV-1a hash of the bytes of the file `path`, as 16 lower-case hexadecimal digits.
/// \throw InvalidArgument if the file cannot be read.
std::string file_fnv1a64(const std::string& path);

}  // namespace tessera
