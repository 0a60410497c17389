// SPDX-License-Identifier: MIT
// The geometric checks of validate(): orientation along M and vertices in S (the overlap check
// is in mesh_validation_overlaps.cpp). The mathematics is in docs/validation.md; the comments
// here say why each step is sound.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <initializer_list>
#include <limits>
#include <numbers>
#include <set>
#include <sstream>
#include <utility>
#include <vector>

#include <Eigen/LU>

#include "tessera/core/describe.h"
#include "tessera/core/error.h"
#include "tessera/core/linearization.h"
#include "tessera/core/parallel_for.h"
#include "tessera/geometry/detail/mesh_validation_checks.h"
#include "tessera/geometry/mesh_quality.h"
#include "tessera/geometry/spatial_order.h"
#include "tessera/geometry/spatial_hash.h"
#include "tessera/geometry/triangle_intersection.h"

namespace tessera::detail {
namespace {

Eigen::VectorXd centroid(const Eigen::Map<const Eigen::MatrixXd>& points, const Triangle& tri) {
  return (points.col(tri[0]) + points.col(tri[1]) + points.col(tri[2])) / 3.0;
}

// Oriented cosine s = det(Tᵀe₁, Tᵀe₂) / |e₁ ∧ e₂| of the triangle against the oriented plane
// spanned by the orthonormal columns of T (n×2). Tᵀ is the orthogonal projection onto that
// plane in T's coordinates, so det(Tᵀe₁, Tᵀe₂)/2 is the signed area of the projected triangle
// and s is the ratio of the projected to the true area: the cosine of the angle between the
// two planes in R³, the product of the cosines of the two principal angles in R^n, with the
// sign of the orientation. |s| ≤ 1.
double oriented_cosine(const Eigen::Map<const Eigen::MatrixXd>& points, const Triangle& tri,
                       double area, const Eigen::MatrixXd& T, const AmbientSpace& space) {
  Eigen::Matrix2d ab;
  ab.col(0) = T.transpose() * (points.col(tri[1]) - points.col(tri[0]));
  ab.col(1) = T.transpose() * (points.col(tri[2]) - points.col(tri[0]));
  space.sum(ab.data(), 4);  // over the ranks of a split mesh (else nothing)
  const Eigen::Vector2d a = ab.col(0);
  const Eigen::Vector2d b = ab.col(1);
  return std::clamp((a.x() * b.y() - a.y() * b.x()) / (2.0 * area), -1.0, 1.0);
}

// The arc that the triangle sweeps around its corner v in the oriented plane T (n×2,
// orthonormal): the angle of its edge to the next corner, and the signed angle from there to
// the edge to the corner after (positive when the projected triangle is counterclockwise).
std::array<double, 2> corner_arc(const Eigen::Map<const Eigen::MatrixXd>& points,
                                 const Triangle& tri, int k, const Eigen::MatrixXd& T,
                                 const AmbientSpace& space) {
  const auto v = points.col(tri[k]);
  Eigen::Matrix2d ab;
  ab.col(0) = T.transpose() * (points.col(tri[(k + 1) % 3]) - v);
  ab.col(1) = T.transpose() * (points.col(tri[(k + 2) % 3]) - v);
  space.sum(ab.data(), 4);  // over the ranks of a split mesh (else nothing)
  const Eigen::Vector2d a = ab.col(0);
  const Eigen::Vector2d b = ab.col(1);
  return {std::atan2(a.y(), a.x()), std::atan2(a.x() * b.y() - a.y() * b.x(), a.dot(b))};
}

}  // namespace

std::string triangle_name(int t, const Triangle& tri) {
  std::ostringstream out;
  out << "triangle " << t << " (vertices " << tri[0] << ", " << tri[1] << ", " << tri[2] << ")";
  return out.str();
}

// 1. Orientation, judged locally. Two triangles that share an edge and traverse it in
// opposite directions (a consistently oriented pair) must lie on opposite sides of it along M:
// projected onto the tangent plane of M at a shared vertex, their signed areas have the same
// sign. If they do not, the pair is folded: one of them is flipped. The test needs one tangent
// basis per vertex, in any orientation (both triangles are projected onto the same one), so it
// needs no orientation transported along M or derived from DF: transport fails where
// neighbouring tangent planes differ by more than 90° (thin tubes at a coarse step), and the
// orientation DF gives reverses across a singular curve of F (the `crossing` problem), while a
// fold is a fold wherever it is. A pair traversing its edge in the same direction (a
// non-orientable mesh) is folded when its signed areas have opposite signs.
//
// Which of a folded pair is the flipped one: the triangle folded against most of its
// neighbours (a flipped triangle is folded against all of them, each neighbour against one of
// its own); where that does not decide (a pair each folded once), both are reported.
// A triangle whose plane stands across M (mean |s| over its corners below min_tangent_cosine,
// s the projected over the true area) is reported too.
//
// Why the vertices and not the triangles' centroids: the vertices lie on M (to the corrector's
// tolerance), where ker DF is M's tangent plane. A centroid lies off M by the chord error e,
// where ker DF approximates the tangent plane only to O(‖D²F‖·e / σ_min(DF)); near a singular
// curve of F (the `crossing` problem's circle, where DF → 0 on M) that is no approximation at
// all. A vertex is shared by about six triangles, so this is also half as many factorisations.
void check_orientation(const MeshView& view, const GeometricInput& geometry,
                       const ValidationOptions& options, CheckStop& stop, DefectRecorder& recorder,
                       MeshValidation& result) {
  const MeshTopology& topology = view.topology;
  const std::vector<Triangle>& triangles = topology.triangles();
  TriangleShapes& shapes = view.shapes;
  const auto points = view.mesh.points();
  const AmbientSpace& space = view.mesh.space();
  const int count = topology.triangle_count();
  const int vertex_count = view.mesh.vertex_count();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  // s of triangle t against the tangent basis at its k-th corner (NaN: not judged there).
  std::vector<std::array<double, 3>> corner_cosine(count, {nan, nan, nan});
  // The arc (start, signed sweep) of triangle t around its k-th corner in the tangent plane there.
  std::vector<std::array<std::array<double, 2>, 3>> corner_arcs(count);
  auto is_judged = [&](int t) { return shapes.is_finite[t] && !shapes.is_degenerate[t]; };
  const auto judge_corners = [&](int v, const Eigen::MatrixXd& T) {
    for (int t : topology.vertex_triangles(v)) {
      if (is_judged(t)) {
        const int k = triangles[t][0] == v ? 0 : (triangles[t][1] == v ? 1 : 2);
        corner_cosine[t][k] = oriented_cosine(points, triangles[t], shapes.area[t], T, space);
        corner_arcs[t][k] = corner_arc(points, triangles[t], k, T, space);
      }
    }
  };
  // For sparse (large n) problems the tangent planes of a vertex's neighbours and their
  // neighbours (two rings) come from its factorisation (tangent_basis_near: one evaluation of DF
  // and a few solves each), so that only about one vertex in ten is factored; the orientation
  // test needs the planes to a few digits only, and the chord from two edges away still
  // contracts fast (where it does not, the vertex is factored itself later). Dense problems
  // factor at every vertex, which costs little there and keeps planes that differ by 90°
  // between neighbours (thin tubes) exact.
  const bool is_sparse = geometry.problem.has_sparse_jacobian();
  constexpr double kNearTangentTolerance = 1e-6;
  constexpr int kSharedRings = 3;
  std::vector<std::uint8_t> is_done(vertex_count, 0);
  if (!is_sparse) {
    // Every vertex on its own: on threads (judge_corners writes only the corners at v).
    // By blocks, a stop request polled between them on this thread; a block is a few
    // milliseconds at small n, fewer vertices where each is a dense factorisation of size n.
    const int threads = threads_for(geometry.problem);
    const int per_block = threads * (view.mesh.ambient_dimension() <= 64 ? 512 : 8);
    for (int first = 0; first < vertex_count && !stop.is_stopped(); first += per_block) {
      parallel_for(std::min(per_block, vertex_count - first), threads, [&](int i) {
        const int v = first + i;
        if (topology.vertex_triangles(v).empty() || !view.is_finite_vertex[v]) {
          return;
        }
        is_done[v] = 1;  // one writer per vertex
        Linearization at_vertex;
        if (at_vertex.factor(geometry.problem, points.col(v))) {
          judge_corners(v, at_vertex.tangent_basis());
        }
      });
    }
  }
  Linearization linearization;
  Eigen::MatrixXd near_tangent;
  std::vector<int> ring;
  std::vector<int> next_ring;
  // Where factorisations are worth sharing (worth_sharing, known from the first), the seeds
  // after the first come along M (a Hilbert curve through the vertices, spatially_ordered), and
  // a seed near the last factorisation takes its plane from it too: in index order the next seed
  // lay anywhere (bratu2d:N=32: 293 factorisations, one per 13 vertices).
  std::vector<int> seeds;
  if (is_sparse) {
    seeds.resize(static_cast<std::size_t>(vertex_count));
    for (int v = 0; v < vertex_count; ++v) {
      seeds[static_cast<std::size_t>(v)] = v;
    }
  }
  bool along_M = false;
  for (std::size_t k = 0; k < seeds.size(); ++k) {
    const int v = seeds[k];
    if (is_done[v] || topology.vertex_triangles(v).empty() || !view.is_finite_vertex[v]) {
      continue;
    }
    if (stop.is_stopped()) {
      break;  // the vertices not done are left unjudged (counted below)
    }
    is_done[v] = 1;
    if (along_M && tangent_basis_near(geometry.problem, linearization, points.col(v),
                                      near_tangent, kNearTangentTolerance)) {
      judge_corners(v, near_tangent);
    } else if (linearization.factor(geometry.problem, points.col(v))) {
      judge_corners(v, linearization.tangent_basis());
      if (!along_M && worth_sharing(linearization)) {
        along_M = true;
        std::vector<int> rest(seeds.begin() + static_cast<std::ptrdiff_t>(k) + 1, seeds.end());
        seeds.resize(k + 1);
        for (const int w : spatially_ordered(view.mesh, std::move(rest))) {
          seeds.push_back(w);
        }
      }
    } else {
      continue;  // DF rank deficient at the vertex: not judged there
    }
    ring.assign(1, v);
    for (int rings = 0; rings < kSharedRings; ++rings) {
      next_ring.clear();
      for (int u : ring) {
        for (int t : topology.vertex_triangles(u)) {
          for (int w : triangles[t]) {
            if (is_done[w] || !view.is_finite_vertex[w]) {
              continue;
            }
            if (tangent_basis_near(geometry.problem, linearization, points.col(w), near_tangent,
                                   kNearTangentTolerance)) {
              is_done[w] = 1;
              judge_corners(w, near_tangent);
              next_ring.push_back(w);
            }
          }
        }
      }
      ring.swap(next_ring);
    }
  }
  // Cut short by a stop request: the vertices never reached have no tangent plane, and their
  // corners vote nowhere; a triangle with none judged is not "unoriented" (DF singular), it
  // was not looked at.
  std::vector<std::uint8_t> is_cut(vertex_count, 0);
  int cut_vertices = 0;
  int judgeable_vertices = 0;
  for (int v = 0; v < vertex_count; ++v) {
    if (!topology.vertex_triangles(v).empty() && view.is_finite_vertex[v]) {
      ++judgeable_vertices;
      if (!is_done[v]) {
        is_cut[v] = 1;
        ++cut_vertices;
      }
    }
  }
  if (cut_vertices > 0) {
    result.checks_cut_short.push_back("orientation along M: " + std::to_string(cut_vertices) +
                                      " of " + std::to_string(judgeable_vertices) +
                                      " vertices not judged");
  }
  auto corner_of = [&](int t, int v) {
    return triangles[t][0] == v ? 0 : (triangles[t][1] == v ? 1 : 2);
  };
  // Folds across interior manifold edges: folded at both ends of the edge, or at one end
  // definitely, both planes within 72° of the tangent plane there and facing opposite ways. The
  // second case is a triangle across which M's normal turns by more than 90° (a coarse
  // tolerance where two sheets of the trough nearly touch): at its far corner it faces away
  // from M while its near corners still agree with its neighbours.
  constexpr double kDefiniteCosine = 0.3;
  std::vector<int> folds(count, 0);
  std::vector<int> interior_edges(count, 0);
  std::vector<std::pair<int, int>> folded_pairs;
  for (int e = 0; e < topology.edge_count(); ++e) {
    const auto pair = topology.edge_triangles(e);
    if (pair.size() != 2 || !is_judged(pair[0]) || !is_judged(pair[1])) {
      continue;
    }
    const int a = pair[0], b = pair[1];
    ++interior_edges[a];
    ++interior_edges[b];
    const bool opposite = topology.is_orientation_consistent(e);
    int votes = 0;
    int judged = 0;
    bool definite = false;
    for (int v : topology.edge(e)) {
      const double sa = corner_cosine[a][corner_of(a, v)];
      const double sb = corner_cosine[b][corner_of(b, v)];
      // A corner where either plane stands across M (|s| below min_tangent_cosine) casts no
      // vote: there the sign of a projected area tells the plane's tilt, not which side of the
      // edge the triangle lies on. (cstr, bezier, stress seed 2026: a triangle at 0.044 at one
      // end of its edge outvoted a fold at 0.26 at the other, and the pair's overlap on M
      // passed as valid.)
      if (std::isnan(sa) || std::isnan(sb) ||
          std::min(std::abs(sa), std::abs(sb)) < options.min_tangent_cosine) {
        continue;
      }
      ++judged;
      const bool vote = opposite ? sa * sb < 0 : sa * sb > 0;
      votes += vote ? 1 : 0;
      definite = definite || (vote && std::min(std::abs(sa), std::abs(sb)) >= kDefiniteCosine);
    }
    if (judged > 0 && (votes == judged || definite)) {
      ++folds[a];
      ++folds[b];
      folded_pairs.emplace_back(a, b);
    }
  }
  std::vector<std::uint8_t> flipped(count, 0);
  for (int t = 0; t < count; ++t) {
    flipped[t] = folds[t] > 0 && 2 * folds[t] > interior_edges[t];
  }
  check_fan_arcs(view, corner_cosine, corner_arcs, options, recorder, result);
  for (const auto& [a, b] : folded_pairs) {
    if (!flipped[a] && !flipped[b]) {
      flipped[a] = flipped[b] = 1;
    }
  }
  for (int t = 0; t < count; ++t) {
    if (!is_judged(t)) {
      continue;  // degenerate or not finite: reported as such
    }
    double magnitude = 0.0;
    int judged = 0;
    for (double c : corner_cosine[t]) {
      if (!std::isnan(c)) {
        magnitude += std::abs(c);
        ++judged;
      }
    }
    if (judged == 0) {
      const Triangle& tri = triangles[t];
      if (!is_cut[tri[0]] && !is_cut[tri[1]] && !is_cut[tri[2]]) {
        ++result.unoriented_triangle_count;
      }
      continue;
    }
    magnitude /= judged;
    const bool stands = magnitude < options.min_tangent_cosine;
    shapes.oriented_cosine[t] = flipped[t] ? -magnitude : magnitude;
    if (!flipped[t] && !stands) {
      continue;
    }
    result.flipped_triangles.push_back(view.original[t]);
    recorder.record(MeshDefectKind::FlippedTriangle, [&] {
      std::ostringstream out;
      out.precision(3);
      const int n = space.dimension();
      out << triangle_name(view.original[t], triangles[t]) << " near "
          << describe_point(centroid(points, triangles[t]), space) << ": ";
      if (flipped[t]) {
        out << "folded over its neighbour(s) across " << folds[t] << " of its " << interior_edges[t]
            << " inner edges";
      } else {
        out << "stands across M, " << (n == 3 ? "normal" : "plane") << " at "
            << degrees(std::acos(magnitude)) << "° to M's" << (n == 3 ? "" : " tangent plane");
      }
      return out.str();
    });
  }
}

// 3. Domain. Vertices on ∂S are placed there by a projection onto the faces, which rounds to
// a few ulp of the coordinates; a vertex farther outside than domain_tolerance_ratio·(1 +
// ‖x‖∞) was not put on ∂S at all.
void check_domain(const MeshView& view, const GeometricInput& geometry,
                  const ValidationOptions& options, DefectRecorder& recorder,
                  MeshValidation& result) {
  const Domain& domain = geometry.domain;
  if (domain.is_unbounded()) {
    return;
  }
  const auto points = view.mesh.points();
  const AmbientSpace& space = view.mesh.space();
  for (int v = 0; v < view.mesh.vertex_count(); ++v) {
    if (!view.is_finite_vertex[v]) {
      continue;  // reported as a non-finite coordinate
    }
    const auto x = points.col(v);
    const double tolerance =
        options.domain_tolerance_ratio * (1.0 + space.maximum(x.lpNorm<Eigen::Infinity>()));
    if (domain.contains(x, tolerance)) {
      continue;
    }
    result.vertices_outside_domain.push_back(v);
    recorder.record(MeshDefectKind::VertexOutsideDomain, [&] {
      const BoundaryDistance nearest = domain.boundary_distance(x);
      const HalfSpace& face = domain.half_spaces()[nearest.nearest_half_space];
      std::ostringstream out;
      out.precision(3);
      out << "vertex " << v << " at " << describe_point(x, space) << " is "
          << -nearest.signed_distance << " outside the domain ("
          << (face.label.empty() ? "half-space " + std::to_string(nearest.nearest_half_space)
                                 : face.label)
          << ")";
      return out.str();
    });
  }
}

}  // namespace tessera::detail
