// SPDX-License-Identifier: MIT
#include "tessera/methods/improvement/improve_mesh.h"

namespace tessera {

MeshImprovement improve_mesh(TriangleMesh& mesh, const ImplicitProblem& problem,
                             const ImprovementOptions& options, int smoothing_passes) {
  MeshImprovement result;
  result.swaps = improve_by_edge_swaps(mesh, problem, options);
  if (smoothing_passes > 0) {
    SmoothingOptions smoothing_options;
    smoothing_options.iterations = smoothing_passes;
    smoothing_options.measure_shapes = options.measure_shapes;
    result.smoothing = smooth_tangentially(mesh, problem, smoothing_options);
    const ImprovementSummary again = improve_by_edge_swaps(mesh, problem, options);
    result.swaps.swaps += again.swaps;
    result.swaps.sweeps += again.sweeps;
    result.swaps.converged = again.converged;
    result.swaps.interrupted = result.swaps.interrupted || again.interrupted;
    result.swaps.rejected_non_convex += again.rejected_non_convex;
    result.swaps.rejected_existing_edge += again.rejected_existing_edge;
    result.swaps.rejected_projection_failed += again.rejected_projection_failed;
    // Before the first round, after the last: the whole improvement's effect.
    result.swaps.min_angle_degrees_after = again.min_angle_degrees_after;
    result.swaps.fraction_angles_below_30_after = again.fraction_angles_below_30_after;
  }
  return result;
}

}  // namespace tessera
