// SPDX-License-Identifier: MIT
// VTK files for ParaView, VisIt and meshio: legacy ASCII .vtk (UNSTRUCTURED_GRID) and XML .vtu
// (UnstructuredGrid, ASCII), written and read back with all n coordinates.
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
  /// Legacy .vtk: appended with "; " to the title "tessera triangle mesh in R^n" (at most 255
  /// characters, longer is cut). .vtu: one XML comment each, after "written by tessera:
  /// triangle mesh in R^n". Each must be a single line; in .vtu it may not contain "--".
  std::vector<std::string> comments{};
};

/// Writes a legacy ASCII VTK file (version 4.2) with DATASET UNSTRUCTURED_GRID.
///
/// POINTS holds the first three coordinates of each vertex (0 for the missing ones if n < 3),
/// CELLS the triangles and CELL_TYPES their type, VTK_TRIANGLE (5). (Files of tessera before
/// issue 34 hold DATASET POLYDATA with POLYGONS, which meshio refuses; read_vtk reads both.)
/// POINT_DATA holds all n coordinates, one SCALARS array (double) per
/// coordinate named by the coordinate names, so that a view can colour by any coordinate of
/// R^n, followed by one SCALARS array per scalar field. read_vtk reads it back whole. The file
/// is replaced atomically (see io_detail::OutputFile).
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

/// Reads a legacy ASCII VTK file with DATASET UNSTRUCTURED_GRID, as write_vtk writes it, or
/// DATASET POLYDATA, as tessera wrote it before.
///
/// The mesh is in R^n for the n of the title "tessera triangle mesh in R^n ..." (written by
/// write_vtk); its coordinates are the first n POINT_DATA arrays, whose first three must equal
/// the POINTS bit for bit. Without that title: the arrays x0, x1, ... if the point data starts
/// with at least three of them, or the arrays named after "coordinates:" in the title (files of
/// earlier tessera versions), else the POINTS (n = 3). Unstructured grid: the CELLS of type
/// triangle (5), quad (9) and polygon (7) become triangles (a cell with k > 3 vertices becomes a
/// fan, keeping its orientation), vertices and lines (types 1 to 4) are skipped, other types
/// (volumes) are refused; CELLS may also be given as OFFSETS and CONNECTIVITY (version 5.1, as
/// meshio writes). Polygonal data: POLYGONS become triangles in the same way; VERTICES, LINES and
/// TRIANGLE_STRIPS are skipped. CELL_DATA, VECTORS and NORMALS are skipped.
///
/// \throw InvalidArgument naming the file and line if it cannot be read, is binary, or is
///        malformed or inconsistent (counts, indices out of range, coordinates that disagree).
///        Counts in the file are checked against its size before anything is allocated.
TriangleMesh read_vtk(const std::string& path);

/// Reads an XML VTK UnstructuredGrid file (.vtu) with one Piece and ASCII data arrays, as
/// write_vtu writes it. The mesh is in R^n for the n of the comment "written by tessera:
/// triangle mesh in R^n"; the coordinates are the first n PointData arrays (the first three
/// equal to the Points bit for bit). Without that comment: as read_vtk (x0, x1, ... arrays, else
/// the Points). Cells must be triangles (type 5), quads (9) or polygons (7); the last two become
/// fans. Binary, appended or compressed data is rejected with a message saying so.
///
/// \throw InvalidArgument naming the file and line as read_vtk.
TriangleMesh read_vtu(const std::string& path);

}  // namespace tessera
