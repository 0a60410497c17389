// SPDX-License-Identifier: MIT
// Combinatorial topology of a triangle mesh: edges, incidences, adjacency, boundary loops,
// connected components and the Euler characteristic.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "tessera/geometry/triangle_mesh.h"

namespace tessera {

/// Which triangles must be reversed so that every manifold edge is traversed in opposite
/// directions by its two triangles; computed by MeshTopology::orientation_assignment().
struct OrientationAssignment {
  /// Per triangle: 1 if the triangle must be reversed. The lowest-numbered triangle of each
  /// component keeps its orientation, so a consistently oriented mesh gets all zeros.
  std::vector<std::uint8_t> is_flipped;
  /// Per component (see MeshTopology::component_of): 0 if no assignment exists (Möbius strip).
  /// For a non-orientable component `is_flipped` is the assignment along a spanning tree.
  std::vector<std::uint8_t> is_component_orientable;
};

/// Edges, incidences and adjacency of a set of oriented triangles, built once in O(N) (for
/// bounded vertex degree; O(N log N) at worst).
///
/// Edges are unordered vertex pairs {a, b}, stored sorted (a < b) and numbered in
/// lexicographic order. Local edge k of triangle t = (t0, t1, t2) joins t[k] and t[(k+1) % 3]
/// and is traversed by t from t[k] to t[(k+1) % 3]. Incidence lists are CSR arrays (one offset
/// array, one index array), so no container is allocated per vertex or per edge; the triangles
/// in every incidence list are in increasing order.
///
/// Meshes that are not manifolds are allowed: an edge may have any number of triangles (see
/// is_manifold_edge) and the triangles around a vertex may form several fans. Checks for such
/// defects are in validate() (mesh_validation.h).
class MeshTopology {
 public:
  /// A sorted vertex pair: edge[0] < edge[1].
  using Edge = std::array<int, 2>;

  /// \pre every index of every triangle is in [0, mesh.vertex_count()) and the three indices
  ///      of a triangle are distinct.
  /// \throw InvalidArgument naming the first triangle that breaks the precondition.
  explicit MeshTopology(const TriangleMesh& mesh);
  /// Same, for `triangles` over the vertices 0, ..., vertex_count - 1.
  MeshTopology(int vertex_count, std::span<const Triangle> triangles);

  /// All vertices, including those no triangle refers to.
  int vertex_count() const { return vertex_count_; }
  /// Vertices that at least one triangle refers to; this is the V of V - E + F.
  int referenced_vertex_count() const { return referenced_vertex_count_; }
  int edge_count() const { return static_cast<int>(edges_.size()); }
  int triangle_count() const { return static_cast<int>(triangles_.size()); }

  const std::vector<Triangle>& triangles() const { return triangles_; }
  const std::vector<Edge>& edges() const { return edges_; }
  const Edge& edge(int e) const { return edges_[e]; }
  /// Index of the edge {a, b} (either order), or -1 if no triangle has it. O(degree of a or b).
  int find_edge(int a, int b) const;

  /// Triangles that have edge `e`, in increasing order.
  std::span<const int> edge_triangles(int e) const {
    return span_of(edge_triangle_offsets_, edge_triangles_, e);
  }
  /// Triangles that have vertex `v`, in increasing order (empty for an unreferenced vertex).
  std::span<const int> vertex_triangles(int v) const {
    return span_of(vertex_triangle_offsets_, vertex_triangles_, v);
  }
  /// Edge indices of triangle t: element k is the edge joining t[k] and t[(k+1) % 3].
  const std::array<int, 3>& triangle_edges(int t) const { return triangle_edges_[t]; }
  /// The triangle across local edge k of triangle t, or -1 if that edge is on the boundary
  /// or is non-manifold (has more than two triangles).
  int adjacent_triangle(int t, int k) const { return triangle_neighbors_[t][k]; }

  /// True if edge `e` has exactly one triangle.
  bool is_boundary_edge(int e) const { return edge_triangles(e).size() == 1; }
  /// True if edge `e` has at most two triangles.
  bool is_manifold_edge(int e) const { return edge_triangles(e).size() <= 2; }
  /// False if `e` has exactly two triangles and both traverse it in the same direction, which
  /// means one of them is flipped relative to the other; true otherwise.
  bool is_orientation_consistent(int e) const { return is_edge_orientation_consistent_[e] != 0; }

  /// Boundary edges (those with one triangle), in increasing order.
  const std::vector<int>& boundary_edges() const { return boundary_edges_; }
  bool has_boundary() const { return !boundary_edges_.empty(); }
  /// True if there is at least one triangle and no boundary edge.
  bool is_closed() const { return !triangles_.empty() && boundary_edges_.empty(); }

  /// Boundary loops: every boundary edge is in exactly one loop. A loop is the cyclic
  /// sequence of its vertices (the first vertex is not repeated at the end), in the direction
  /// in which its triangles traverse its edges where they agree; for a consistently oriented
  /// mesh the surface is on the left of the loop. A bow-tie vertex on the boundary splits
  /// the loop there when it can. With non-manifold edges a vertex may end an odd number of
  /// boundary edges; a chain that cannot continue is then reported as an (open) loop.
  int boundary_loop_count() const { return static_cast<int>(boundary_loop_offsets_.size()) - 1; }
  std::span<const int> boundary_loop(int i) const {
    return span_of(boundary_loop_offsets_, boundary_loop_vertices_, i);
  }

  /// Triangles are in one component if a chain of triangles joins them, each sharing an edge
  /// with the next (triangles that share only a vertex are in different components).
  int component_count() const { return component_count_; }
  /// Component of triangle t, in [0, component_count()); numbered by their lowest triangle.
  int component_of(int t) const { return triangle_component_[t]; }

  /// V - E + F, with V = referenced_vertex_count().
  int euler_characteristic() const {
    return referenced_vertex_count_ - edge_count() + triangle_count();
  }

  /// Breadth-first search across manifold edges that reverses triangles as needed for their
  /// neighbours to agree. O(N).
  OrientationAssignment orientation_assignment() const;

 private:
  static std::span<const int> span_of(const std::vector<int>& offsets,
                                      const std::vector<int>& values, int i) {
    return {values.data() + offsets[i], static_cast<std::size_t>(offsets[i + 1] - offsets[i])};
  }
  void build_vertex_triangles();
  void build_edges();
  void build_components();
  void build_boundary_loops();

  int vertex_count_ = 0;
  int referenced_vertex_count_ = 0;
  int component_count_ = 0;
  std::vector<Triangle> triangles_;
  std::vector<Edge> edges_;
  std::vector<int> edges_by_low_vertex_offsets_;  // edges whose smaller vertex is v: a range
  std::vector<int> edge_triangle_offsets_;
  std::vector<int> edge_triangles_;
  std::vector<int> vertex_triangle_offsets_;
  std::vector<int> vertex_triangles_;
  std::vector<std::array<int, 3>> triangle_edges_;
  std::vector<std::array<int, 3>> triangle_neighbors_;
  std::vector<std::uint8_t> is_edge_orientation_consistent_;
  std::vector<int> triangle_component_;
  std::vector<int> boundary_edges_;
  std::vector<int> boundary_loop_offsets_{0};
  std::vector<int> boundary_loop_vertices_;
};

/// The triangles of `mesh`, with triangles reversed so that neighbours across every manifold
/// edge agree; the lowest-numbered triangle of each component keeps its orientation. For a
/// non-orientable component (Möbius strip) no such orientation exists; its triangles are
/// oriented along a spanning tree and `*is_orientable` (if given) is set to false.
/// \throw InvalidArgument as MeshTopology(mesh).
std::vector<Triangle> orient_consistently(const TriangleMesh& mesh, bool* is_orientable = nullptr);

}  // namespace tessera
