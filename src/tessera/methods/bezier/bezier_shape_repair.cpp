// SPDX-License-Identifier: MIT
// bezier's shape repair after the build: needles collapsed, caps swapped away.
#include <sstream>

#include "tessera/geometry/mesh_quality.h"
#include "tessera/methods/bezier/bezier_builder.h"
#include "tessera/methods/improvement/edge_swap.h"
#include "tessera/methods/improvement/needle_collapse.h"

namespace tessera::detail {

// Hohmann's continuation places each new point by its step control and connects it to the
// front where the softened overlap tests allow, so its triangles have angles down to 0.1° (the
// stress campaign: medians of 1°–7° per surface): needles whose short edge joins two points of
// neighbouring fronts, and caps across which the front closed. Their planes are badly
// determined, their sampled distances to M miss the worst point, and two of them crossed on a
// genus-2 surface. The triangulation is repaired after the build, with the same vertices (all
// still points of the continuation): the short edges of needles are collapsed where that keeps
// the mesh valid and improves its angles (collapse_needles), then Lawson's swaps for the largest
// smallest angle judged in M's tangent planes (improve_by_edge_swaps) remove the caps, until
// nothing changes (docs/algorithms/bezier.md, "Shape repair").
void repair_shapes(const ImplicitProblem& problem, const BezierOptions& options,
                   CoveringResult& result) {
  TriangleMesh& mesh = result.mesh;
  if (mesh.triangle_count() == 0 ||
      result.summary.termination == CoveringTermination::Interrupted) {
    return;  // a stopped run wants its mesh now, and its stop request is not asked again
  }
  const double before = measure_shape(mesh).min_angle_degrees;
  NeedleCollapseOptions collapse;
  collapse.stop_requested = options.stop_requested;
  ImprovementOptions swaps;
  swaps.stop_requested = options.stop_requested;
  int collapsed = 0;
  int swapped = 0;
  for (int round = 0; round < 4; ++round) {
    const NeedleCollapseSummary needles = collapse_needles(mesh, problem, collapse);
    // Swaps for the angles may choose a diagonal farther from M (on the torus at the default
    // step, edge midpoints 0.145 from M instead of 0.088): only where refinement to a
    // tolerance bounds the distance afterwards. The collapses keep the vertices' places.
    const ImprovementSummary swapping =
        options.tolerance > 0 ? improve_by_edge_swaps(mesh, problem, swaps) : ImprovementSummary{};
    collapsed += needles.collapsed_edges;
    swapped += swapping.swaps;
    if (needles.interrupted || swapping.interrupted ||
        (needles.collapsed_edges == 0 && round > 0)) {
      break;
    }
  }
  if (collapsed + swapped == 0) {
    return;
  }
  result.patches_need_rebuild = !result.patches.empty();
  std::ostringstream note;
  note.precision(3);
  note << "shape repair: " << collapsed << " short edge(s) of needles collapsed, " << swapped
       << " edge(s) swapped; smallest angle " << before << "° -> "
       << measure_shape(mesh).min_angle_degrees << "°";
  result.summary.notes.push_back(note.str());
}

}  // namespace tessera::detail
