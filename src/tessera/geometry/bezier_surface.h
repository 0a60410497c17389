// SPDX-License-Identifier: MIT
// A piecewise cubic surface: one triangular Bézier patch per triangle of a mesh (method
// `bezier`), its evaluation on a finer mesh and a check that neighbouring patches join.
#pragma once

#include <vector>

#include "tessera/geometry/bezier_patch.h"
#include "tessera/geometry/triangle_mesh.h"

namespace tessera {

/// The mesh of the cubic surface sampled on the K×K subdivision of every triangle: the points
/// p_t(i/K, j/K, k/K), i + j + k = K, joined into K² triangles per patch, oriented like the
/// triangle. Corner points are the mesh's vertices (the patches interpolate them) and the
/// K − 1 points on an edge are computed once and shared by both triangles at that edge, so the
/// result is watertight exactly when the input is (see max_edge_mismatch for the geometry).
/// The first vertex_count() vertices of the result are the input vertices, in order.
///
/// \param patches one per triangle, patches[t] over mesh.triangle(t) in its vertex order.
/// \param subdivisions K ≥ 1 (K = 1 returns the flat triangles).
/// \throw InvalidArgument if the counts or dimensions disagree or K < 1.
TriangleMesh refine_bezier_surface(const TriangleMesh& mesh,
                                   const std::vector<CubicBezierPatch>& patches, int subdivisions);

/// The largest distance, over every edge shared by two triangles and `samples` points along
/// it, between the two patches' edge curves. Zero up to rounding when the surface is continuous
/// (the edge curve of eq. 3.5 depends only on the edge's end points and tangent planes).
double max_edge_mismatch(const TriangleMesh& mesh, const std::vector<CubicBezierPatch>& patches,
                         int samples = 7);

}  // namespace tessera
