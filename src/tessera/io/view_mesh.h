// SPDX-License-Identifier: MIT
// A mesh written in a view: each vertex replaced by the view's functionals of it, e.g. a surface
// in R^1002 written as (lambda, epsilon, max:u) in R^3.
#pragma once

#include <string>

#include "tessera/geometry/triangle_mesh.h"
#include "tessera/io/mesh_io.h"
#include "tessera/problems/view.h"

namespace tessera {

/// The image of `mesh` under the view φ: vertex j at φ(vertex j of mesh), the same triangles.
///
/// A split mesh (mesh.space().is_distributed(), docs/cluster.md) is viewed collectively: every
/// rank calls this and gets the same mesh in R^k (View::evaluate_columns with the mesh's space:
/// a few reductions for all vertices at once).
///
/// \return a mesh in R^k for a view of k ≥ 3 functionals; for k = 2, in R^3 with the third
///         coordinate 0 (viewers place points by x, y and z; the surface lies in the plane z = 0).
/// \throw InvalidArgument if view.ambient_dimension() != n (mesh.space().dimension()) or if the
///        view has fewer than two functionals (one value per vertex cannot place a surface).
TriangleMesh mesh_in_view(const TriangleMesh& mesh, const View& view);

/// The coordinate names of mesh_in_view(mesh, view): the view's column names (View::names), and
/// for a view of two functionals "zero" for the third coordinate (or "zero_2", … if a column is
/// already called that).
std::vector<std::string> coordinate_names_in_view(const View& view);

/// Writes mesh_in_view(mesh, view) to `path` with write_mesh (format by extension, atomic
/// replacement). The first three functionals are the geometry (PLY x, y, z; VTK points; OBJ v);
/// PLY and VTK/VTU files also carry every functional under its column name (PLY: x, y, z, then
/// the 4th, 5th, … as vertex properties and a comment "coordinate names: …"; VTK/VTU: one
/// point-data array per functional); OBJ keeps the first three. A comment "view: SPECIFICATION"
/// (View::specification) is added to `options.comments`.
///
/// A split mesh: collective, every rank computes the view (mesh_in_view) and rank 0 alone
/// writes; if it fails, every rank throws (rank 0 its own error).
///
/// \param options  as for write_mesh; coordinate_names and obj_coordinates are replaced.
/// \throw InvalidArgument as mesh_in_view and write_mesh.
void write_mesh_in_view(const std::string& path, const TriangleMesh& mesh, const View& view,
                        MeshFileOptions options = {});

}  // namespace tessera
