// SPDX-License-Identifier: MIT
#include "tessera/methods/improvement/needle_collapse.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <sstream>
#include <utility>
#include <vector>

#include "tessera/core/error.h"
#include "tessera/core/linearization.h"
#include "tessera/geometry/mesh_quality.h"
#include "tessera/geometry/mesh_topology.h"

namespace tessera {

std::string NeedleCollapseSummary::brief_report() const {
  std::ostringstream out;
  out << "collapsed " << collapsed_edges << " short edge(s) of needles in " << passes
      << " pass(es)";
  if (refused > 0) {
    out << " (" << refused << " refused)";
  }
  if (interrupted) {
    out << ", interrupted";
  }
  return out.str();
}

namespace {

// Twice the signed area of the triangle (a, b, c) seen in the tangent plane T (n×2), over its
// longest side squared in that plane: the shape a fold or a sliver shows up in.
double signed_area_ratio(const Eigen::MatrixXd& T, const Eigen::VectorXd& a,
                         const Eigen::VectorXd& b, const Eigen::VectorXd& c) {
  const Eigen::Vector2d p = T.transpose() * a;
  const Eigen::Vector2d q = T.transpose() * b;
  const Eigen::Vector2d r = T.transpose() * c;
  const double twice_area = (q - p).x() * (r - p).y() - (q - p).y() * (r - p).x();
  const double longest =
      std::max({(q - p).squaredNorm(), (r - q).squaredNorm(), (p - r).squaredNorm()});
  return longest > 0.0 ? twice_area / longest : 0.0;
}

// The collapse of vertex `removed` into `kept`: the triangles around `removed` that do not
// have `kept` are its fan with `kept` in its place; the one or two on the edge disappear.
struct Collapse {
  int removed = -1;
  int kept = -1;
  std::vector<int> changed;  // triangles that gain `kept`
  std::vector<int> dropped;  // triangles on the edge
  double min_angle_after = 0.0;
};

}  // namespace

NeedleCollapseSummary collapse_needles(TriangleMesh& mesh, const ImplicitProblem& problem,
                                       const NeedleCollapseOptions& options) {
  TESSERA_CHECK(mesh.ambient_dimension() == problem.ambient_dimension(),
                "collapse_needles: the mesh lives in R^" << mesh.ambient_dimension()
                                                         << ", the problem in R^"
                                                         << problem.ambient_dimension());
  TESSERA_CHECK(!mesh.space().is_distributed(),
                "collapse_needles: the mesh is split over ranks; it needs whole points");
  NeedleCollapseSummary summary;
  const double threshold = options.min_angle_degrees * std::numbers::pi / 180.0;
  Linearization at_kept;
  Linearization at_removed;
  for (summary.passes = 0; summary.passes < options.max_passes; ++summary.passes) {
    const MeshTopology topology(mesh);
    std::vector<Triangle> triangles = mesh.triangles();
    std::vector<std::uint8_t> on_boundary(mesh.vertex_count(), 0);
    for (int e : topology.boundary_edges()) {
      on_boundary[topology.edge(e)[0]] = on_boundary[topology.edge(e)[1]] = 1;
    }
    // The needles and their short edges, shortest first.
    std::vector<std::pair<double, std::array<int, 3>>> needles;  // (length, {u, v, triangle})
    for (int t = 0; t < mesh.triangle_count(); ++t) {
      const Triangle& tri = triangles[t];
      if (min_angle(mesh, tri) >= threshold) {
        continue;
      }
      std::array<std::pair<double, int>, 3> sides;
      for (int k = 0; k < 3; ++k) {
        sides[k] = {(mesh.point(tri[(k + 1) % 3]) - mesh.point(tri[k])).norm(), k};
      }
      std::sort(sides.begin(), sides.end());
      if (sides[0].first <= options.needle_edge_ratio * sides[1].first) {
        const int k = sides[0].second;
        needles.push_back({sides[0].first, {tri[k], tri[(k + 1) % 3], t}});
      }
    }
    std::sort(needles.begin(), needles.end());
    std::vector<std::uint8_t> touched(mesh.vertex_count(), 0);
    std::vector<std::uint8_t> alive(triangles.size(), 1);
    int collapsed = 0;
    // The best admissible collapse of the edge (u, v) into one of its ends, if any.
    const auto plan = [&](int u, int v) {
      Collapse best;
      std::vector<int> neighbours_u, neighbours_v, opposite;
      for (int t : topology.vertex_triangles(u)) {
        for (int w : triangles[t]) {
          neighbours_u.push_back(w);
        }
      }
      for (int t : topology.vertex_triangles(v)) {
        for (int w : triangles[t]) {
          neighbours_v.push_back(w);
        }
        const Triangle& tri = triangles[t];
        if (tri[0] == u || tri[1] == u || tri[2] == u) {
          for (int w : tri) {
            if (w != u && w != v) {
              opposite.push_back(w);
            }
          }
        }
      }
      for (auto* list : {&neighbours_u, &neighbours_v, &opposite}) {
        std::sort(list->begin(), list->end());
        list->erase(std::unique(list->begin(), list->end()), list->end());
      }
      // Link condition: the common neighbours are exactly the vertices opposite the edge.
      std::vector<int> common;
      std::set_intersection(neighbours_u.begin(), neighbours_u.end(), neighbours_v.begin(),
                            neighbours_v.end(), std::back_inserter(common));
      common.erase(
          std::remove_if(common.begin(), common.end(), [&](int w) { return w == u || w == v; }),
          common.end());
      if (common != opposite || opposite.empty()) {
        return best;
      }
      for (const auto& [removed, kept] : {std::pair{u, v}, std::pair{v, u}}) {
        if (on_boundary[removed]) {
          continue;
        }
        Collapse candidate;
        candidate.removed = removed;
        candidate.kept = kept;
        double min_before = std::numbers::pi;
        for (int t : topology.vertex_triangles(removed)) {
          const Triangle& tri = triangles[t];
          min_before = std::min(min_before, min_angle(mesh, tri));
          const bool on_edge = tri[0] == kept || tri[1] == kept || tri[2] == kept;
          (on_edge ? candidate.dropped : candidate.changed).push_back(t);
        }
        for (int t : topology.vertex_triangles(kept)) {
          min_before = std::min(min_before, min_angle(mesh, triangles[t]));
        }
        if (!at_kept.factor(problem, mesh.point(kept)) ||
            !at_removed.factor(problem, mesh.point(removed))) {
          continue;
        }
        // The fan's orientation in each tangent plane: the sign of the old triangles' areas.
        bool admissible = true;
        candidate.min_angle_after = std::numbers::pi;
        for (const Linearization* plane : {&at_kept, &at_removed}) {
          const Eigen::MatrixXd& T = plane->tangent_basis();
          double sign = 0.0;
          for (int t : topology.vertex_triangles(removed)) {
            const Triangle& tri = triangles[t];
            sign +=
                signed_area_ratio(T, mesh.point(tri[0]), mesh.point(tri[1]), mesh.point(tri[2]));
          }
          sign = sign >= 0.0 ? 1.0 : -1.0;
          for (int t : candidate.changed) {
            Triangle tri = triangles[t];
            std::replace(tri.begin(), tri.end(), removed, kept);
            admissible =
                admissible && sign * signed_area_ratio(T, mesh.point(tri[0]), mesh.point(tri[1]),
                                                       mesh.point(tri[2])) >
                                  options.min_area_ratio;
          }
        }
        for (int t : candidate.changed) {
          Triangle tri = triangles[t];
          std::replace(tri.begin(), tri.end(), removed, kept);
          candidate.min_angle_after = std::min(candidate.min_angle_after, min_angle(mesh, tri));
        }
        // The kept end's other triangles do not change.
        for (int t : topology.vertex_triangles(kept)) {
          const Triangle& tri = triangles[t];
          if (tri[0] != removed && tri[1] != removed && tri[2] != removed) {
            candidate.min_angle_after = std::min(candidate.min_angle_after, min_angle(mesh, tri));
          }
        }
        if (admissible && candidate.min_angle_after > min_before &&
            candidate.min_angle_after > best.min_angle_after) {
          best = std::move(candidate);
        }
      }
      return best;
    };
    for (const auto& [length, needle] : needles) {
      if (options.stop_requested && options.stop_requested()) {
        summary.interrupted = true;
        break;
      }
      const int u = needle[0], v = needle[1], t = needle[2];
      if (!alive[t] || touched[u] || touched[v]) {
        continue;  // the next pass sees it with its new neighbours
      }
      const Collapse collapse = plan(u, v);
      if (collapse.removed < 0) {
        ++summary.refused;
        continue;
      }
      for (int s : {u, v}) {
        for (int r : topology.vertex_triangles(s)) {
          for (int w : triangles[r]) {
            touched[w] = 1;
          }
        }
      }
      for (int r : collapse.dropped) {
        alive[r] = 0;
      }
      for (int r : collapse.changed) {
        std::replace(triangles[r].begin(), triangles[r].end(), collapse.removed, collapse.kept);
      }
      ++collapsed;
    }
    if (collapsed == 0) {
      break;
    }
    summary.collapsed_edges += collapsed;
    // The surviving triangles, and the vertices they use, in their old order.
    std::vector<int> new_index(mesh.vertex_count(), -1);
    std::vector<Triangle> kept_triangles;
    for (std::size_t t = 0; t < triangles.size(); ++t) {
      if (alive[t]) {
        kept_triangles.push_back(triangles[t]);
        for (int w : triangles[t]) {
          new_index[w] = 0;
        }
      }
    }
    int count = 0;
    for (int& index : new_index) {
      if (index == 0) {
        index = count++;
      }
    }
    Eigen::MatrixXd points(mesh.ambient_dimension(), count);
    for (int w = 0; w < mesh.vertex_count(); ++w) {
      if (new_index[w] >= 0) {
        points.col(new_index[w]) = mesh.point(w);
      }
    }
    for (Triangle& tri : kept_triangles) {
      for (int& w : tri) {
        w = new_index[w];
      }
    }
    mesh = TriangleMesh(points, std::move(kept_triangles));
    if (summary.interrupted) {
      break;
    }
  }
  return summary;
}

}  // namespace tessera
