// SPDX-License-Identifier: MIT
// What clip_to_domain measures and keeps beside the mesh: the faces each vertex lies on, and
// the lengths, angles and stop requests of a pass taken at once. On a split mesh (SPMD,
// docs/cluster.md: each rank its rows of every point, the domain cut to the same rows) each is
// one reduction over the ranks, so that every rank takes the same branch; in one process the
// expressions are the serial code's own.
#pragma once

#include <functional>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "tessera/core/ambient_space.h"
#include "tessera/core/domain.h"
#include "tessera/geometry/triangle_mesh.h"

namespace tessera::detail {

/// Per vertex: the sorted faces of the domain it lies on.
using FaceSets = std::vector<std::vector<int>>;

/// ‖point(u) − point(w)‖ of each pair (u, w).
std::vector<double> lengths(const TriangleMesh& mesh, const AmbientSpace& space,
                            const std::vector<std::pair<int, int>>& pairs);

/// min_angle of each triangle.
std::vector<double> min_angles(const TriangleMesh& mesh, const AmbientSpace& space,
                               const std::vector<Triangle>& triangles);

/// Whether the caller asked to stop (on a split mesh: whether any rank did).
bool is_stop_requested(const std::function<bool()>& stop_requested, const AmbientSpace& space);

/// A vertex already at the corner point x of M ∩ (the faces `faces`), or −1.
int find_corner(const TriangleMesh& mesh, const AmbientSpace& space, const FaceSets& vertex_faces,
                const std::vector<int>& faces, const Eigen::VectorXd& x);

/// The faces two sorted face sets share.
std::vector<int> common_faces(const std::vector<int>& a, const std::vector<int>& b);

/// The faces each vertex lies on (to a relative 1e-9), the vertex put on them exactly.
FaceSets faces_of_vertices(const Domain& domain, const AmbientSpace& space, TriangleMesh& mesh);

/// Face k's label, quoted, for messages.
std::string describe_face(const Domain& domain, int k);

/// Keeps the triangles with keep[t] and the vertices they use, in place, with their face sets.
void compact(TriangleMesh& mesh, FaceSets& on_faces, const std::vector<bool>& keep);

}  // namespace tessera::detail
