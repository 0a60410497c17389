// SPDX-License-Identifier: MIT
// What a file's name says: its extension, by which every reader and writer chooses a format.
#pragma once

#include <string>

namespace tessera {

/// The extension of `path` with its dot, in lower case: "mesh.PLY" → ".ply", "a/b" → "".
std::string lowercase_extension(const std::string& path);

/// The file of curves computed on a mesh, beside it: "out.ply" → "out.KIND.ply" (.vtk and .vtu
/// alike); meshes in formats without lines (.obj) get "out.KIND.csv".
std::string curve_file_beside(const std::string& mesh_path, const std::string& kind);

}  // namespace tessera
