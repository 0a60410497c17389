// SPDX-License-Identifier: MIT
// Polylines in R^k (fold, Hopf and other curves in a view) written as VTK, VTU, PLY edges, JSON
// or CSV, and read back from JSON or CSV.
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
  /// Name of the 0/1 column of the marks: what the marked points are ("cusp" on fold curves,
  /// "bogdanov_takens" on Hopf curves, "zero_hopf").
  std::string marker_name = "cusp";
  /// What the curves are: "fold", "hopf", "neutral_saddle", "level", or empty (not written;
  /// read back as empty, which pictures draw as fold curves, as every file before kinds).
  std::string kind;
  /// .vtk title, .vtu XML comments, .ply comments, .json "comments", .csv '#' lines.
  std::vector<std::string> comments;
};

/// Writes `polylines` to `path` by its extension (case-insensitive), replacing it atomically:
///   .vtk  legacy ASCII UNSTRUCTURED_GRID: POINTS, CELLS of type VTK_LINE (3), one segment per
///         pair of consecutive points (a closed polyline has one back to its first point), and
///         VTK_VERTEX (1) for a polyline of one point; one POINT_DATA array per coordinate and
///         the marks;
///   .vtu  UnstructuredGrid with the same cells and arrays (segments rather than VTK_POLY_LINE,
///         which meshio does not read);
///   .ply  ASCII: element vertex (x, y, z, the further coordinates, the marks) and element edge
///         (vertex1, vertex2), one edge per segment;
///   .json {"columns": […], "marker": m, "kind": k, "polylines": [{"closed": b, "points": [[…], …],
///         "marked": [i, …]}]} ("kind" only when options.kind is set);
///   .csv  '#' comment lines, `# kind: k` (when set), then the header
///         `curve,point,<names>,<marker_name>`, one row per point, curves numbered from 0.
/// The kind is the comment "kind: k" in .vtk (title), .vtu and .ply.
/// docs/mesh-files.md describes them.
/// \throw InvalidArgument for another extension (listing these), names that do not match k or
///        are empty or repeated, marks of the wrong length, and if the file cannot be written.
void write_polylines(const std::string& path, const std::vector<Polyline>& polylines,
                     const PolylineFileOptions& options);

/// True if write_polylines knows the extension of `path`.
bool is_polyline_file(const std::string& path);

/// The content of a polylines file: the curves and what write_polylines was told about them.
struct PolylineFile {
  std::vector<Polyline> polylines;
  /// names: the columns (JSON "columns", CSV header; empty in a JSON file without "columns");
  /// marker_name: JSON "marker" or the CSV header's last column (default "cusp"); kind: JSON
  /// "kind" or the CSV line `# kind: k` (empty when absent); comments as written.
  PolylineFileOptions options;
};

/// Reads a polylines file written by write_polylines (or by hand, docs/pictures.md) by its
/// extension: .json, .csv, and the .vtk, .vtu and ASCII .ply files write_polylines writes (their
/// columns from the arrays' names, or the PLY's `comment coordinate names:` line; consecutive
/// segments that share a point are one polyline; a point in no line, such as a fold–Hopf point,
/// is a polyline of one point). Also the files of earlier versions: .vtk with DATASET POLYDATA
/// and LINES, .vtu with one VTK_POLY_LINE per polyline. Every point has the same count
/// k >= 2 of finite coordinates; JSON "columns", when present, names them (k names).
/// \throw InvalidArgument naming the file (and the line of a CSV file, the polyline and point of
///        a JSON file) if it cannot be read, is not valid JSON, or breaks the layout; another
///        extension is refused with a message naming the formats read.
PolylineFile read_polylines(const std::string& path);

}  // namespace tessera
