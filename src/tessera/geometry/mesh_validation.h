// SPDX-License-Identifier: MIT
// Validation of a triangle mesh in R^n: counts, topology and every combinatorial or geometric
// defect, each named with the indices where it occurs.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "tessera/geometry/triangle_mesh.h"

namespace tessera {

enum class MeshDefectKind {
  IndexOutOfRange,          ///< a triangle has a vertex index outside [0, vertex_count)
  RepeatedIndex,            ///< a triangle has the same vertex twice, e.g. (4, 7, 4)
  DuplicateTriangle,        ///< a triangle has the same vertex set as an earlier one
  NonManifoldEdge,          ///< an edge has more than two triangles
  NonManifoldVertex,        ///< the triangles around a vertex form more than one fan (bow tie)
  InconsistentOrientation,  ///< in an orientable component, two triangles traverse an edge alike
  UnreferencedVertex,       ///< a vertex that no triangle refers to
  DegenerateTriangle,       ///< area <= degenerate_area_ratio * (longest edge)^2
  NonFiniteCoordinate,      ///< a vertex with a NaN or infinite coordinate
};

/// "index out of range", "non-manifold edge", ...
std::string_view to_string(MeshDefectKind kind);

/// One kind of defect: how often it occurs and where, for the first few occurrences.
struct MeshDefect {
  MeshDefectKind kind = MeshDefectKind::IndexOutOfRange;
  int count = 0;                      ///< triangles, edges or vertices that have the defect
  std::vector<std::string> examples;  ///< e.g. "edge (12, 40) has 3 triangles: 7, 9, 31"
};

struct ValidationOptions {
  /// A triangle is degenerate if area <= ratio * (longest edge)^2. The area is computed with
  /// an absolute error of a few ulp * (longest edge)^2 (see mesh_validation.cpp), so 1e-14
  /// (about 45 ulp) flags collinear and coincident points without flagging honest slivers:
  /// an isosceles triangle with apex angle 1e-6 radians has ratio 5e-7.
  double degenerate_area_ratio = 1e-14;
  /// Examples kept per defect kind; the counts are always complete.
  int max_examples = 5;
};

/// The result of validate(): plain members, so that it can be written as JSON field by field.
struct MeshValidation {
  // Counts. Triangles with an index out of range or a repeated index are left out of the
  // topology (edges, boundary, components, Euler characteristic) but counted in triangle_count.
  int ambient_dimension = 0;
  int vertex_count = 0;
  int referenced_vertex_count = 0;  ///< vertices used by a well-formed triangle
  int edge_count = 0;
  int triangle_count = 0;
  int boundary_edge_count = 0;
  int boundary_loop_count = 0;
  std::vector<int> boundary_loop_vertex_counts;  ///< one per boundary loop, as MeshTopology
  int component_count = 0;                       ///< edge-connected components of triangles
  int euler_characteristic = 0;                  ///< V - E + F, V = referenced_vertex_count
  /// Sum over components of (2 - chi_i) / 2 for a closed, orientable mesh without
  /// non-manifold edges or vertices, so 0 for a sphere and 1 for a torus; -1 otherwise.
  int genus = -1;
  bool is_orientable = true;               ///< every component is (across manifold edges)
  int non_orientable_component_count = 0;  ///< e.g. one per Möbius strip; not a defect

  // Defect counts; each nonzero count also has an entry in `defects`.
  int index_out_of_range_count = 0;        ///< triangles
  int repeated_index_count = 0;            ///< triangles
  int duplicate_triangle_count = 0;        ///< triangles that repeat an earlier triangle
  int non_manifold_edge_count = 0;         ///< edges
  int non_manifold_vertex_count = 0;       ///< vertices
  int inconsistent_orientation_count = 0;  ///< edges, in orientable components only
  int unreferenced_vertex_count = 0;       ///< vertices no triangle refers to (even a bad one)
  int degenerate_triangle_count = 0;       ///< triangles
  int non_finite_vertex_count = 0;         ///< vertices

  /// One entry per defect kind that occurs, in the order of MeshDefectKind.
  std::vector<MeshDefect> defects;

  /// True if there is no defect. Edges whose triangles disagree in orientation count only in
  /// orientable components: a Möbius strip is a valid, non-orientable mesh.
  bool is_valid() const { return defects.empty(); }
  /// At least one triangle and no boundary edge.
  bool is_closed() const { return triangle_count > 0 && boundary_edge_count == 0; }
  /// No non-manifold edge or vertex.
  bool is_manifold() const {
    return non_manifold_edge_count == 0 && non_manifold_vertex_count == 0;
  }
  /// Number of occurrences of `kind` (0 if none).
  int count(MeshDefectKind kind) const;
  /// Multi-line summary: counts, topology, then one line per defect example.
  std::string report() const;
};

/// Checks `mesh` for every kind of MeshDefectKind and computes its counts and topology.
/// Never throws for a bad mesh: every defect is reported, not raised. O(N) for bounded vertex
/// degree plus O(n) per vertex and triangle for the geometric checks in R^n.
/// \throw InvalidArgument if options.degenerate_area_ratio < 0 or options.max_examples < 0.
MeshValidation validate(const TriangleMesh& mesh, const ValidationOptions& options = {});

}  // namespace tessera
