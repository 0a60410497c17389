// SPDX-License-Identifier: MIT
// Internal to the io layer: the mesh readers on a file's content in memory, for fuzz targets and
// exhaustive tests that must not touch the disk. read_ply / read_vtk / read_vtu read the file
// and call these.
#pragma once

#include <Eigen/Core>
#include <string>
#include <string_view>
#include <vector>

#include "tessera/geometry/triangle_mesh.h"
#include "tessera/io/vertex_data.h"

namespace tessera::io_detail {

/// read_ply on `content`, the whole file; `path` only names it in messages. With
/// `vertex_scalars`, the scalar vertex properties that are not coordinates go there, in file order.
TriangleMesh parse_ply(const std::string& content, const std::string& path,
                       const std::vector<std::string>& coordinate_names = {},
                       std::vector<VertexScalars>* vertex_scalars = nullptr);
/// read_vtk on `content`, the whole file; `path` only names it in messages. With
/// `vertex_scalars`, the one-component point-data arrays that are not coordinates go there.
TriangleMesh parse_vtk(const std::string& content, const std::string& path,
                       std::vector<VertexScalars>* vertex_scalars = nullptr);
/// read_vtu on `content`, the whole file; `path` only names it in messages. `vertex_scalars`
/// as parse_vtk.
TriangleMesh parse_vtu(const std::string& content, const std::string& path,
                       std::vector<VertexScalars>* vertex_scalars = nullptr);
/// The points of read_states_npy from the content of the states file: n×V, one point per column.
Eigen::MatrixXd parse_npy_points(std::string_view content, const std::string& path);
/// The triangles of read_states_npy from the content of the triangles file, each index checked
/// against `vertex_count`.
std::vector<Triangle> parse_npy_triangles(std::string_view content, const std::string& path,
                                          int vertex_count);

}  // namespace tessera::io_detail
