// SPDX-License-Identifier: MIT
// PLY (Stanford polygon file) reading and writing for triangle meshes in R^n.
#pragma once

#include <string>
#include <vector>

#include "tessera/geometry/triangle_mesh.h"
#include "tessera/io/vertex_data.h"

namespace tessera {

/// How write_ply lays out the file.
struct PlyOptions {
  /// Binary little endian is exact and about ten times smaller and faster than ASCII; ASCII is
  /// for reading by eye and is exact too (shortest round-trip decimal form of each double).
  bool binary = true;
  /// One name per coordinate; empty means default_coordinate_names(n) (core/implicit_problem.h).
  /// The first three coordinates are always written as properties x, y, z, the only names
  /// meshio, ParaView and VTK take a vertex position from. Coordinate k >= 3 is written under
  /// its name here if that is an identifier ([A-Za-z_][A-Za-z0-9_]*) that no other property
  /// uses, else as coordinate_k; the defaults give x, y, z, x3, x4, .... When names are given
  /// and differ from the properties, a comment "coordinate names: ..." keeps them.
  std::vector<std::string> coordinate_names{};
  /// Extra vertex properties (double), written after the coordinates in this order; their names
  /// may not be x, y or z.
  std::vector<VertexScalars> vertex_scalars{};
  /// Written as "comment ..." header lines; each must be a single line.
  std::vector<std::string> comments{};
};

/// Writes `mesh` as PLY: one element "vertex" with a double property per coordinate (x, y, z,
/// then the extra coordinates of R^n, see PlyOptions::coordinate_names) and per scalar field,
/// one element "face" with "property list uchar int vertex_indices", and the comment
/// "written by tessera: triangle mesh in R^n" from which read_ply takes n. For n != 3 the
/// coordinates beyond z are extra vertex properties to other tools (meshio: point_data).
/// The file is replaced atomically (see io_detail::OutputFile): a failed write leaves the
/// previous file.
///
/// \throw InvalidArgument if the options break their documented rules, if a triangle has an
///        index outside [0, vertex_count), or if the file cannot be written (message names it).
void write_ply(const std::string& path, const TriangleMesh& mesh, const PlyOptions& options = {});

/// Reads a PLY file: ASCII, binary little endian or binary big endian.
///
/// Coordinates are the vertex properties named `coordinate_names` in that order. If it is empty:
/// in a file with the comment "written by tessera: triangle mesh in R^n", the first n vertex
/// properties (so files of every tessera version read back whole, whatever their names);
/// otherwise x0, x1, ... (as many as are consecutive) if x0 is present, else x, y, z followed
/// by x3, x4, ... or coordinate_3, coordinate_4, ... (as many as are consecutive). They may be
/// of any PLY scalar type; the point has as many coordinates as found, so the mesh is in R^n
/// for the n of the file. Other vertex
/// properties and other elements are skipped. Faces come from the list property
/// "vertex_indices" (or "vertex_index") of element "face"; a polygon with k > 3 vertices
/// (v0, v1, ..., v{k-1}) becomes the fan (v0, v{i}, v{i+1}), i = 1..k-2, which keeps its
/// orientation; a face with fewer than 3 vertices is rejected. No face element gives a mesh
/// without triangles. Data after the last declared element is ignored.
///
/// \throw InvalidArgument naming the file (and for ASCII the line) if it cannot be read, the
///        header is malformed, the data is truncated or malformed, or an index is out of range.
TriangleMesh read_ply(const std::string& path,
                      const std::vector<std::string>& coordinate_names = {});

}  // namespace tessera
