// SPDX-License-Identifier: MIT
// Internal to the io layer: checks every writer makes before it creates a file.
#pragma once

#include <string>
#include <vector>

#include "tessera/geometry/triangle_mesh.h"
#include "tessera/io/vertex_data.h"

namespace tessera::io_detail {

/// The coordinate names to write: `requested` if not empty, else default_coordinate_names(n)
/// (core/implicit_problem.h). Checks, naming `options_name` in the message, that there is one
/// name per coordinate, that every name (coordinate or scalar) is non-empty without whitespace
/// and unique, and that every scalar field has one value per vertex.
/// \throw InvalidArgument if a check fails.
std::vector<std::string> checked_vertex_data_names(const TriangleMesh& mesh,
                                                   const std::vector<std::string>& requested,
                                                   const std::vector<VertexScalars>& scalars,
                                                   const std::string& options_name);

/// \throw InvalidArgument naming the triangle if a vertex index is outside [0, vertex_count).
/// Checked before writing so that no file is produced that no reader accepts.
void check_triangle_indices(const TriangleMesh& mesh, const std::string& path);

/// \throw InvalidArgument if a comment holds a line break (it would end the comment early).
void check_comments(const std::vector<std::string>& comments, const std::string& options_name);

}  // namespace tessera::io_detail
