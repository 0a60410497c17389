// SPDX-License-Identifier: MIT
// Checks on output paths made before any computation, so that a usage error never costs a run
// (the CLI and the bindings check their -o, --summary, --states, … paths with these).
#pragma once

#include <string>

namespace tessera {

/// \throw InvalidArgument if the folder of `path` does not exist (empty path: no check).
void check_output_folder(const std::string& path);

/// check_output_folder, and the extension must be a mesh format write_mesh knows.
void check_mesh_output(const std::string& path);

}  // namespace tessera
