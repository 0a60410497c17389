// SPDX-License-Identifier: MIT
// Validation of a triangle mesh in R^n: counts, topology and every combinatorial or geometric
// defect, each named with the indices where it occurs. Given the problem and the domain, also
// the geometric validity of a mesh of M ∩ S: orientation along M, no overlap on M, vertices in
// S (docs/validation.md).
#pragma once

#include <functional>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "tessera/core/domain.h"
#include "tessera/core/implicit_problem.h"
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
  // Geometric defects, checked only by validate(mesh, problem, domain):
  FlippedTriangle,       ///< its orientation disagrees with M's orientation around it (or it
                         ///< stands across M)
  OverlappingTriangles,  ///< two triangles that share no edge cover the same part of M
  VertexOutsideDomain,   ///< a vertex outside the domain S by more than rounding
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

  // Geometric checks (validate with a problem); the reasons are in docs/validation.md.
  /// A triangle whose oriented cosine s = det(Tᵀe₁, Tᵀe₂)/|e₁ ∧ e₂| against M's oriented tangent
  /// basis T (mean over its corners) is below this is flipped: s < 0 is reversed, 0 ≤ s < 0.1 means
  /// its plane stands across M at more than 84°. A triangle of size h on a surface of curvature
  /// κ tilts by O(κh) from the tangent plane, so s ≥ cos(κh) ≈ 0.5 even at κh = 1, a coarser
  /// mesh than any method makes; s < 0.1 is a fold, not a coarse triangle.
  double min_tangent_cosine = 0.1;
  /// Two triangles are tested on M when their projections onto the plane of the better aligned
  /// one overlap in more than this fraction of the smaller triangle's area: a filter only.
  /// Triangles sharing a vertex overlap in area 0 up to rounding (1e-16); two needles 0.1° wide
  /// that cross overlap in about 1e-4 of their area, so the filter must be far below that (the
  /// test on M decides, docs/validation.md).
  double overlap_area_ratio = 1e-9;
  /// They cover the same part of M if (the chart overlap being wider than the chart's
  /// distortion) the points q₁, q₂ of the two triangles over the overlap's centroid in M's
  /// tangent plane project onto M at nearly the same point: |P(q₁) − P(q₂)| ≤ ratio·|q₁ − q₂|.
  /// On the same sheet the ratio is at most κρ (ρ the overlap's reach, a fraction of an edge);
  /// on another sheet (the trough's, 5e-5 away, or the far side of a thin tube) P(q₂) stays on
  /// that sheet, a ratio near 1. 0.25 lies between the two.
  double overlap_same_point_ratio = 0.25;
  /// ... and they are taken for two sheets only if each of q₁, q₂ lies nearer to M than this
  /// fraction of |q₁ − q₂|: a triangle whose points sink deeper between the sheets than that
  /// (one that spans a thin tube) follows neither, and covers what its neighbour covers.
  double overlap_sheet_depth_ratio = 0.5;
  /// Sheets of M that cross (the `crossing` problem's sphere and plane, each covered as a
  /// component of its own by `--components all`): two triangles of different components that
  /// both lie along M (|s| ≥ crossing_alignment, see min_tangent_cosine) and whose planes meet
  /// at more than acos(crossing_plane_cosine) (|det(U₁ᵀU₂)| below it, U the planes' orthonormal
  /// bases) touch where the sheets cross: M's own shape, not a part of M covered twice. Within
  /// 18° of M each (0.95), two triangles over one sheet that turns by κh ≤ 0.5 rad between them
  /// meet at 65° at most, below the 69.5° of 0.35 (the atlas's min_sheet_cosine).
  double crossing_plane_cosine = 0.35;
  double crossing_alignment = 0.95;
  /// A vertex x is outside the domain if a half-space's signed distance is below
  /// −ratio·(1 + ‖x‖∞): rounding of a point placed on a face is a few ulp of its coordinates
  /// (2e-16·‖x‖∞), so 1e-12 accepts every vertex snapped to ∂S and reports one 3.9e-7 outside.
  double domain_tolerance_ratio = 1e-12;
  /// Polled before each factorisation of DF and each projection onto M of the geometric checks
  /// (orientation, overlaps on M, thin triangles): the cost of validation at large n (one
  /// factorisation is a second at n = 10⁵). Once it returns true those checks are cut short:
  /// what they judged stands, the rest is left unjudged and MeshValidation::checks_cut_short
  /// says what. The combinatorial checks and the domain check, which need no factorisation,
  /// always run in full. Empty: never cut short. On a split mesh the ranks decide together.
  std::function<bool()> stop_requested;
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

  // Geometric checks: set only by validate(mesh, problem, domain, options).
  bool is_geometry_checked = false;  ///< the geometric checks ran
  int flipped_triangle_count = 0;    ///< triangles reversed or standing across M
  int overlapping_pair_count = 0;    ///< pairs of triangles that cover the same part of M
  int vertex_outside_domain_count = 0;
  /// Triangles whose orientation could not be judged: DF is rank deficient or not finite at
  /// all three corners (e.g. on the crossing curve of two sheets). Not a defect.
  int unoriented_triangle_count = 0;
  /// Pairs of triangles of different components that cross transversally, both along M: sheets
  /// of M crossing (ValidationOptions::crossing_plane_cosine). Not a defect.
  int crossing_pair_count = 0;
  /// Complete lists, ascending, so that a caller can repair locally (remove and re-fill).
  std::vector<int> flipped_triangles;
  std::vector<std::pair<int, int>> overlapping_triangle_pairs;  ///< (s, t), s < t
  std::vector<int> vertices_outside_domain;

  /// What a stop request (ValidationOptions::stop_requested) left unjudged, one entry per
  /// geometric check it cut short, e.g. "orientation along M: 310 of 431 vertices not judged";
  /// empty when every check ran in full. A mesh valid with entries here is valid as far as it
  /// was checked, no more.
  std::vector<std::string> checks_cut_short;

  /// One entry per defect kind that occurs, in the order of MeshDefectKind.
  std::vector<MeshDefect> defects;

  /// True if there is no defect. Edges whose triangles disagree in orientation count only in
  /// orientable components: a Möbius strip is a valid, non-orientable mesh.
  bool is_valid() const { return defects.empty(); }
  /// A stop request cut the geometric checks short (see checks_cut_short).
  bool is_cut_short() const { return !checks_cut_short.empty(); }
  /// No defect but vertices that no triangle uses (what an edit leaves before compaction).
  bool is_valid_but_unreferenced() const {
    return defects.size() == static_cast<std::size_t>(unreferenced_vertex_count > 0 ? 1 : 0);
  }
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

/// Checks `mesh` for every combinatorial kind of MeshDefectKind (all but the geometric ones at
/// the end, which need M) and computes its counts and topology.
/// Never throws for a bad mesh: every defect is reported, not raised. O(N) for bounded vertex
/// degree plus O(n) per vertex and triangle for the areas in R^n.
/// \throw InvalidArgument if options.degenerate_area_ratio < 0 or options.max_examples < 0.
MeshValidation validate(const TriangleMesh& mesh, const ValidationOptions& options = {});

/// validate(mesh, options) for a mesh edited only at the vertices `changed` since it was last
/// found valid (vertices moved or created, triangles around them replaced; triangles may be
/// removed anywhere): the whole topology is checked (integers only, O(N)), the coordinates and
/// shapes only at those vertices and their triangles. What an edit of a large-n mesh needs,
/// where validate() costs O(n) per vertex and triangle; unchanged parts are not judged again.
/// \throw InvalidArgument as validate(), or if a changed index is out of range.
MeshValidation validate_around(const TriangleMesh& mesh, std::span<const int> changed,
                               const ValidationOptions& options = {});

/// validate(mesh, options) and the geometric validity of `mesh` as a mesh of M ∩ S, M = {F = 0}
/// of `problem` and S = `domain` (docs/validation.md):
///  - FlippedTriangle: its orientation, measured in M's tangent planes at its corners and made
///    consistent over each connected piece of the mesh, disagrees with the piece's majority
///    (weighted by area), it is folded over a neighbour at one corner definitely (both planes
///    within 72° of M's tangent plane there, facing opposite ways), or its plane stands across
///    M (options.min_tangent_cosine). A whole
///    component with reversed orientation is valid. Degenerate triangles are not judged.
///  - OverlappingTriangles: two triangles that share no edge (they may share a vertex) cover
///    the same part of M; close sheets of M (the trough, thin tubes) are not overlaps.
///  - VertexOutsideDomain: a vertex outside S by more than options.domain_tolerance_ratio.
/// Each example names the triangles or vertex and its coordinates; the lists in the result are
/// complete. Cost: one factorisation of DF per vertex (no n×n dense work),
/// an expected linear-time hash grid for the candidate pairs, and two projections onto M per
/// pair whose projections overlap in the plane. Numerical failures (a projection that does not
/// converge) leave a triangle or pair unjudged, never throw.
/// \throw InvalidArgument for bad options (as above, or a geometric ratio < 0), or if the mesh,
///        the problem and a bounded domain do not all live in the same R^n.
MeshValidation validate(const TriangleMesh& mesh, const ImplicitProblem& problem,
                        const Domain& domain, const ValidationOptions& options = {});

}  // namespace tessera
