// SPDX-License-Identifier: MIT
// Method `atlas`: Henderson's covering of M by charts (disks in tangent planes) whose radii
// follow the curvature, kept as polygons cut by their neighbours; the mesh is the dual of the
// polygon complex. See docs/algorithms/atlas.md for the algorithm and where tessera differs.
#pragma once

#include <Eigen/Core>

#include "tessera/core/corrector.h"
#include "tessera/core/domain.h"
#include "tessera/core/implicit_problem.h"
#include "tessera/methods/atlas/atlas_checkpoint.h"
#include "tessera/methods/covering.h"

namespace tessera {

/// Where a new chart is centred, relative to the uncovered corner of its parent's polygon.
enum class AtlasPlacement {
  /// Henderson's: on the parent's disk boundary, towards the corner. All angles stay near or
  /// above 30° without post-processing; about twice the vertices of an ideal mesh.
  Disk,
  /// Towards a hexagonal packing (centres about 1.5 R apart): about 30 % fewer vertices. The
  /// mesh is then improved (Delaunay swaps and one pass of tangential smoothing on M) and
  /// every triangle is checked against the tolerance and bisected where needed.
  Hexagonal,
};

/// A quarter of the physical memory of this machine (sysconf), and at least 2 GiB: the bytes
/// the atlas may spend on factorisations kept for its queued charts by default.
double default_factorisation_budget();

/// The atlas's own options; the shared ones (tolerance, step = the largest chart radius,
/// max_vertices, max_start_distance, corrector, progress) are in CoveringOptions.
struct AtlasOptions : CoveringOptions {
  /// ε defaults to 1e-3 (every point of every triangle within it of M; chart radii are
  /// R = sqrt(2ε/κ) with κ the largest normal curvature at the centre, section 2.4); the step
  /// is the largest chart radius, used where M is flat.
  AtlasOptions() {
    tolerance = 1e-3;
    step = 0.5;
  }
  /// Where new charts are centred (see AtlasPlacement).
  AtlasPlacement placement = AtlasPlacement::Disk;
  /// Hexagonal placement: the side of the triangles it aims for, in radii (√3 ≈ 1.73 would be
  /// the densest covering; 1.5 leaves room for the irregularity of a growing atlas).
  double hexagonal_side = 1.5;
  /// A chart's radius is at most this factor times its parent's, so that the triangles between
  /// charts of different sizes keep good angles.
  double radius_growth = 1.5;
  /// κR ≤ this (radians): the tangent planes of overlapping charts differ by at most about
  /// twice this angle, which keeps the tangent-plane projections one-to-one and the power
  /// diagrams that neighbouring charts see in their own planes alike (0.5 left holes on cstr
  /// at tolerance 0.03, where M turns fast near x1 = 1; issue 10).
  double max_turning_angle = 0.35;
  /// Overlapping charts whose tangent planes have |det(T_iᵀT_j)| below this lie on different
  /// sheets of M (a transversal crossing, section 8) and are never glued.
  double min_sheet_cosine = 0.35;
  /// Where the domain is bounded, charts are continued up to this many radii outside it, so
  /// that the mesh covers M ∩ S before it is clipped to ∂S.
  double domain_margin = 1.0;
  /// Chart centres closer than this many radii to a face of the domain are moved onto
  /// M ∩ face, giving a row of charts on ∂S (0 disables; clipping then does all the work).
  double boundary_snap = 0.45;
  /// Radii below step·this mean the corrector cannot converge: ProjectionFailed.
  double min_radius_fraction = 1.0 / 4096.0;
  /// Delaunay-type edge swaps in the tangent planes after the mesh is assembled. Off: the dual
  /// of the power cells is already a weighted Delaunay triangulation, and measured swaps
  /// changed nothing on the catalogue while costing 2× the run time.
  bool swap_edges = false;
  /// The factorisations of the charts waiting in the queue are kept until the chart projects
  /// its children, at most this many bytes of them (the newest are dropped first and factored
  /// again when their turn comes). At n = 10⁴ on a 2-D grid one factorisation holds about
  /// 10 MB, at n = 10⁵ about 120 MB, and the boundary of an atlas a few hundred charts, so
  /// without a bound the boundary alone would outgrow the machine; with too small a bound most
  /// charts are factored twice (bratu2d:N=316 with 2 GiB: 256 of 422). Default: a quarter of
  /// the machine's physical memory, at least 2 GiB (default_factorisation_budget).
  double max_factorisation_bytes = default_factorisation_budget();
  /// The charts are sized for this tolerance instead of `tolerance` (0: `tolerance`); the
  /// refinement then bisects every triangle until it meets `tolerance`. `tessera extend
  /// --tolerance` sets it to the tolerance of the atlas it continues, whose charts it keeps.
  /// \pre 0 or ≥ tolerance (charts sized finer than the tolerance asks are wasted).
  double chart_tolerance = 0.0;
  /// A chart whose parent's factorisation reaches it solves with that factorisation instead of
  /// factoring DF at its own centre (Linearization::borrow): its tangent plane is still the
  /// exact ker DF there (tangent_basis_near), its projections still end on M with the exact F;
  /// only their chord contracts a little slower. Where the tangent iteration from the parent's
  /// factorisation does not converge within a few steps, the chart factors its own. Sparse
  /// problems only (where a factorisation costs many solves), and not with checkpoints (whose
  /// resumed builds re-make each kept factorisation at its chart). Issue 30.
  bool share_factorisations = true;
  /// Checkpoints of the build and continuing from one (off by default).
  AtlasCheckpointing checkpoint;

  /// \throw InvalidArgument naming the first option out of range.
  void validate() const;
};

/// Covers the component of M ∩ S containing (the projection of) `start` with an atlas of
/// charts and returns its triangulation, clipped to the domain.
///
/// \param start n-vector near M. \param domain S; if unbounded, M must be closed and bounded
///        (or the run ends at max_vertices).
/// Runs the shared skeleton (covering.h): clipping, refinement to options.tolerance and the
/// geometric validation are done there.
/// \return a valid mesh whatever the termination: complete when summary.termination is
///         Completed, partial otherwise (the summary says where and why, StartFailed included).
/// \throw InvalidArgument for bad options or sizes.
CoveringResult cover_by_atlas(const ImplicitProblem& problem, const Eigen::VectorXd& start,
                              const Domain& domain, const AtlasOptions& options);

}  // namespace tessera
