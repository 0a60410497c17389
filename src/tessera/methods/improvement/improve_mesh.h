// SPDX-License-Identifier: MIT
// The improvement pipeline used by `tessera improve` and `tessera mesh --improve`.
#pragma once

#include "tessera/methods/improvement/edge_swap.h"
#include "tessera/methods/improvement/tangential_smoothing.h"

namespace tessera {

struct MeshImprovement {
  /// Both rounds of swaps, added up; its before/after measures are the mesh's before the first
  /// round and after the last.
  ImprovementSummary swaps;
  SmoothingSummary smoothing;   ///< empty when no smoothing passes were asked for
};

/// Edge swaps; then, if smoothing_passes > 0, that many passes of tangential smoothing and a
/// second round of swaps (the moved vertices can make other diagonals better).
MeshImprovement improve_mesh(TriangleMesh& mesh, const ImplicitProblem& problem,
                             const ImprovementOptions& options, int smoothing_passes);

}  // namespace tessera
