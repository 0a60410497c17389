// SPDX-License-Identifier: MIT
// Checks on output paths made before any computation, so that a usage error never costs a run
// (the CLI and the bindings check their -o, --summary, --states, … paths with these), and so
// that a run never silently replaces a tessera file of another kind.
#pragma once

#include <string>

namespace tessera {

/// \throw InvalidArgument if the folder of `path` does not exist (empty path: no check).
void check_output_folder(const std::string& path);

/// check_output_folder, and the extension must be a mesh format write_mesh knows.
void check_mesh_output(const std::string& path);

/// The kinds of file tessera writes, as far as their content tells them apart.
enum class TesseraFileKind {
  None,            ///< no file, a file of another tool, or one not recognised
  Mesh,            ///< .ply, .vtk, .vtu of write_mesh (`tessera mesh -o`, `improve`, `ddt`)
  Curves,          ///< .json, .ply, .vtk, .vtu of write_polylines (--folds, --hopf, --level)
  MeshSummary,     ///< .json of `tessera mesh --summary` (report/summary_json.h)
  ImproveSummary,  ///< .json of `tessera improve --summary`
  BezierPatches,   ///< .json of `tessera mesh --patches` (io/bezier_patches.h)
};

/// What the file at `path` is: JSON by its top-level keys ("problem" and "ambient_dimension";
/// "criterion", "swaps" and "before"; "control_points" and "multi_indices"; "polylines"), mesh and
/// curve files by the marks their writers put in the header ("written by tessera: triangle mesh
/// in R^n", a legacy title "tessera triangle mesh in R^n" or "tessera polylines", a PLY `edge`
/// element with "coordinate names:", a VTU comment "kind: K"). Never throws: a file that cannot
/// be read or parsed is TesseraFileKind::None.
TesseraFileKind tessera_file_kind(const std::string& path);

/// The kind in words for messages, e.g. "the JSON summary of a `tessera mesh` run".
std::string describe(TesseraFileKind kind);

/// Overwriting a file of the same kind (an earlier run's) is normal; replacing a tessera file of
/// another kind silently is not (`--patches torus.json` over the summary `torus.json` of an
/// earlier `tessera mesh --summary torus.json`).
/// \param option  the option that names `path`, for the message ("--patches").
/// \throw InvalidArgument if `path` holds a tessera file of a kind other than `kind`, naming the
///        option, the file, what it holds, and a name that would not collide.
void check_replaces_same_kind(const std::string& option, const std::string& path,
                              TesseraFileKind kind);

}  // namespace tessera
