// SPDX-License-Identifier: MIT
// The polyline files of the mesh formats (legacy VTK, VTU, ASCII PLY) read back: read_polylines
// (polyline_reader.cpp) dispatches here by extension; JSON and CSV, and the assembly of the
// polylines from points and lines shared by all, stay there.
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "tessera/io/polylines.h"

namespace tessera::io_detail {

/// \throw InvalidArgument "polylines file 'PATH': MESSAGE".
[[noreturn]] void refuse_polylines(const std::string& path, const std::string& message);

/// Polylines from the points of a file (k×N, in file order) and its lines as index lists (a
/// closed polyline repeats its first index, as line_indices writes it); points in no line are
/// polylines of one point (special points).
std::vector<Polyline> assemble_polylines(const Eigen::MatrixXd& points,
                                         const std::vector<int>& marks,
                                         const std::vector<std::vector<int>>& lines);

/// Each: the polylines of a file's text as write_polylines writes it in that format.
/// \throw InvalidArgument naming the file and what is wrong.
PolylineFile read_vtk_polylines(const std::string& path, const std::string& text);
PolylineFile read_vtu_polylines(const std::string& path, const std::string& text);
PolylineFile read_ply_polylines(const std::string& path, const std::string& text);

}  // namespace tessera::io_detail
