// SPDX-License-Identifier: MIT
// Method `atlas` (Henderson). The covered region is the union of the charts' polygons: chart i
// owns P_i = {p in its tangent plane : |p|² − R_i² ≤ |p − p_j|² − R_j² for each neighbour j}
// (the power cell of its disk, as in Henderson's later MULTIFARIO) clipped to a square slightly
// larger than the disk. A polygon vertex outside the disk is a place the atlas does not cover
// yet; a new chart is centred on the disk boundary towards it, which always cuts it away.
// When no such vertex is left the atlas is complete, and its triangulation is the dual of the
// polygon complex: every polygon vertex where the cells of i, j, k meet is the triangle ijk.
#include "tessera/methods/atlas/atlas.h"

#include <Eigen/Core>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <sstream>

#include "tessera/core/counted_problem.h"
#include "tessera/core/describe.h"
#include "tessera/core/error.h"
#include "tessera/core/linearization.h"
#include "tessera/geometry/mesh_topology.h"
#include "tessera/methods/atlas/atlas_builder.h"
#include "tessera/methods/atlas/atlas_triangulation.h"
#include "tessera/methods/atlas/chart_polygon.h"
#include "tessera/methods/common/clip_to_domain.h"
#include "tessera/methods/common/refine_to_tolerance.h"
#include "tessera/methods/improvement/edge_swap.h"
#include "tessera/methods/improvement/improve_mesh.h"
#include "tessera/methods/start_point.h"

namespace tessera {

void AtlasOptions::validate() const {
  TESSERA_CHECK(std::isfinite(tolerance) && tolerance > 0,
                "AtlasOptions::tolerance = " << tolerance << " must be a finite number > 0");
  TESSERA_CHECK(std::isfinite(max_radius) && max_radius > 0,
                "AtlasOptions::max_radius = " << max_radius << " must be a finite number > 0");
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
  TESSERA_CHECK(
      min_radius_fraction > 0 && min_radius_fraction < 1,
      "AtlasOptions::min_radius_fraction = " << min_radius_fraction << " must lie in (0, 1)");
  TESSERA_CHECK(max_start_distance >= 0,
                "AtlasOptions::max_start_distance = " << max_start_distance << " must be >= 0");
  TESSERA_CHECK(max_vertices >= 3,
                "AtlasOptions::max_vertices = " << max_vertices << " must be at least 3");
}

namespace {

using detail::AtlasBuilder;

// Bisects the listed triangles (and their offspring) until sampled points lie within ε of M.
int refine_where(const ImplicitProblem& problem, const Domain& domain, TriangleMesh& mesh,
                 const std::vector<int>& triangles, const AtlasOptions& options) {
  if (triangles.empty()) {
    return 0;
  }
  ToleranceRefinementOptions refine;
  refine.tolerance = options.tolerance;
  refine.corrector = options.corrector;
  return refine_to_tolerance(problem, domain, mesh, triangles, refine).split_edges;
}

// Post-condition of a completed run, checked rather than assumed: on a closed surface the mesh
// has no boundary; in a bounded domain every boundary edge lies on ∂S, i.e. both its ends lie
// on one face or on two adjacent ones (a corner). (Both ends on ∂S is not enough: where M ∩ S is a
// band narrower than the charts, an edge can run across the band from one face to the opposite one,
// and a missing row of triangles there cuts the mesh in two with every boundary vertex on ∂S; seen
// on bvp:points=1000.) Anything else is a hole in the covering, reported with its place.
void check_coverage(const Domain& domain, const TriangleMesh& mesh, CoveringSummary& summary) {
  if (!summary.is_complete()) {
    return;
  }
  const MeshTopology topology(mesh);
  const double tolerance = 1e-6 * (1.0 + summary.max_chart_radius);
  const int faces = domain.is_unbounded() ? 0 : static_cast<int>(domain.half_spaces().size());
  for (int e : topology.boundary_edges()) {
    const int v = topology.edge(e)[0];
    const int w = topology.edge(e)[1];
    // Both ends on one face, or on two adjacent faces (an edge that cuts a corner of S, left
    // by the clipping); never on two opposite faces (normals at more than 120°).
    bool on_boundary = false;
    for (int k = 0; k < faces && !on_boundary; ++k) {
      if (std::abs(domain.signed_distance(k, mesh.point(v))) > tolerance) {
        continue;
      }
      for (int l = 0; l < faces && !on_boundary; ++l) {
        const auto& nk = domain.half_spaces()[k].normal;
        const auto& nl = domain.half_spaces()[l].normal;
        on_boundary = std::abs(domain.signed_distance(l, mesh.point(w))) <= tolerance &&
                      nk.dot(nl) > -0.5 * nk.norm() * nl.norm();
      }
    }
    if (!on_boundary) {
      summary.termination = CoveringTermination::TriangulationFailed;
      summary.message = "the mesh has a hole: its boundary edge from " +
                        describe_point(mesh.point(v)) + " to " + describe_point(mesh.point(w)) +
                        (domain.is_unbounded() ? " lies on M, which is closed"
                                               : " does not lie on one face of the domain");
      return;
    }
  }
}

CoveringResult cover_once(CountedProblem& problem, const StartPoint& start_point,
                          const Domain& domain, const AtlasOptions& options,
                          bool& clipping_failed) {
  CoveringResult result;
  CoveringSummary& summary = result.summary;
  summary.method = "atlas";
  summary.tolerance = options.tolerance;
  AtlasBuilder builder(problem, domain, options);
  builder.run(start_point.x, summary);

  // The mesh: the dual of the polygons, with the places where the charts disagree closed.
  AtlasCells cells;
  cells.ambient_dimension = problem.ambient_dimension();
  cells.chart_count = builder.chart_count();
  cells.center = [&builder](int c) { return Eigen::VectorXd(builder.center(c)); };
  cells.tangent = [&builder](int c) { return Eigen::MatrixXd(builder.tangent(c)); };
  cells.polygon = [&builder](int c) -> const ChartPolygon& { return builder.chart(c).polygon; };
  cells.radius = [&builder](int c) { return builder.chart(c).radius; };
  cells.is_closed = [&builder](int c) { return builder.is_closed(c); };
  AtlasTriangulation triangulation = triangulate_atlas(cells);
  result.mesh = std::move(triangulation.mesh);
  summary.filled_holes = triangulation.filled_holes;
  if (!triangulation.message.empty() && summary.is_complete()) {
    summary.termination = CoveringTermination::TriangulationFailed;
    summary.message = triangulation.message;
  }
  double min_radius = options.max_radius;
  double max_radius = 0.0;
  for (int c = 0; c < builder.chart_count(); ++c) {
    min_radius = std::min(min_radius, builder.chart(c).radius);
    max_radius = std::max(max_radius, builder.chart(c).radius);
  }
  summary.min_chart_radius = min_radius;
  summary.max_chart_radius = max_radius;
  summary.step = max_radius;

  if (options.placement == AtlasPlacement::Hexagonal && result.mesh.triangle_count() > 0) {
    improve_mesh(result.mesh, problem, ImprovementOptions{}, 3);
  } else if (options.swap_edges && result.mesh.triangle_count() > 0) {
    ImprovementOptions swaps;
    improve_by_edge_swaps(result.mesh, problem, swaps);
  }
  {
    // The radius follows the curvature at the chart's centre; where the curvature changes
    // across a triangle (its charts' radii differ) or vertices were moved by smoothing, the
    // quadratic model behind the radius no longer bounds the triangle: check and bisect there.
    std::vector<int> to_check;
    for (int t = 0; t < result.mesh.triangle_count(); ++t) {
      const Triangle& tri = result.mesh.triangle(t);
      const double small = std::min({triangulation.radius[tri[0]], triangulation.radius[tri[1]],
                                     triangulation.radius[tri[2]]});
      const double large = std::max({triangulation.radius[tri[0]], triangulation.radius[tri[1]],
                                     triangulation.radius[tri[2]]});
      if (options.placement == AtlasPlacement::Hexagonal || large > 1.05 * small) {
        to_check.push_back(t);
      }
    }
    summary.refined_edges += refine_where(problem, domain, result.mesh, to_check, options);
  }
  double boundary_scale = min_radius;  // median radius of the charts near ∂S (set below)
  if (!domain.is_unbounded() && result.mesh.triangle_count() > 0) {
    ClipOptions clip;
    // Snap and collapse lengths follow the charts near the boundary: the median radius of the
    // charts outside or within one radius of ∂S.
    std::vector<double> boundary_radii;
    for (int c = 0; c < builder.chart_count(); ++c) {
      if (domain.boundary_distance(builder.center(c)).signed_distance < builder.chart(c).radius) {
        boundary_radii.push_back(builder.chart(c).radius);
      }
    }
    double& scale = boundary_scale;
    if (!boundary_radii.empty()) {
      std::nth_element(boundary_radii.begin(), boundary_radii.begin() + boundary_radii.size() / 2,
                       boundary_radii.end());
      scale = boundary_radii[boundary_radii.size() / 2];
    }
    clip.snap_distance = 0.35 * scale;
    clip.min_boundary_edge = 0.2 * scale;
    clip.corrector = options.corrector;
    const ClipSummary clipped = clip_to_domain(problem, domain, result.mesh, clip);
    summary.clipped_half_spaces = clipped.half_spaces_crossed;
    clipping_failed = !clipped.message.empty();
    if (!clipped.message.empty() && summary.is_complete()) {
      summary.termination = CoveringTermination::ProjectionFailed;
      summary.message = clipped.message;
    }
  }
  // Clipping leaves poor angles at ∂S that Delaunay swaps in the tangent planes repair (the
  // interior is a weighted Delaunay triangulation already; measured: cut sphere 22° → 28°).
  // Snapping, cutting and swapping reshape the triangles near ∂S: those are then bisected
  // until their sampled points are within ε of M again.
  if (!domain.is_unbounded() && result.mesh.triangle_count() > 0) {
    improve_by_edge_swaps(result.mesh, problem, ImprovementOptions{});
    // Swaps stay within a triangle or two of ∂S: check the band of two boundary radii.
    const auto near_boundary = [&] {
      std::vector<int> band;
      for (int t = 0; t < result.mesh.triangle_count(); ++t) {
        for (int v : result.mesh.triangle(t)) {
          if (domain.boundary_distance(result.mesh.point(v)).signed_distance <=
              2.0 * boundary_scale) {
            band.push_back(t);
            break;
          }
        }
      }
      return band;
    };
    const int split = refine_where(problem, domain, result.mesh, near_boundary(), options);
    summary.refined_edges += split;
    if (split > 0) {
      // Bisection can leave a poor angle next to the split edge: swap once more, and check
      // again, so that the last word is the distance bound's.
      improve_by_edge_swaps(result.mesh, problem, ImprovementOptions{});
      summary.refined_edges += refine_where(problem, domain, result.mesh, near_boundary(), options);
    }
  }
  check_coverage(domain, result.mesh, summary);
  summary.notes.push_back(
      "covered the component of M that contains the start point; other "
      "components, if any, need their own start points");
  return result;
}

}  // namespace

CoveringResult cover_by_atlas(const ImplicitProblem& user_problem, const Eigen::VectorXd& start,
                              const Domain& domain, const AtlasOptions& options) {
  options.validate();
  check_domain_dimension(domain, user_problem);
  const auto clock_start = std::chrono::steady_clock::now();
  CountedProblem problem(user_problem);
  const double max_start_distance =
      options.max_start_distance > 0 ? options.max_start_distance : 10.0 * options.max_radius;
  const StartPoint start_point = project_start_point(problem, start, domain, max_start_distance);
  bool clipping_failed = false;
  CoveringResult result = cover_once(problem, start_point, domain, options, clipping_failed);
  if (clipping_failed && options.boundary_snap > 0) {
    // Charts snapped onto ∂S can leave the clipping a configuration it refuses (seen where M
    // meets a face at a shallow angle); the atlas is then computed again without snapping.
    AtlasOptions unsnapped = options;
    unsnapped.boundary_snap = 0.0;
    result = cover_once(problem, start_point, domain, unsnapped, clipping_failed);
    result.summary.notes.push_back(
        "charts snapped onto the domain boundary left a mesh the "
        "clipping refused; computed again without snapping");
  }
  finish_summary(result.mesh, result.summary, problem, clock_start);
  return result;
}

}  // namespace tessera
