// SPDX-License-Identifier: MIT
// Method `front`: Brodzik & Rheinboldt's advancing-front simplicial approximation (PITMAN).
// See docs/algorithms/front.md for the algorithm, where tessera differs from the paper and why.
#pragma once

#include <Eigen/Core>

#include "tessera/core/domain.h"
#include "tessera/core/implicit_problem.h"
#include "tessera/methods/covering.h"
#include "tessera/methods/front/front_checkpoint.h"

namespace tessera {

/// The order in which frontal vertices are processed.
enum class FrontOrder {
  /// The paper's: a FIFO queue of frontal points. Neighbouring fans then overlap locally and
  /// are repaired by merges; on some surfaces (elongated or saddle-shaped) the repairs fail.
  Fifo,
  /// Smallest gap angle first (the usual advancing-front rule): small gaps are closed before
  /// their neighbours add points over them, which avoids most overlaps. tessera's default.
  SmallestGapFirst,
};

/// The front's own options; the shared ones are in CoveringOptions: step is h, the edge length
/// of the projected hexagons (paper: "suggested step"); tolerance, when > 0, bounds the
/// distance of the finished mesh to M by bisection (the front's steps do not depend on it).
struct FrontOptions : CoveringOptions {
  /// α_min: gaps below this are closed by merging the two open edges; sectors are never made
  /// narrower than this. 0.8 rad (46°): sectors then lie in [46°, 92°) around the ideal 60°.
  double min_gap_angle = 0.8;
  /// The paper's limit of 6 triangles per vertex (its `nod` array has six columns).
  int max_valence = 7;
  /// Step halving stops below step·min_step_fraction with ProjectionFailed (paper: "too small").
  double min_step_fraction = 1.0 / 64.0;
  /// A new point closer than this fraction of h to a vertex that is not its neighbour means the
  /// front meets itself: FrontCollision, reported with the location.
  double collision_distance_fraction = 0.5;
  /// Vertices within this fraction of h of a domain face are snapped onto it when clipping, so
  /// that no needle triangles appear at the boundary (see clip_to_domain).
  double boundary_snap_fraction = 0.35;
  FrontOrder order = FrontOrder::SmallestGapFirst;
  /// Checkpoints of the build and the state to continue (front_checkpoint.h).
  FrontCheckpointing checkpoint;

  /// \throw InvalidArgument naming the first option that is out of range.
  void validate() const;
};

/// Covers the component of M ∩ S that contains (the projection of) `start` by PITMAN.
///
/// \param start n-vector near M; \param domain S (unbounded: M must be closed and bounded).
/// Runs the shared skeleton (covering.h), which clips, refines and validates.
/// \return the mesh (valid even when the run stops early: see summary.termination, StartFailed
///         included) and a summary.
/// \throw InvalidArgument for bad options or sizes.
CoveringResult triangulate_by_front(const ImplicitProblem& problem, const Eigen::VectorXd& start,
                                    const Domain& domain, const FrontOptions& options);

}  // namespace tessera
