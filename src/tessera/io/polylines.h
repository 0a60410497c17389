// SPDX-License-Identifier: MIT
// Polylines in R^k (fold curves in a view) written as VTK, VTU, PLY edges, JSON or CSV.
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

namespace tessera {

/// A polyline in R^k: points in order, some of them marked (e.g. cusps).
struct Polyline {
  Eigen::MatrixXd points;    ///< k×m, one point per column
  std::vector<bool> marked;  ///< m flags, or empty (none marked)
  bool is_closed = false;    ///< the last point joins the first
};

struct PolylineFileOptions {
  /// One name per coordinate (k); the first three place the points in VTK and PLY (k = 2: the
  /// third is 0). Every coordinate is also written as a named column or array.
  std::vector<std::string> names;
  /// Name of the 0/1 column of the marks.
  std::string marker_name = "cusp";
  /// .vtk title, .vtu XML comments, .ply comments, .json "comments", .csv '#' lines.
  std::vector<std::string> comments;
};

/// Writes `polylines` to `path` by its extension (case-insensitive), replacing it atomically:
///   .vtk  legacy ASCII POLYDATA: POINTS, LINES (a closed polyline repeats its first index), one
///         POINT_DATA array per coordinate and the marks;
///   .vtu  UnstructuredGrid with one VTK_POLY_LINE cell per polyline, the same arrays;
///   .ply  ASCII: element vertex (x, y, z, the further coordinates, the marks) and element edge
///         (vertex1, vertex2), one edge per segment;
///   .json {"columns": […], "polylines": [{"closed": b, "points": [[…], …], "marked": [i, …]}]};
///   .csv  header `curve,point,<names>,<marker_name>`, one row per point, curves numbered from 0.
/// docs/mesh-files.md describes them.
/// \throw InvalidArgument for another extension (listing these), names that do not match k or
///        are empty or repeated, marks of the wrong length, and if the file cannot be written.
void write_polylines(const std::string& path, const std::vector<Polyline>& polylines,
                     const PolylineFileOptions& options);

/// True if write_polylines knows the extension of `path`.
bool is_polyline_file(const std::string& path);

}  // namespace tessera
