// SPDX-License-Identifier: MIT
// The checks of a completed covering's result: no hole, and no hole of M ∩ S covered over.
#include "tessera/methods/covering_checks.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "tessera/core/corrector.h"
#include "tessera/core/describe.h"
#include "tessera/core/factorisation_cache.h"
#include "tessera/core/linearization.h"
#include "tessera/geometry/mesh_topology.h"

namespace tessera::detail {

// Post-condition of a completed run, checked rather than assumed: on a closed surface the mesh
// has no boundary; in a bounded domain every boundary edge lies on ∂S, i.e. both its ends lie
// on one face or on two adjacent ones (a corner the clipping cut). Both ends on ∂S is not
// enough: where M ∩ S is a band narrower than the mesh's edges, an edge can run across the band
// from one face to the opposite one, and a missing row of triangles there cuts the mesh in two
// with every boundary vertex on ∂S (seen on bvp:points=1000). Anything else is a hole in the
// covering, reported with its place.
//
// A split mesh (each rank its rows of every vertex, the domain cut to them) measures in two
// reductions: the endpoints' distances to the faces, then the angles between the faces that
// the endpoints lie on; the verdict is taken on those sums, the same on every rank.
void check_coverage(const Domain& domain, double step, CoveringResult& result) {
  if (!result.summary.is_complete() || result.mesh.triangle_count() == 0) {
    return;
  }
  const TriangleMesh& mesh = result.mesh;
  const AmbientSpace& space = mesh.space();
  const MeshTopology topology(mesh);
  const double tolerance = 1e-6 * (1.0 + step);
  const int faces = domain.is_unbounded() ? 0 : static_cast<int>(domain.half_spaces().size());
  const std::vector<int>& boundary = topology.boundary_edges();
  // 1. Every boundary vertex's distance to every face (entry (k, 2i + j): endpoint j of the
  //    boundary edge i).
  std::vector<int> endpoints;
  endpoints.reserve(2 * boundary.size());
  for (int e : boundary) {
    endpoints.push_back(topology.edge(e)[0]);
    endpoints.push_back(topology.edge(e)[1]);
  }
  const Eigen::MatrixXd distance =
      faces > 0 ? domain.signed_distances(mesh.points(), endpoints) : Eigen::MatrixXd();
  const auto is_on = [&](int k, std::size_t i, int j) {
    return std::abs(distance(k, static_cast<Eigen::Index>(2 * i + j))) <= tolerance;
  };
  // 2. For each pair of faces (k, l) that some edge's ends lie on, b_k·b_l and ‖b_k‖², ‖b_l‖².
  std::map<std::pair<int, int>, int> pair_index;
  for (std::size_t i = 0; i < boundary.size(); ++i) {
    for (int k = 0; k < faces; ++k) {
      for (int l = 0; l < faces && is_on(k, i, 0); ++l) {
        if (is_on(l, i, 1)) {
          pair_index.emplace(std::make_pair(k, l), 0);
          pair_index.emplace(std::make_pair(k, k), 0);
          pair_index.emplace(std::make_pair(l, l), 0);
        }
      }
    }
  }
  std::vector<double> products;
  for (auto& [pair, index] : pair_index) {
    index = static_cast<int>(products.size());
    const Eigen::VectorXd& nk = domain.half_spaces()[pair.first].normal;
    const Eigen::VectorXd& nl = domain.half_spaces()[pair.second].normal;
    // ‖b‖² as squaredNorm: its root is b.norm() to the bit, in one process.
    products.push_back(pair.first == pair.second ? nk.squaredNorm() : nk.dot(nl));
  }
  if (!products.empty()) {
    space.sum(products.data(), static_cast<int>(products.size()));
  }
  const auto product = [&](int k, int l) { return products[pair_index.at({k, l})]; };
  for (std::size_t i = 0; i < boundary.size(); ++i) {
    // Never on two opposite faces (normals more than 120° apart).
    bool on_boundary = false;
    for (int k = 0; k < faces && !on_boundary; ++k) {
      if (!is_on(k, i, 0)) {
        continue;
      }
      for (int l = 0; l < faces && !on_boundary; ++l) {
        on_boundary = is_on(l, i, 1) &&
                      product(k, l) > -0.5 * std::sqrt(product(k, k)) * std::sqrt(product(l, l));
      }
    }
    if (!on_boundary) {
      const int v = topology.edge(boundary[i])[0];
      const int w = topology.edge(boundary[i])[1];
      result.summary.record_failure(
          CoveringTermination::TriangulationFailed,
          "the mesh has a hole: its boundary edge from " + describe_point(mesh.point(v), space) +
              " to " + describe_point(mesh.point(w), space) +
              (domain.is_unbounded() ? " lies on M, which is closed"
                                     : " does not lie on one face of the domain"));
      return;
    }
  }
}

// A triangle with every corner inside S can still cover a part of M outside S: where S cuts a
// hole into M smaller than the triangle (a cap of the sphere cut off by a face of a box, at a
// step larger than the cap), clipping sees no edge across the face and the mesh covers the hole
// over (the front on the sphere in [-0.97, 0.97]³ at h = 0.49: χ −2 for −4, "completed"). The
// centroid of such a triangle projects onto M beyond the face. Looked for where it can happen:
// a triangle with all corners strictly inside S and one within `snap_distance` of a face and a
// quarter of its longest edge (clipping snaps vertices that near onto the face unless that
// would fold a triangle, as it would around such a hole). Each centroid is projected by the
// chord from a factorisation at its corner nearest the face. On sparse problems, where M meets
// a face at a shallow angle, many triangles qualify (bvp:points=60 near ε = 0.3: 3566 of them,
// 0.21 factorisations per vertex), which costs nothing at n = 3 and too much at a PDE's n.
// There the check needs a tolerance and looks only within twice of it from the face: a
// triangle whose corners are all farther than d from the face, and under which M crosses the
// face, is at least d from M there, which refinement to the tolerance does not leave. Without
// a tolerance, the Euler characteristic, where known, catches a hole covered over.
//
// A split mesh measures the vertices' distances to the faces, their norms and the triangles'
// edges first, in two reductions, and decides on those sums; only the centroids that qualify
// are projected (collective calls, the same on every rank).
void check_holes_covered_over(const ImplicitProblem& problem, const Domain& domain,
                              double snap_distance, double tolerance,
                              const CorrectorOptions& corrector, const StopRequest& stop_requested,
                              CoveringResult& result) {
  if (!result.summary.is_complete() || domain.is_unbounded()) {
    return;
  }
  if (problem.has_sparse_jacobian()) {
    if (tolerance <= 0) {
      return;
    }
    snap_distance = std::min(snap_distance, 2.0 * tolerance);
  }
  const TriangleMesh& mesh = result.mesh;
  const AmbientSpace& space = mesh.space();
  const int faces = static_cast<int>(domain.half_spaces().size());
  const int vertex_count = mesh.vertex_count();
  const int triangle_count = mesh.triangle_count();
  // Every vertex's distance to every face; then every vertex's ‖x‖² and every triangle's
  // squared edges (their roots are Eigen's norms to the bit, in one process).
  std::vector<int> vertices(static_cast<std::size_t>(vertex_count));
  for (int v = 0; v < vertex_count; ++v) {
    vertices[static_cast<std::size_t>(v)] = v;
  }
  const Eigen::MatrixXd distance = domain.signed_distances(mesh.points(), vertices);
  std::vector<double> squared(static_cast<std::size_t>(vertex_count + 3 * triangle_count));
  for (int v = 0; v < vertex_count; ++v) {
    squared[static_cast<std::size_t>(v)] = mesh.point(v).squaredNorm();
  }
  for (int t = 0; t < triangle_count; ++t) {
    const Triangle& tri = mesh.triangle(t);
    for (int r = 0; r < 3; ++r) {
      squared[static_cast<std::size_t>(vertex_count + 3 * t + r)] =
          (mesh.point(tri[r]) - mesh.point(tri[(r + 1) % 3])).squaredNorm();
    }
  }
  if (!squared.empty()) {
    space.sum(squared.data(), static_cast<int>(squared.size()));
  }
  // The triangles to look under, with the face and the corner nearest it, then projected
  // grouped by that corner: each corner is factored once. (In the triangles' order the
  // factorisations were evicted between uses where one is tens of MB: bratu2d:N=316's front
  // at --tolerance 0.3 paid 1443 factorisations here, 4.5 per vertex, for 1.7 in the rest.)
  struct Candidate {
    int nearest;
    int triangle;
    int face;
    double longest;
  };
  std::vector<Candidate> candidates;
  for (int index = 0; index < triangle_count; ++index) {
    const Triangle& t = mesh.triangle(index);
    double longest = 0.0;
    for (int r = 0; r < 3; ++r) {
      longest = std::max(
          longest, std::sqrt(squared[static_cast<std::size_t>(vertex_count + 3 * index + r)]));
    }
    for (int k = 0; k < faces; ++k) {
      int nearest = -1;
      double smallest = std::numeric_limits<double>::infinity();
      bool inside = true;
      for (int v : t) {
        const double d = distance(k, v);
        inside = inside && d > 1e-9 * (1.0 + std::sqrt(squared[static_cast<std::size_t>(v)]));
        if (d < smallest) {
          smallest = d;
          nearest = v;
        }
      }
      if (inside && smallest < std::min(0.25 * longest, snap_distance)) {
        candidates.push_back({nearest, index, k, longest});
      }
    }
  }
  std::stable_sort(candidates.begin(), candidates.end(),
                   [](const Candidate& a, const Candidate& b) { return a.nearest < b.nearest; });
  FactorisationCache factorisations(2, std::size_t{64} << 20);
  // A corner borrows the last corner's factorisation where that is near enough
  // (borrow_nearby; the corners come sorted, mostly neighbours along ∂S): bratu2d:N=316's atlas
  // at step 0.5 spent 349 factorisations here, 0.99 per vertex.
  Linearization borrowed;
  int borrowed_at = -1;
  std::size_t looked = 0;
  for (const auto& [nearest, index, k, longest] : candidates) {
    // Polled by every rank alike (the candidates are the same everywhere): a stop ends the
    // check on all of them at the same triangle.
    if (stop_requested &&
        (space.is_distributed() ? space.maximum(stop_requested() ? 1.0 : 0.0) > 0.0
                                : stop_requested())) {
      result.summary.record_failure(
          CoveringTermination::Interrupted,
          "interrupted during the check for holes covered over: " +
              std::to_string(candidates.size() - looked) + " of " +
              std::to_string(candidates.size()) +
              " triangle(s) near a face of the domain were not looked under");
      return;
    }
    ++looked;
    const Triangle& t = mesh.triangle(index);
    const Linearization* frozen = nearest == borrowed_at ? &borrowed : factorisations.find(nearest);
    if (frozen == nullptr) {
      const Linearization* last = borrowed_at >= 0 ? &borrowed : factorisations.newest();
      Linearization next;
      if (last != nullptr && borrow_nearby(problem, *last, mesh.point(nearest), longest, next)) {
        borrowed = std::move(next);
        borrowed_at = nearest;
        frozen = &borrowed;
      } else {
        frozen = factorisations.factor(nearest, problem, mesh.point(nearest));
        borrowed = Linearization();  // (its factors may be large: not held beyond use)
        borrowed_at = -1;
      }
    }
    if (frozen == nullptr || !frozen->is_factored()) {
      continue;
    }
    Eigen::VectorXd x = (mesh.point(t[0]) + mesh.point(t[1]) + mesh.point(t[2])) / 3.0;
    CorrectorOptions options = corrector;
    options.max_displacement = longest;
    if (!project_chord(problem, *frozen, x, options).is_success()) {
      continue;
    }
    const double beyond = -domain.signed_distance(k, x);
    if (beyond > 1e-3 * longest) {
      std::ostringstream message;
      message << "the mesh covers a part of M outside the domain: the triangle with corners "
              << describe_point(mesh.point(t[0]), space) << ", "
              << describe_point(mesh.point(t[1]), space) << ", "
              << describe_point(mesh.point(t[2]), space) << " lies inside the face '"
              << domain.half_spaces()[k].label << "', but M under it reaches "
              << describe_point(x, space) << ", " << beyond
              << " beyond it (M ∩ S has a hole there smaller than the triangle; try a "
                 "smaller step)";
      result.summary.record_failure(CoveringTermination::TriangulationFailed, message.str());
      return;
    }
  }
}

}  // namespace tessera::detail
