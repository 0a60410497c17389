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
    result.smoothing = smooth_tangentially(mesh, problem, smoothing_options);
    const ImprovementSummary again = improve_by_edge_swaps(mesh, problem, options);
    result.swaps.swaps += again.swaps;
    result.swaps.sweeps += again.sweeps;
    result.swaps.converged = again.converged;
  }
  return result;
}

}  // namespace tessera
