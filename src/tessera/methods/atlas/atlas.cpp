// SPDX-License-Identifier: MIT
// Method `atlas` (Henderson). The covered region is the union of the charts' polygons: chart i
// owns P_i = {p in its tangent plane : |p|² − R_i² ≤ |p − p_j|² − R_j² for each neighbour j}
// (the power cell of its disk, as in Henderson's later MULTIFARIO) clipped to a square slightly
// larger than the disk. A polygon vertex outside the disk is a place the atlas does not cover
// yet; a new chart is centred on the disk boundary towards it, which always cuts it away.
// When no such vertex is left the atlas is complete, and its triangulation is the dual of the
// polygon complex: every polygon vertex where the cells of i, j, k meet is the triangle ijk.
#include "tessera/methods/atlas/atlas.h"

#include <unistd.h>

#include <Eigen/Core>
#include <algorithm>
#include <cmath>

#include "tessera/core/counted_problem.h"
#include "tessera/core/error.h"
#include "tessera/methods/atlas/atlas_builder.h"
#include "tessera/methods/atlas/atlas_triangulation.h"
#include "tessera/methods/atlas/chart_polygon.h"
#include "tessera/methods/improvement/edge_swap.h"
#include "tessera/methods/improvement/improve_mesh.h"
#include "tessera/methods/start_point.h"

namespace tessera {

double default_factorisation_budget() {
  constexpr double minimum = 2.0 * 1024 * 1024 * 1024;
  const long pages = sysconf(_SC_PHYS_PAGES);
  const long page_size = sysconf(_SC_PAGE_SIZE);
  if (pages <= 0 || page_size <= 0) {
    return minimum;
  }
  return std::max(minimum, 0.25 * static_cast<double>(pages) * static_cast<double>(page_size));
}

void AtlasOptions::validate() const {
  validate_common("AtlasOptions");
  TESSERA_CHECK(tolerance > 0, "AtlasOptions::tolerance = "
                                   << tolerance << " must be > 0: the chart radii are sized by it");
  TESSERA_CHECK(chart_tolerance == 0 || chart_tolerance >= tolerance,
                "AtlasOptions::chart_tolerance = "
                    << chart_tolerance << " must be 0 or >= the tolerance " << tolerance
                    << ": charts sized for a finer tolerance than the mesh's are wasted");
  TESSERA_CHECK(hexagonal_side >= 1.0 && hexagonal_side <= 1.9,
                "AtlasOptions::hexagonal_side = " << hexagonal_side << " must lie in [1, 1.9]");
  TESSERA_CHECK(radius_growth >= 1.0 && radius_growth <= 4.0,
                "AtlasOptions::radius_growth = " << radius_growth << " must lie in [1, 4]");
  TESSERA_CHECK(
      max_turning_angle > 0 && max_turning_angle <= 1.0,
      "AtlasOptions::max_turning_angle = " << max_turning_angle << " must lie in (0, 1] radians");
  TESSERA_CHECK(min_sheet_cosine >= 0 && min_sheet_cosine < 1,
                "AtlasOptions::min_sheet_cosine = " << min_sheet_cosine << " must lie in [0, 1)");
  TESSERA_CHECK(domain_margin >= 0 && domain_margin <= 4,
                "AtlasOptions::domain_margin = " << domain_margin << " must lie in [0, 4]");
  TESSERA_CHECK(max_factorisation_bytes >= 0,
                "AtlasOptions::max_factorisation_bytes = " << max_factorisation_bytes
                                                            << " must be >= 0");
  TESSERA_CHECK(
      min_radius_fraction > 0 && min_radius_fraction < 1,
      "AtlasOptions::min_radius_fraction = " << min_radius_fraction << " must lie in (0, 1)");
}

namespace {

using detail::AtlasBuilder;

// Tangential smoothing after the hexagonal placement (see build_atlas).
constexpr int kHexagonalSmoothingPasses = 1;

// The median radius of the charts outside or within one radius of ∂S; −1 if there are none.
double median_boundary_radius(const Domain& domain, const AtlasBuilder& builder) {
  std::vector<double> boundary_radii;
  for (int c = 0; c < builder.chart_count(); ++c) {
    if (domain.boundary_distance(builder.center(c)).signed_distance < builder.chart(c).radius) {
      boundary_radii.push_back(builder.chart(c).radius);
    }
  }
  if (boundary_radii.empty()) {
    return -1.0;
  }
  std::nth_element(boundary_radii.begin(), boundary_radii.begin() + boundary_radii.size() / 2,
                   boundary_radii.end());
  return boundary_radii[boundary_radii.size() / 2];
}

// The atlas and its triangulation; the skeleton (covering.h) clips it to the domain, refines
// it to the tolerance and validates it.
void build_atlas(CoveringContext& context, const AtlasOptions& given, CoveringResult& result) {
  AtlasOptions options = given;
  if (context.attempt > 0) {
    // Charts snapped onto ∂S can leave the clipping a configuration it refuses (seen where M
    // meets a face at a shallow angle); the second attempt does without snapping.
    options.boundary_snap = 0.0;
    // Its checkpoints would hold another build than the first attempt's, which a resumed run
    // starts with: a run killed now is continued from the first attempt's last checkpoint.
    options.checkpoint = {};
  }
  if (options.chart_tolerance > 0) {
    // The builder sizes its charts by options.tolerance; the skeleton refines to the given one.
    options.tolerance = options.chart_tolerance;
  }
  CoveringSummary& summary = result.summary;
  AtlasBuilder builder(context.problem, context.domain, options);
  builder.run(context.start.x, summary);

  // The mesh: the dual of the polygons, with the places where the charts disagree closed.
  AtlasCells cells = builder.cells();
  cells.take_centers = [&builder](const std::vector<bool>& keep) {
    return builder.take_centers(keep);
  };
  // What the boundary needs of the charts, measured before their centres become the mesh's.
  double boundary_scale = -1.0;
  if (!context.domain.is_unbounded()) {
    boundary_scale = median_boundary_radius(context.domain, builder);
  }
  AtlasTriangulation triangulation = triangulate_atlas(cells);
  result.mesh = std::move(triangulation.mesh);
  summary.filled_holes = triangulation.filled_holes;
  summary.placement = options.placement == AtlasPlacement::Hexagonal ? "hexagonal" : "disk";
  if (!triangulation.message.empty() && summary.is_complete()) {
    summary.termination = CoveringTermination::TriangulationFailed;
    summary.message = triangulation.message;
  }
  double min_radius = options.step;
  double max_radius = 0.0;
  for (int c = 0; c < builder.chart_count(); ++c) {
    min_radius = std::min(min_radius, builder.chart(c).radius);
    max_radius = std::max(max_radius, builder.chart(c).radius);
  }
  summary.min_chart_radius = min_radius;
  summary.max_chart_radius = max_radius;
  summary.step = max_radius;

  if (options.placement == AtlasPlacement::Hexagonal && result.mesh.triangle_count() > 0) {
    // One pass of smoothing: three cost 6 more evaluations of F per vertex for 1–2° more of
    // smallest angle (torus at 1e-3: 28.7° after one pass, 30.7° after three; V·H the same).
    ImprovementOptions improvement;
    improvement.measure_shapes = false;  // the summary is not kept
    improve_mesh(result.mesh, context.problem, improvement, kHexagonalSmoothingPasses);
  } else if (options.swap_edges && result.mesh.triangle_count() > 0) {
    ImprovementOptions swaps;
    improve_by_edge_swaps(result.mesh, context.problem, swaps);
  }
  if (!context.domain.is_unbounded()) {
    // Snap and collapse lengths follow the charts near the boundary: the median radius of the
    // charts outside or within one radius of ∂S. Clipping leaves poor angles at ∂S that
    // Delaunay swaps in the tangent planes repair (the interior is a weighted Delaunay
    // triangulation already; measured: cut sphere 22° → 28°).
    context.boundary_edge_length = boundary_scale > 0 ? boundary_scale : min_radius;
    context.swap_after_clipping = true;
    context.retry_if_clipping_fails = options.boundary_snap > 0;
  }
  summary.notes.emplace_back(kStartComponentNote);
}

}  // namespace

CoveringResult cover_by_atlas(const ImplicitProblem& problem, const Eigen::VectorXd& start,
                              const Domain& domain, const AtlasOptions& options) {
  options.validate();
  return run_covering("atlas", problem, start, domain, options,
                      [&options](CoveringContext& context, CoveringResult& result) {
                        build_atlas(context, options, result);
                      });
}

}  // namespace tessera
