// SPDX-License-Identifier: MIT
// The zero set of a function given at the vertices of a triangle mesh, as polylines: marching
// triangles on the sign changes and chaining of the crossings. Shared by the curves on M that
// tessera computes on a finished mesh (fold curves, level curves, Hopf curves), which then refine
// every crossing onto their own curve. docs/algorithms/level-curves.md has the algorithm.
#pragma once

#include <Eigen/Core>
#include <array>
#include <functional>
#include <optional>
#include <vector>

#include "tessera/geometry/mesh_topology.h"
#include "tessera/geometry/triangle_mesh.h"

namespace tessera {

/// What find_zero_set_curves may skip and where it starts.
struct ZeroSetOptions {
  /// Called once for each triangle reached, after the values of its three corners are known;
  /// true leaves the triangle out (no segment is drawn in it, it spreads the search no further)
  /// and counts it (ZeroSetCurves::skipped_triangle_count). Empty: no triangle is skipped.
  /// The fold curves skip triangles where the test function is rounding at every corner.
  std::function<bool(int triangle)> skip_triangle;
  /// The triangles the search starts from, in order (repeats are harmless); from each, the
  /// search spreads across every crossed edge to the triangles beside it, so a curve is
  /// followed to its ends from any triangle it passes through. Absent: every triangle (every
  /// vertex value is then asked for). Values are asked for only at the corners of triangles
  /// reached, so seeds near the expected curves keep an expensive value function cheap.
  std::optional<std::vector<int>> seed_triangles;
};

/// An edge of the mesh on which the vertex values change sign.
struct ZeroSetCrossing {
  int edge = -1;      ///< MeshTopology edge id
  int triangle = -1;  ///< a triangle beside the edge (the first that found the crossing)
  /// The edge's two vertices, as MeshTopology::edge(edge) lists them.
  std::array<int, 2> vertices = {-1, -1};
  /// Where the linear interpolant of the values vanishes: the point is
  /// (1 − fraction)·x(vertices[0]) + fraction·x(vertices[1]); fraction = v₀/(v₀ − v₁) in [0, 1].
  double fraction = 0.0;
};

/// Crossings in order along one curve of the zero set.
struct ZeroSetChain {
  std::vector<int> crossings;  ///< indices into ZeroSetCurves::crossings
  bool is_closed = false;      ///< the last crossing joins the first (in a triangle)
};

/// What find_zero_set_curves found.
struct ZeroSetCurves {
  std::vector<ZeroSetCrossing> crossings;  ///< in the order the search found them
  /// Every crossing is in exactly one chain: first the open chains, each walked from an end (a
  /// crossing in one triangle only: at the mesh boundary, beside a skipped triangle or a vertex
  /// without value), then the closed ones, then isolated crossings (chains of one, is_closed
  /// false: a crossing whose triangles are all skipped or end there).
  std::vector<ZeroSetChain> chains;
  int crossing_count = 0;            ///< crossings.size()
  int skipped_triangle_count = 0;    ///< triangles left out by ZeroSetOptions::skip_triangle
  int processed_triangle_count = 0;  ///< triangles reached (skipped ones included)
  int evaluated_vertex_count = 0;    ///< vertices whose value was asked for
};

/// The value at a vertex: the sign tells on which side of the zero set the vertex lies (0 counts
/// as positive); NaN says the value is unknown there.
using VertexValueFunction = std::function<double(int vertex)>;

/// Finds the curves where a function, linear on each triangle between its vertex values,
/// vanishes (marching triangles).
///
/// A mesh edge is crossed when the values at its two vertices are known (not NaN) and one is
/// ≥ 0 and the other < 0: 0 counts as positive, so a triangle whose three values are known has
/// zero or two crossed edges, and its two crossings are joined by a segment. An edge touching a
/// vertex with value NaN is never crossed: a triangle with such a corner has at most one crossed
/// edge, and a curve that reaches it ends there (a vertex where the function cannot be
/// evaluated, e.g. a Hopf test function where no eigenvalue pair is near the axis).
///
/// The search processes the seed triangles and spreads across every crossed edge to the
/// triangles beside it. Chains of crossings joined by segments are the polylines: open where a
/// crossing lies in one processed triangle only (the mesh boundary, a skipped triangle, a NaN
/// corner), closed when they return.
///
/// \param mesh  the triangles (only the connectivity is used).
/// \param topology  MeshTopology(mesh).
/// \param vertex_value  called at most once per vertex, lazily (only at the corners of
///        triangles reached); its results are kept.
/// \throw InvalidArgument if topology does not belong to mesh or a seed triangle is out of range.
ZeroSetCurves find_zero_set_curves(const TriangleMesh& mesh, const MeshTopology& topology,
                                   const VertexValueFunction& vertex_value,
                                   const ZeroSetOptions& options = {});

/// The same with every vertex value known up front (NaN: unknown).
/// \param vertex_values  one per vertex (mesh.vertex_count()), else InvalidArgument.
ZeroSetCurves find_zero_set_curves(const TriangleMesh& mesh, const MeshTopology& topology,
                                   const std::vector<double>& vertex_values,
                                   const ZeroSetOptions& options = {});

/// The linear estimate of a crossing's zero: (1 − s)·a + s·b for the points a, b of its edge's
/// vertices (columns of `points`, n×N, as TriangleMesh::points()).
Eigen::VectorXd crossing_point(const ZeroSetCrossing& crossing,
                               const Eigen::Ref<const Eigen::MatrixXd>& points);

}  // namespace tessera
