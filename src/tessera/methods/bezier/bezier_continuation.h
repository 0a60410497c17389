// SPDX-License-Identifier: MIT
// Method `bezier`: Hohmann's adaptive continuation for implicitly defined surfaces (1991), with
// Gauss–Newton step control and the nine-parameter cubic Bézier interpolant as predictor.
// See docs/algorithms/bezier.md for the algorithm, the paper-to-code table and the deviations.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "tessera/core/domain.h"
#include "tessera/core/implicit_problem.h"
#include "tessera/geometry/bezier_patch.h"
#include "tessera/methods/covering.h"

namespace tessera {

/// Every constant of the method. Defaults are the paper's values where the paper gives one
/// (section and equation in the comment), otherwise tessera's choice with its reason.
/// The shared options are in CoveringOptions: step is s of the initial triangle (tangent
/// continuation from the first solution), tolerance ε (see below), corrector the Gauss–Newton
/// stopping rule of every vertex.
struct BezierOptions : CoveringOptions {
  /// Upper bound on any step. The paper has none; without one a flat region (θ ≈ 0) would let
  /// s grow without limit. 0 means 8 × step.
  double max_step = 0.0;
  /// Steps below min_step_fraction × step are not tried: the edge cannot be realised.
  double min_step_fraction = 1.0 / 64.0;
  /// θ̄ of section 2/5: the target contraction of the first Gauss–Newton step; the predictor is
  /// s = min(√(θ̄/θ_j) s_j, √(θ̄/θ_k) s_k). Paper: 0.25 (as in ALCON).
  double target_contraction = 0.25;
  /// The growth factor √(θ̄/θ) is capped here (θ ≈ 0 on flat or quadratic problems would
  /// give an unbounded factor). ALCON-style codes cap the increase at 2; the paper is silent.
  double max_step_growth = 2.0;
  /// Natural monotonicity test (2.3): a first contraction θ₀ above this rejects the point and
  /// the step is reduced by √(θ̄/θ₀). Paper: 1/2.
  double max_contraction = 0.5;
  /// α_min of section 4: |⟨t_ij, t_ji⟩| ≥ α_min on every real and imaginary edge, i.e. the
  /// tangent planes at the ends of an edge differ by at most arccos(0.8) ≈ 36.9°. Paper: 0.8.
  double min_tangent_cosine = 0.8;
  /// ρ of section 5: the barycentric overlap tests are softened to λ ≥ −ρ. Paper: 0.3.
  double overlap_safety = 0.3;
  /// β of section 5: width of the connection sector S. Paper: 1.5.
  double connection_sector = 1.5;
  /// l_ij = edge_length_factor·‖y_j − y_i‖ in eq. 3.4. The paper (after Farin) uses 1.2, which
  /// makes the interpolant only O(h²) accurate; 1.0 matches the arc length to leading order and
  /// gives O(h⁴) on the sphere (measured, docs/algorithms/bezier.md). tessera's default: 1.0.
  double edge_length_factor = 1.0;
  /// Steps are multiplied by this when an imaginary or real triangle violates α_min or an
  /// overlap cannot be resolved. The paper only says "reduce"; halving is the usual choice.
  double step_reduction = 0.5;
  /// An existing front vertex closer than this fraction of s to the predicted vertex is taken
  /// instead of computing a new point (avoids tiny edges; tessera's addition to section 4).
  double close_vertex_fraction = 0.5;
  /// A new vertex within this fraction of s of a domain face is moved onto M ∩ face, so that
  /// no sliver is left between it and the boundary (tessera's choice; the paper only fixes a
  /// coordinate for points outside the box).
  double boundary_snap_fraction = 0.3;
  // tolerance ε > 0 (CoveringOptions): the distance to M of the midpoints of new edges
  // (estimated by one simplified Gauss–Newton step) is kept ≤ ε by reducing s, and the next
  // steps are limited by s·√(ε/d) (a flat triangle's distance to M grows like s²); the skeleton
  // then checks every triangle and bisects where the estimate was short. 0: the paper's
  // control only.

  /// \throw InvalidArgument naming the first option that is out of range.
  void validate() const;
};

/// Covers the component of M ∩ S containing (the projection of) `start` by Hohmann's method.
///
/// \param start n-vector near M; \param domain S: unbounded (then M must be closed and bounded)
///        or a polyhedron; on its faces points are computed on M ∩ face (paper, example 3).
/// \return the mesh, the patches (one per triangle, patches[t] over mesh.triangle(t) in its
///         vertex order; neighbours share their edge curves) and a summary. When an imaginary
///         triangle cannot be realised the run stops (summary.termination, summary.message says
///         where and why) and the mesh built so far is returned, cleaned to be valid; a start
///         or initial triangle that cannot be built ends with StartFailed.
/// \throw InvalidArgument for bad options or sizes.
/// \see Hohmann, An adaptive continuation method for implicitly defined surfaces, ZIB SC 91-20.
CoveringResult triangulate_by_bezier_continuation(const ImplicitProblem& problem,
                                                  const Eigen::VectorXd& start,
                                                  const Domain& domain,
                                                  const BezierOptions& options);

}  // namespace tessera
