// SPDX-License-Identifier: MIT
// Mesh improvement on M: tangential smoothing that moves interior vertices toward the average of
// their neighbours within the tangent plane of M and projects them back onto M.
#pragma once

#include <string>

#include "tessera/core/implicit_problem.h"
#include "tessera/geometry/triangle_mesh.h"

namespace tessera {

struct SmoothingOptions {
  /// Passes over all interior vertices.
  int iterations = 3;
  /// ω: a vertex x moves to x + ω·T Tᵀ(x̄ − x) before projection, x̄ the average of its
  /// neighbours, T the n×2 tangent basis at x. 0.5 damps the oscillation of plain Laplacian
  /// smoothing (ω = 1) on irregular stars.
  double relaxation = 0.5;
  /// A move is refused if a triangle of the star would have |signed area| ≤ ratio·(longest
  /// edge)² in the tangent plane, as in ImprovementOptions::min_area_ratio.
  double min_area_ratio = 1e-6;
  /// Refuse a move that lowers the smallest angle of the vertex's star ("smart" Laplacian), so
  /// that the mesh's minimum angle never drops. false: plain Laplacian (folds are still refused).
  bool keep_min_angle = true;
  /// Measure the smallest angle before and after for the summary (a pass over the triangles
  /// each), as ImprovementOptions::measure_shapes.
  bool measure_shapes = true;

  /// \throw InvalidArgument naming the first option that is out of range.
  void validate() const;
};

struct SmoothingSummary {
  int iterations = 0;
  int moves = 0;                ///< accepted vertex moves, summed over the passes
  int rejected_fold = 0;        ///< a triangle of the star would flip or degenerate
  int rejected_angle = 0;       ///< the star's smallest angle would drop
  int rejected_projection = 0;  ///< the moved point could not be projected onto M
  double min_angle_degrees_before = 0.0;
  double min_angle_degrees_after = 0.0;
  /// e.g. "140 moves in 3 passes; min angle 23.1° -> 26.0°".
  std::string brief_report() const;
};

/// Smart Laplacian smoothing on M. Every vertex that is not on the boundary (nor on a
/// non-manifold edge) is moved toward the average of its neighbours within the tangent plane at
/// it, then projected onto M with project_gauss_newton (so vertices stay on M to the corrector's
/// tolerance). A move is kept only if every triangle of the vertex's star keeps its orientation
/// and stays non-degenerate in the tangent planes at the old and at the new position, and (with
/// keep_min_angle) the smallest angle of the star (in Rⁿ) does not drop; so the mesh's minimum
/// angle never drops and a valid mesh stays valid, with the same triangles and boundary. The
/// problem's domain is not consulted: interior vertices move within their star. \pre
/// mesh.ambient_dimension() == problem.ambient_dimension() (else InvalidArgument).
SmoothingSummary smooth_tangentially(TriangleMesh& mesh, const ImplicitProblem& problem,
                                     const SmoothingOptions& options = {});

}  // namespace tessera
