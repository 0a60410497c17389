// SPDX-License-Identifier: MIT
// Edge bisection on M until sampled points of the chosen triangles lie within a distance of M.
#pragma once

#include <functional>
#include <vector>

#include "tessera/core/corrector.h"
#include "tessera/core/domain.h"
#include "tessera/core/implicit_problem.h"
#include "tessera/geometry/triangle_mesh.h"

namespace tessera {

struct ToleranceRefinementOptions {
  /// A triangle is split if its centroid, an edge midpoint or its circumcentre (when inside)
  /// lies farther than tolerance·sample_safety from M.
  double tolerance = 1e-3;
  /// The samples include the farthest point of a triangle on a surface of constant curvature
  /// (the circumcentre, or a midpoint for obtuse triangles); 0.97 covers the rest.
  double sample_safety = 0.97;
  /// Each round bisects the longest edge of every triangle still too far; a flat triangle's
  /// distance to M scales like its edge length squared, so two rounds divide it by about 4 and
  /// 12 rounds by about 4000.
  int max_rounds = 12;
  /// Points within this of a domain face count as lying on it (boundary edges stay on ∂S).
  double face_tolerance = 1e-8;
  CorrectorOptions corrector;
  /// Polled once per triangle checked on one thread, once per block of anchor groups (1024
  /// a thread) on several, always on the calling thread; true stops the refinement between two
  /// checks, with the mesh as valid as it was (ToleranceRefinement::interrupted). Empty: never
  /// stopped.
  std::function<bool()> stop_requested;
};

struct ToleranceRefinement {
  int rounds = 0;
  int split_edges = 0;
  int remaining = 0;  ///< triangles still above the threshold after max_rounds
  /// Their indices in the mesh returned, ascending (remaining of them).
  std::vector<int> far_triangles;
  /// stop_requested said so: the triangles not yet checked were left as they were, and
  /// remaining and max_distance speak only of those checked.
  bool interrupted = false;
  /// The largest sampled distance to M over the triangles checked last (all candidates and
  /// their offspring); +infinity if a sample could not be projected.
  double max_distance = 0.0;
  /// The same over the triangles checked that are within the threshold: the bound of the mesh
  /// once far_triangles are removed.
  double max_distance_within = 0.0;
  /// The sample where the distance is largest among the triangles still above the threshold
  /// (empty if remaining == 0), for messages.
  Eigen::VectorXd worst_point;
};

/// For the triangles whose index is in `candidates` (all if empty), and for the triangles made
/// by splitting them: samples the centroid and the edge midpoints, projects them onto M, and
/// bisects the longest edge of every triangle that is too far from M. The new vertex is the
/// midpoint projected onto M, or onto M ∩ face for an edge lying on a domain face, so the
/// boundary stays on ∂S. Neighbours across a split edge are split with it (the mesh stays
/// conforming, valid and oriented as it was).
///
/// A split mesh (TriangleMesh::set_space: this rank's rows of every vertex) of a distributed
/// problem, with the domain cut to the same rows (Domain::distributed), is refined as in one
/// process: every rank calls this alike, and each pass over the triangles reduces its
/// measures at once (their Gram numbers, the faces' distances of the edges to split, the
/// sides of the quadrilaterals to cut), so that every rank takes the same decisions.
/// \throw InvalidArgument if the mesh does not hold the problem's rows (check_mesh_of_problem)
///        or the domain not the mesh's.
ToleranceRefinement refine_to_tolerance(const ImplicitProblem& problem, const Domain& domain,
                                        TriangleMesh& mesh, std::vector<int> candidates,
                                        const ToleranceRefinementOptions& options);

}  // namespace tessera
