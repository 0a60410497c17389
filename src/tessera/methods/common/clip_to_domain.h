// SPDX-License-Identifier: MIT
// Clipping a mesh of M to a polyhedral domain so that its boundary lies on M ∩ ∂S.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "tessera/core/corrector.h"
#include "tessera/core/face_projection.h"
#include "tessera/core/domain.h"
#include "tessera/core/implicit_problem.h"
#include "tessera/geometry/triangle_mesh.h"

namespace tessera {

struct ClipOptions {
  /// Vertices closer than this to a face are moved onto M ∩ face before cutting; cut points
  /// then stay at least this far from every kept vertex, so no needle triangles appear.
  double snap_distance = 0.0;
  /// Boundary edges shorter than this are collapsed after clipping (where two faces meet, a
  /// cut can still leave a vertex a hair from a corner); 0 disables.
  double min_boundary_edge = 0.0;
  CorrectorOptions corrector;
  /// Polled before every projection onto a face (at large n each costs a factorisation or a
  /// few solves). A stop ends the clipping without more projections: the face being clipped
  /// and those left are cut by removing the triangles outside them (as when a face cannot be
  /// clipped), so the mesh stays valid and inside S; its boundary there is ragged.
  std::function<bool()> stop_requested;
};

struct ClipSummary {
  int half_spaces_crossed = 0;  ///< faces the mesh crossed and was clipped to
  int snapped_vertices = 0;
  int cut_edges = 0;
  int collapsed_edges = 0;  ///< short boundary edges collapsed after clipping
  /// Non-empty if a face could not be clipped: the triangles across it were removed instead
  /// (the mesh stays valid and inside S; its boundary there is not on M ∩ ∂S). Names the place.
  std::string message;
  bool interrupted = false;  ///< stop_requested ended the clipping (see ClipOptions)
};

/// Clips `mesh` (vertices on M) to S = ∩ half-spaces, one face at a time ("snap, then cut"):
///  1. vertices within snap_distance of the face are projected onto M ∩ face (Gauss–Newton on
///     F = 0, b·(x − p) = 0, plus the faces the vertex already lies on);
///  2. each edge that still crosses the face gets a cut point on M ∩ face, started from the
///     linear interpolant (edges lying on an earlier face stay on it);
///  3. triangles are split along the cut (quadrilaterals by the diagonal of larger minimum
///     angle) and the parts outside are dropped, with the vertices no longer used.
/// Every snap, cut and collapse keeps the orientation of the triangles it reshapes (checked in
/// the tangent plane of M) or is not made; vertices within 1e-9·(1 + |x|) of a face count as on
/// it; boundary vertices are put on their faces exactly (place_on_faces), so no vertex of the
/// result lies outside S. See docs/algorithms/front.md, *Boundary*.
/// This resolves what Brodzik & Rheinboldt leave open ("adjust the exterior points onto the
/// boundary"): the boundary of the result lies on M ∩ ∂S up to the corrector tolerance, and
/// snapping before cutting keeps cut points away from vertices, so no needles are created.
ClipSummary clip_to_domain(const ImplicitProblem& problem, const Domain& domain, TriangleMesh& mesh,
                           const ClipOptions& options);

}  // namespace tessera
