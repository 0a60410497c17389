// SPDX-License-Identifier: MIT
// Mesh files by extension: write_mesh / read_mesh choose PLY, OBJ, VTK or VTU from the path.
// Every format written can be read back; all but OBJ keep the n coordinates bit for bit.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "tessera/geometry/triangle_mesh.h"
#include "tessera/io/obj.h"
#include "tessera/io/ply.h"
#include "tessera/io/vertex_data.h"
#include "tessera/io/vtk.h"

namespace tessera {

/// Options for write_mesh; each format uses the fields it has a place for.
struct MeshFileOptions {
  /// .ply only: binary little endian (exact, compact) or ASCII (exact too, readable).
  bool binary = true;
  /// .ply, .vtk, .vtu: one name per coordinate; empty means default_coordinate_names(n)
  /// (core/implicit_problem.h). See PlyOptions::coordinate_names for viewers of PLY files.
  std::vector<std::string> coordinate_names{};
  /// .ply, .vtk, .vtu: extra per-vertex scalars. Ignored for .obj, which has no place for them.
  std::vector<VertexScalars> vertex_scalars{};
  /// .ply: comment lines; .vtk: the title; .vtu: XML comments. Ignored for .obj.
  std::vector<std::string> comments{};
  /// .obj only: the three coordinates written (see write_obj).
  std::array<int, 3> obj_coordinates = {0, 1, 2};
};

/// Writes `mesh` in the format named by the extension of `path` (case-insensitive):
/// .ply (write_ply), .obj (write_obj), .vtk (write_vtk), .vtu (write_vtu). Every writer
/// replaces the file atomically: a failed write leaves the previous file and no temporary.
///
/// \throw InvalidArgument for another extension (the message lists the supported ones), and
///        whatever the chosen writer throws.
void write_mesh(const std::string& path, const TriangleMesh& mesh,
                const MeshFileOptions& options = {});

/// Reads a mesh from .ply (read_ply, any n), .obj (read_obj, n = 3), .vtk (read_vtk, any n),
/// .vtu (read_vtu, any n) or .npy (read_states_npy: the states of `tessera mesh --states` with
/// their triangles beside them), by extension (case-insensitive).
///
/// \throw InvalidArgument for another extension (the message lists the supported ones), and
///        whatever the chosen reader throws.
TriangleMesh read_mesh(const std::string& path);

/// read_mesh, and the named per-vertex data the file carries beside the coordinates into
/// `vertex_scalars` (replaced): .ply the scalar vertex properties that are not coordinates,
/// .vtk and .vtu the one-component point-data arrays after the coordinates, in file order, each
/// with one value per vertex (e.g. `unstable_count` of `tessera mesh --stability`). .obj and
/// .npy carry none.
/// \throw as read_mesh.
TriangleMesh read_mesh(const std::string& path, std::vector<VertexScalars>& vertex_scalars);

/// The names of the `dimension` coordinates of the mesh file `path` as tessera wrote them, so
/// that a mesh written in a view (`tessera mesh --view lambda,epsilon,max:u`) is labelled and
/// coloured by its columns when it is read back:
///   .ply  the comment "coordinate names: …" (write_ply with names), else "coordinates: …"
///         (`tessera mesh`);
///   .vtk  the first `dimension` POINT_DATA arrays if the title starts "tessera triangle mesh in
///         R^" (write_vtk), else the names after "coordinates:" in the title;
///   .vtu  the first `dimension` PointData arrays if a comment says "written by tessera".
/// Anything else (another format or writer, a count other than `dimension`, empty or repeated
/// names, a file that cannot be read): default_coordinate_names(dimension). Never throws for a
/// dimension ≥ 1: the names are labels, read_mesh has checked the file.
std::vector<std::string> read_coordinate_names(const std::string& path, int dimension);

/// The comments tessera wrote into the mesh file `path`, in order: .ply the `comment` lines of
/// the header (without "comment "), .vtk the parts of the title separated by "; ", .vtu the XML
/// comments before <VTKFile> (where "--" was written as "- -"). .obj and .npy carry none.
/// Empty for a file that cannot be read (read_mesh says why). Never throws.
std::vector<std::string> read_mesh_comments(const std::string& path);

}  // namespace tessera
