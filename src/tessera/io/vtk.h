// SPDX-License-Identifier: MIT
// VTK output for ParaView and VisIt: legacy ASCII .vtk (POLYDATA) and XML .vtu
// (UnstructuredGrid, ASCII).
#pragma once

#include <string>
#include <vector>

#include "tessera/geometry/triangle_mesh.h"
#include "tessera/io/vertex_data.h"

namespace tessera {

/// What write_vtk and write_vtu put next to the geometry.
struct VtkOptions {
  /// One name per coordinate; empty means default_coordinate_names(n) (core/implicit_problem.h):
  /// x, y, z for n = 3, else x0 ... x{n-1}.
  std::vector<std::string> coordinate_names{};
  /// Extra point-data arrays (Float64), written after the coordinate arrays.
  std::vector<VertexScalars> vertex_scalars{};
  /// Legacy .vtk: joined with "; " into the title line (at most 255 characters, longer is cut).
  /// .vtu: one XML comment each. Each must be a single line; in .vtu it may not contain "--".
  std::vector<std::string> comments{};
};

/// Writes a legacy ASCII VTK file (version 4.2) with DATASET POLYDATA.
///
/// POINTS holds the first three coordinates of each vertex (0 for the missing ones if n < 3),
/// POLYGONS the triangles. POINT_DATA holds all n coordinates, one SCALARS array (double) per
/// coordinate named by the coordinate names, so that a view can colour by any coordinate of
/// R^n, followed by one SCALARS array per scalar field.
///
/// \throw InvalidArgument if the options break their documented rules, if a triangle has an
///        index outside [0, vertex_count), or if the file cannot be written.
void write_vtk(const std::string& path, const TriangleMesh& mesh, const VtkOptions& options = {});

/// Writes an XML VTK UnstructuredGrid file (.vtu, version 1.0, ASCII data) with the same content
/// as write_vtk: Points = first three coordinates, cells of type VTK_TRIANGLE (5), and PointData
/// arrays (Float64) for every coordinate and every scalar field.
///
/// \throw as write_vtk.
void write_vtu(const std::string& path, const TriangleMesh& mesh, const VtkOptions& options = {});

}  // namespace tessera
