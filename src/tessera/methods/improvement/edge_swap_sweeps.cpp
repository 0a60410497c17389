// SPDX-License-Identifier: MIT
// Lawson's sweeps of improve_by_edge_swaps: every edge once, then only the edges that swaps
// changed, until no swap improves the criterion (one swap's machinery: detail/swap_quad.h).
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <memory>
#include <span>
#include <unordered_map>
#include <vector>

#include "tessera/core/ambient_space.h"
#include "tessera/core/linearization.h"
#include "tessera/core/parallel_for.h"
#include "tessera/geometry/mesh_quality.h"
#include "tessera/geometry/mesh_topology.h"
#include "tessera/methods/improvement/detail/swap_quad.h"
#include "tessera/methods/improvement/edge_swap.h"

namespace tessera {

using detail::check_dimensions;
using detail::check_quad_geometry;
using detail::CornerTangents;
using detail::judge_swap;
using detail::kQuadSides;
using detail::orient_quad;
using detail::Quad;
using detail::quad_sides;
using detail::Verdict;

ImprovementSummary improve_by_edge_swaps(TriangleMesh& mesh, const ImplicitProblem& problem,
                                         const ImprovementOptions& options) {
  check_dimensions(mesh, problem);
  options.validate();
  ImprovementSummary summary;
  if (options.measure_shapes) {
    const MeshQuality shape_before = measure_shape(mesh);
    summary.min_angle_degrees_before = shape_before.min_angle_degrees;
    summary.fraction_angles_below_30_before = shape_before.fraction_angles_below_30;
  }

  std::vector<Triangle> triangles = mesh.triangles();
  // The first sweep's topology. Later sweeps visit only the edges a swap may have changed, so
  // instead of rebuilding it (at 10⁶ vertices two full sweeps of nearly no swaps were a fifth of
  // a torus's run) the vertices' triangles are patched where swaps changed them.
  const MeshTopology topology(mesh.vertex_count(), triangles);
  std::unordered_map<int, std::vector<int>> patched_stars;
  const auto star_of = [&](int v) -> std::span<const int> {
    const auto found = patched_stars.find(v);
    return found != patched_stars.end() ? std::span<const int>(found->second)
                                        : topology.vertex_triangles(v);
  };
  // The triangles on the edge u–w (the first two in `incident`, which may be null) and how
  // many there are: those of u's that have w. 0: u and w are not joined.
  const auto triangles_on_edge = [&](int u, int w, std::array<int, 2>* incident) {
    int found = 0;
    for (const int t : star_of(u)) {
      const Triangle& tri = triangles[static_cast<std::size_t>(t)];
      if (tri[0] == w || tri[1] == w || tri[2] == w) {
        if (incident != nullptr && found < 2) {
          (*incident)[static_cast<std::size_t>(found)] = t;
        }
        ++found;
      }
    }
    return found;
  };
  const auto patch_star = [&](int v, int removed, int added) {
    auto found = patched_stars.find(v);
    if (found == patched_stars.end()) {
      const auto initial = topology.vertex_triangles(v);
      found = patched_stars.emplace(v, std::vector<int>(initial.begin(), initial.end())).first;
    }
    std::vector<int>& star = found->second;
    if (removed >= 0) {
      std::erase(star, removed);
    }
    if (added >= 0) {
      star.push_back(added);
    }
  };
  CornerTangents corner_tangents(problem);
  Linearization workspace;
  std::vector<std::uint8_t> is_changed(triangles.size(), 0);
  // A split mesh (SPMD): every rank its rows of the points; what a swap is judged by is summed
  // over the ranks, so that all make the same swaps.
  const std::shared_ptr<const AmbientSpace> shared_space = problem.space();
  const AmbientSpace& space = *shared_space;
  const bool split = space.is_distributed();
  // The edges of a sweep, as vertex pairs: the first sweep every edge, each later one the edges
  // of the triangles the sweep before changed and those refused because their other diagonal
  // was an edge (a swap may have removed it), in order. Any other edge keeps its quad and its
  // verdict, so it would not be swapped.
  std::vector<std::array<int, 2>> visit;
  visit.reserve(static_cast<std::size_t>(topology.edge_count()));
  for (const auto& edge : topology.edges()) {
    visit.push_back({edge[0], edge[1]});
  }
  std::vector<Quad> quads;
  std::vector<std::uint8_t> has_quad;
  std::vector<std::array<int, 2>> refused_existing;
  std::vector<int> changed;
  // kQuadSides lengths per visited edge (split meshes, MaxMinAngle).
  std::vector<double> quad_lengths;
  // Verdicts made before the sweep (on threads): the quads do not move while it runs, and an
  // edge whose triangles a swap changed is skipped, so each is the verdict it would get in turn.
  std::vector<std::int8_t> verdicts;
  const bool judge_ahead = !split && (options.criterion == ImprovementCriterion::MaxMinAngle ||
                                      options.criterion == ImprovementCriterion::NormalAngle);
  while (summary.sweeps < options.max_sweeps) {
    ++summary.sweeps;
    const bool first_sweep = summary.sweeps == 1;
    const int count = static_cast<int>(visit.size());
    quads.assign(visit.size(), Quad{});
    has_quad.assign(visit.size(), 0);
    int interior_edges = 0;
    for (int i = 0; i < count; ++i) {
      const auto [u, w] = visit[static_cast<std::size_t>(i)];
      std::array<int, 2> incident{-1, -1};
      int found = 0;
      if (first_sweep) {
        const auto on_edge = topology.edge_triangles(i);
        found = static_cast<int>(on_edge.size());
        if (found == 2) {
          incident = {on_edge[0], on_edge[1]};
        }
      } else {
        found = triangles_on_edge(u, w, &incident);
      }
      if (found != 2) {
        continue;  // boundary edges are never swapped; non-manifold edges are left alone
      }
      ++interior_edges;
      has_quad[static_cast<std::size_t>(i)] =
          orient_quad(triangles, incident[0], incident[1], u, w, quads[static_cast<std::size_t>(i)])
              ? 1
              : 0;
    }
    if (first_sweep) {
      summary.interior_edges = interior_edges;
    }
    if (split && options.criterion == ImprovementCriterion::MaxMinAngle) {
      // Swaps move no point: every quad's lengths are measured at once (one reduction).
      quad_lengths.assign(kQuadSides * visit.size(), 0.0);
      for (int i = 0; i < count; ++i) {
        if (has_quad[static_cast<std::size_t>(i)]) {
          const auto pairs = quad_sides(quads[static_cast<std::size_t>(i)]);
          for (std::size_t k = 0; k < pairs.size(); ++k) {
            quad_lengths[kQuadSides * static_cast<std::size_t>(i) + k] =
                (mesh.point(pairs[k].first) - mesh.point(pairs[k].second)).squaredNorm();
          }
        }
      }
      if (!quad_lengths.empty()) {
        space.sum(quad_lengths.data(), static_cast<int>(quad_lengths.size()));
      }
      for (double& length : quad_lengths) {
        length = std::sqrt(length);
      }
    }
    if (judge_ahead) {
      verdicts.assign(visit.size(), static_cast<std::int8_t>(Verdict::DoesNotImprove));
      parallel_for(count, thread_count(), [&](int i) {
        if (has_quad[static_cast<std::size_t>(i)]) {
          verdicts[static_cast<std::size_t>(i)] = static_cast<std::int8_t>(judge_swap(
              mesh, problem, quads[static_cast<std::size_t>(i)], options, workspace, nullptr));
        }
      });
    }
    refused_existing.clear();
    changed.clear();
    int swaps_in_sweep = 0;
    for (int i = 0; i < count; ++i) {
      if (!has_quad[static_cast<std::size_t>(i)]) {
        continue;
      }
      const Quad& q = quads[static_cast<std::size_t>(i)];
      if (is_changed[static_cast<std::size_t>(q.t1)] || is_changed[static_cast<std::size_t>(q.t2)]) {
        continue;  // an edge of a changed triangle: the next sweep visits it
      }
      if (triangles_on_edge(q.c, q.d, nullptr) > 0) {
        ++summary.rejected_existing_edge;
        refused_existing.push_back(visit[static_cast<std::size_t>(i)]);
        continue;
      }
      // A split mesh polls where a swap is wanted, before its factorisations: the request is
      // one rank's, so the ranks agree on it by a reduction, which per edge would cost more
      // than the criterion measured for the whole sweep at once.
      if (!split && options.stop_requested && options.stop_requested()) {
        summary.interrupted = true;
        break;
      }
      // The criterion first: most edges of a reasonable mesh do not want a swap, and for them
      // the projection and the five factorisations of the validity check would be wasted.
      const Verdict verdict =
          judge_ahead ? static_cast<Verdict>(verdicts[static_cast<std::size_t>(i)])
                      : judge_swap(mesh, problem, q, options, workspace,
                                   quad_lengths.empty()
                                       ? nullptr
                                       : quad_lengths.data() + kQuadSides * static_cast<std::size_t>(i));
      if (verdict == Verdict::ProjectionFailed) {
        ++summary.rejected_projection_failed;
        continue;
      }
      if (verdict == Verdict::DoesNotImprove) {
        continue;
      }
      if (split && options.stop_requested &&
          space.maximum(options.stop_requested() ? 1.0 : 0.0) > 0.0) {
        summary.interrupted = true;
        break;
      }
      const SwapCheck check =
          check_quad_geometry(mesh, problem, q, options, workspace, corner_tangents);
      if (check == SwapCheck::NonConvex) {
        ++summary.rejected_non_convex;
        continue;
      }
      if (check != SwapCheck::Allowed) {
        ++summary.rejected_projection_failed;
        continue;
      }
      // (a, b, c) becomes (c, a, d) and (b, a, d) becomes (d, b, c): b leaves t1 and d joins it,
      // a leaves t2 and c joins it. The mesh's triangles are read by the criteria (through the
      // mesh points only), so they are written back at the end.
      triangles[static_cast<std::size_t>(q.t1)] = {q.c, q.a, q.d};
      triangles[static_cast<std::size_t>(q.t2)] = {q.d, q.b, q.c};
      patch_star(q.b, q.t1, -1);
      patch_star(q.d, -1, q.t1);
      patch_star(q.a, q.t2, -1);
      patch_star(q.c, -1, q.t2);
      is_changed[static_cast<std::size_t>(q.t1)] = 1;
      is_changed[static_cast<std::size_t>(q.t2)] = 1;
      changed.push_back(q.t1);
      changed.push_back(q.t2);
      ++swaps_in_sweep;
    }
    summary.swaps += swaps_in_sweep;
    if (summary.interrupted) {
      break;
    }
    if (swaps_in_sweep == 0) {
      summary.converged = true;
      break;
    }
    visit = std::move(refused_existing);
    refused_existing = {};
    for (const int t : changed) {
      const Triangle& tri = triangles[static_cast<std::size_t>(t)];
      for (int k = 0; k < 3; ++k) {
        visit.push_back({std::min(tri[k], tri[(k + 1) % 3]), std::max(tri[k], tri[(k + 1) % 3])});
      }
      is_changed[static_cast<std::size_t>(t)] = 0;
    }
    std::sort(visit.begin(), visit.end());
    visit.erase(std::unique(visit.begin(), visit.end()), visit.end());
  }
  mesh.set_triangles(std::move(triangles));
  if (options.measure_shapes) {
    const MeshQuality shape_after = measure_shape(mesh);
    summary.min_angle_degrees_after = shape_after.min_angle_degrees;
    summary.fraction_angles_below_30_after = shape_after.fraction_angles_below_30;
  }
  return summary;
}

}  // namespace tessera
