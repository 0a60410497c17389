// SPDX-License-Identifier: MIT
// What `tessera mesh` writes from a mesh's points, for a mesh in one process or split over the
// ranks of a distributed problem (docs/cluster.md): the mesh file in a view, the states.
#pragma once

#include <string>
#include <vector>

#include "tessera/core/ambient_space.h"
#include "tessera/geometry/triangle_mesh.h"
#include "tessera/io/mesh_io.h"
#include "tessera/problems/view.h"

namespace tessera {

/// The files written from a mesh's points.
struct MeshOutput {
  std::string mesh_path;    ///< .ply, .obj, .vtk or .vtu; empty: none
  View view;                ///< what mesh_path shows; View::is_all_coordinates(): every coordinate
  MeshFileOptions options;  ///< as for write_mesh (every coordinate) or write_mesh_in_view
  std::string states_path;  ///< the vertices as .npy (write_states_npy); empty: none
};

/// The largest n for which a split mesh's file of every coordinate is written, its points
/// gathered to rank 0: kLargeAmbientDimension, up to which tessera writes every coordinate by
/// default. At most 400 bytes a vertex, as small as a view's few functionals.
constexpr int kMaxGatheredDimension = kLargeAmbientDimension;

/// Whether write_mesh_output can write a mesh of `space` in `view`; a caller checks this
/// before computing the mesh. Not collective: the same answer on every rank.
/// \throw InvalidArgument for a mesh file of every coordinate of a split mesh in R^n with
///        n > kMaxGatheredDimension: rank 0 would hold every vertex's n-vector, which the split
///        over the ranks exists to avoid. The message names the ways out: the states to one
///        .npy file, streamed (--states), and the mesh file in a view of a few functionals
///        (--view).
void check_split_mesh_output(const AmbientSpace& space, const View& view);

/// Writes output.mesh_path (if given) and then output.states_path (if given) from `mesh`.
///
/// The mesh file: with every coordinate (write_mesh, options as given) if the view is
/// all coordinates, else in the view (write_mesh_in_view). The states: write_states_npy.
///
/// In one process these are the serial writers, byte for byte. A split mesh
/// (mesh.space().is_distributed()): collective, every rank calls this with the same arguments
/// and only rank 0 touches files. The view's functionals are reduced over the ranks for all
/// vertices at once (mesh_in_view); the states are streamed to rank 0 a few MB at a time
/// (write_split_states_npy); every coordinate, for n ≤ kMaxGatheredDimension, is gathered
/// whole to rank 0. If rank 0 fails to write, every rank throws.
/// \return the paths written, in order (the same on every rank).
/// \throw InvalidArgument as check_split_mesh_output (before any communication), write_mesh,
///        write_mesh_in_view and write_states_npy.
std::vector<std::string> write_mesh_output(const TriangleMesh& mesh, const MeshOutput& output);

}  // namespace tessera
