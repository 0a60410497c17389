// SPDX-License-Identifier: MIT
#include "tessera/geometry/mesh_validation.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <initializer_list>
#include <limits>
#include <numbers>
#include <sstream>
#include <utility>

#include <Eigen/LU>

#include "tessera/core/describe.h"
#include "tessera/core/error.h"
#include "tessera/core/linearization.h"
#include "tessera/core/scaled_problem.h"
#include "tessera/geometry/mesh_quality.h"
#include "tessera/geometry/mesh_topology.h"
#include "tessera/geometry/spatial_hash.h"
#include "tessera/geometry/triangle_intersection.h"

namespace tessera {
namespace {

constexpr int kind_count = static_cast<int>(MeshDefectKind::VertexOutsideDomain) + 1;
constexpr std::size_t max_listed_indices = 8;  // per example line, e.g. triangles of an edge

std::string triangle_text(int t, const Triangle& tri) {
  std::ostringstream out;
  out << "triangle " << t << " = (" << tri[0] << ", " << tri[1] << ", " << tri[2] << ")";
  return out.str();
}

// "7, 9, 31" or "7, 9, 31, ... (12 in all)"
template <class Range, class Map>
std::string index_list(const Range& indices, Map map) {
  std::ostringstream out;
  std::size_t i = 0;
  for (auto index : indices) {
    if (i == max_listed_indices) {
      out << ", ... (" << std::size(indices) << " in all)";
      break;
    }
    out << (i == 0 ? "" : ", ") << map(index);
    ++i;
  }
  return out.str();
}

// Counts every occurrence and keeps the first `max_examples` descriptions of each kind. The
// description is built lazily so that a mesh with a million defects costs no strings.
class DefectRecorder {
 public:
  explicit DefectRecorder(int max_examples) : max_examples_(max_examples) {
    for (int i = 0; i < kind_count; ++i) {
      defects_[i].kind = static_cast<MeshDefectKind>(i);
    }
  }
  template <class Describe>
  void record(MeshDefectKind kind, const Describe& describe) {
    MeshDefect& defect = defects_[static_cast<int>(kind)];
    ++defect.count;
    if (static_cast<int>(defect.examples.size()) < max_examples_) {
      defect.examples.push_back(describe());
    }
  }
  int count(MeshDefectKind kind) const { return defects_[static_cast<int>(kind)].count; }
  std::vector<MeshDefect> take_present() {
    std::vector<MeshDefect> present;
    for (MeshDefect& defect : defects_) {
      if (defect.count > 0) {
        present.push_back(std::move(defect));
      }
    }
    return present;
  }

 private:
  int max_examples_;
  std::array<MeshDefect, kind_count> defects_;
};

// Union-find over triangle corners (corner 3t + k is vertex tri[k] of triangle t), used to
// group the triangles around each vertex into fans.
class CornerSets {
 public:
  explicit CornerSets(std::size_t size) : parent_(size) {
    for (std::size_t i = 0; i < size; ++i) {
      parent_[i] = static_cast<int>(i);
    }
  }
  int find(int c) {
    while (parent_[c] != c) {
      parent_[c] = parent_[parent_[c]];  // path halving
      c = parent_[c];
    }
    return c;
  }
  void unite(int a, int b) {
    a = find(a);
    b = find(b);
    if (a != b) {
      parent_[std::max(a, b)] = std::min(a, b);
    }
  }

 private:
  std::vector<int> parent_;
};

int corner(const std::vector<Triangle>& triangles, int t, int v) {
  const Triangle& tri = triangles[t];
  return 3 * t + (tri[0] == v ? 0 : (tri[1] == v ? 1 : 2));
}

// Area of the triangle (a, b, c) in R^n and its longest edge squared. The area equals
// sqrt(det G) / 2 for the Gram matrix G of two edge vectors, but det G = |u|^2 |v|^2 - (u.v)^2
// cancels catastrophically for thin triangles (its rounding error, ~1e-16 L^4, would give a
// collinear triangle an area of ~1e-8 L^2). Instead the apex is projected onto the longest
// edge u: area = |u| |w| / 2 with w = v - (u.v / u.u) u, whose error is a few ulp * L^2.
std::pair<double, double> area_and_longest_squared(const Eigen::Map<const Eigen::MatrixXd>& points,
                                                   const Triangle& tri) {
  std::array<double, 3> squared_length;  // edge k joins tri[k] and tri[(k + 1) % 3]
  for (int k = 0; k < 3; ++k) {
    squared_length[k] = (points.col(tri[(k + 1) % 3]) - points.col(tri[k])).squaredNorm();
  }
  const int k = static_cast<int>(std::max_element(squared_length.begin(), squared_length.end()) -
                                 squared_length.begin());
  const double uu = squared_length[k];
  if (uu == 0.0) {
    return {0.0, 0.0};
  }
  const auto base = points.col(tri[k]);
  const auto u = points.col(tri[(k + 1) % 3]) - base;
  const auto v = points.col(tri[(k + 2) % 3]) - base;
  const double s = u.dot(v) / uu;
  const double ww = (v - s * u).squaredNorm();
  return {0.5 * std::sqrt(uu * ww), uu};
}

// ---------------------------------------------------------------------------------------------
// Geometric checks (validate with a problem and a domain). The mathematics is in
// docs/validation.md; the comments here say why each step is sound.

struct GeometricInput {
  const ImplicitProblem& problem;
  const Domain& domain;
};

// Per topology triangle: what the combinatorial pass measured, and what the orientation pass
// finds for the overlap pass.
struct TriangleShapes {
  explicit TriangleShapes(int count)
      : area(count, 0.0),
        longest_edge(count, 0.0),
        is_finite(count, 0),
        is_degenerate(count, 0),
        oriented_cosine(count, std::numeric_limits<double>::quiet_NaN()) {}
  std::vector<double> area;
  std::vector<double> longest_edge;
  std::vector<std::uint8_t> is_finite;      // all three vertices finite
  std::vector<std::uint8_t> is_degenerate;  // a DegenerateTriangle defect
  // s_t against M's orientation as the mesh's piece sees it (σ applied, mean over the
  // corners); NaN if not judged.
  std::vector<double> oriented_cosine;
};

struct MeshView {
  const TriangleMesh& mesh;
  const MeshTopology& topology;
  const std::vector<int>& original;  // topology triangle -> mesh triangle
  TriangleShapes& shapes;
  const std::vector<std::uint8_t>& is_finite_vertex;
};

Eigen::VectorXd centroid(const Eigen::Map<const Eigen::MatrixXd>& points, const Triangle& tri) {
  return (points.col(tri[0]) + points.col(tri[1]) + points.col(tri[2])) / 3.0;
}

// "triangle 17 (vertices 3, 8, 9)"
std::string triangle_name(int t, const Triangle& tri) {
  std::ostringstream out;
  out << "triangle " << t << " (vertices " << tri[0] << ", " << tri[1] << ", " << tri[2] << ")";
  return out.str();
}

double degrees(double radians) { return radians * 180.0 / std::numbers::pi; }

// Oriented cosine s = det(Tᵀe₁, Tᵀe₂) / |e₁ ∧ e₂| of the triangle against the oriented plane
// spanned by the orthonormal columns of T (n×2). Tᵀ is the orthogonal projection onto that
// plane in T's coordinates, so det(Tᵀe₁, Tᵀe₂)/2 is the signed area of the projected triangle
// and s is the ratio of the projected to the true area: the cosine of the angle between the
// two planes in R³, the product of the cosines of the two principal angles in R^n, with the
// sign of the orientation. |s| ≤ 1.
double oriented_cosine(const Eigen::Map<const Eigen::MatrixXd>& points, const Triangle& tri,
                       double area, const Eigen::MatrixXd& T) {
  const Eigen::Vector2d a = T.transpose() * (points.col(tri[1]) - points.col(tri[0]));
  const Eigen::Vector2d b = T.transpose() * (points.col(tri[2]) - points.col(tri[0]));
  return std::clamp((a.x() * b.y() - a.y() * b.x()) / (2.0 * area), -1.0, 1.0);
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
                       const ValidationOptions& options, DefectRecorder& recorder,
                       MeshValidation& result) {
  const MeshTopology& topology = view.topology;
  const std::vector<Triangle>& triangles = topology.triangles();
  TriangleShapes& shapes = view.shapes;
  const auto points = view.mesh.points();
  const int count = topology.triangle_count();
  const int vertex_count = view.mesh.vertex_count();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  // s of triangle t against the tangent basis at its k-th corner (NaN: not judged there).
  std::vector<std::array<double, 3>> corner_cosine(count, {nan, nan, nan});
  auto is_judged = [&](int t) { return shapes.is_finite[t] && !shapes.is_degenerate[t]; };
  const auto judge_corners = [&](int v, const Eigen::MatrixXd& T) {
    for (int t : topology.vertex_triangles(v)) {
      if (is_judged(t)) {
        const int k = triangles[t][0] == v ? 0 : (triangles[t][1] == v ? 1 : 2);
        corner_cosine[t][k] = oriented_cosine(points, triangles[t], shapes.area[t], T);
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
  std::vector<std::uint8_t> is_done(vertex_count, 0);
  Linearization linearization;
  Eigen::MatrixXd near_tangent;
  std::vector<int> ring;
  std::vector<int> next_ring;
  for (int v = 0; v < vertex_count; ++v) {
    if (is_done[v] || topology.vertex_triangles(v).empty() || !view.is_finite_vertex[v]) {
      continue;
    }
    is_done[v] = 1;
    if (!linearization.factor(geometry.problem, points.col(v))) {
      continue;  // DF rank deficient at the vertex: not judged there
    }
    judge_corners(v, linearization.tangent_basis());
    if (!is_sparse) {
      continue;
    }
    ring.assign(1, v);
    for (int rings = 0; rings < 2; ++rings) {
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
  auto corner_of = [&](int t, int v) {
    return triangles[t][0] == v ? 0 : (triangles[t][1] == v ? 1 : 2);
  };
  // Folds across interior manifold edges.
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
    for (int v : topology.edge(e)) {
      const double sa = corner_cosine[a][corner_of(a, v)];
      const double sb = corner_cosine[b][corner_of(b, v)];
      if (std::isnan(sa) || std::isnan(sb)) {
        continue;
      }
      ++judged;
      votes += (opposite ? sa * sb < 0 : sa * sb > 0) ? 1 : 0;
    }
    if (judged > 0 && votes == judged) {
      ++folds[a];
      ++folds[b];
      folded_pairs.emplace_back(a, b);
    }
  }
  std::vector<std::uint8_t> flipped(count, 0);
  for (int t = 0; t < count; ++t) {
    flipped[t] = folds[t] > 0 && 2 * folds[t] > interior_edges[t];
  }
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
      ++result.unoriented_triangle_count;
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
      const int n = view.mesh.ambient_dimension();
      out << triangle_name(view.original[t], triangles[t]) << " near "
          << describe_point(centroid(points, triangles[t])) << ": ";
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

// Lifts the planar point x (coordinates in the orthonormal basis U at origin o) to R^n.
Eigen::VectorXd lift(const Eigen::VectorXd& o, const Eigen::MatrixXd& U, const Eigen::Vector2d& x) {
  return o + U * x;
}

// 2. Overlap. Two triangles that share no edge must not cover the same part of M. Candidates:
// every pair within 0.25·(longest edge) of each other in R^n (nearby_triangle_pairs, expected
// linear time); 0.25·h exceeds the chord errors of both triangles (≤ κh²/8), so two triangles
// on opposite sides of M are found too. A candidate pair is projected onto the plane of the
// better aligned of the two (larger |s_t|): within O(κh) of the tangent plane of M there and
// needing no factorisation; the planar intersection is clipped exactly. If it exceeds
// overlap_area_ratio of the smaller area, its centroid (inside both projections) is lifted to
// q₁ on the reference triangle and projected onto M: p = P(q₁). The second triangle covers
// p if M's normal space at p meets it, at q₂; it covers the same part of M, and not a close
// sheet, if P(q₂) returns to p: |P(q₂) − p| ≤ overlap_same_point_ratio · |q₂ − p|.
void check_overlaps(const MeshView& view, const GeometricInput& geometry,
                    const ValidationOptions& options, DefectRecorder& recorder,
                    MeshValidation& result) {
  const MeshTopology& topology = view.topology;
  const std::vector<Triangle>& triangles = topology.triangles();
  const TriangleShapes& shapes = view.shapes;
  const auto points = view.mesh.points();
  const int count = topology.triangle_count();
  const int n = view.mesh.ambient_dimension();
  std::vector<double> margins(count, -1.0);
  for (int t = 0; t < count; ++t) {
    if (shapes.is_finite[t] && !shapes.is_degenerate[t]) {
      margins[t] = 0.25 * shapes.longest_edge[t];
    }
  }
  std::vector<std::pair<int, int>> pairs = nearby_triangle_pairs(points, triangles, margins);
  std::sort(pairs.begin(), pairs.end());
  // The barycentric slack for "q₂ lies in the second triangle": the overlap's centroid lies
  // inside both projections, and lifting along M's normal at p instead of the reference
  // plane's normal moves it by O(κ·e·h), a small fraction of the triangle; 1% allows for it.
  constexpr double barycentric_slack = 0.01;
  Linearization workspace;
  // Scratch for the planar test, which runs for every candidate pair: no allocation in it.
  Eigen::MatrixXd U(n, 2);
  Eigen::VectorXd o(n);
  Eigen::VectorXd d(n);
  Eigen::Matrix<double, 2, 3> a;
  Eigen::Matrix<double, 2, 3> b;
  for (const auto& [s, t] : pairs) {
    int shared = 0;
    for (int v : triangles[s]) {
      shared += (v == triangles[t][0] || v == triangles[t][1] || v == triangles[t][2]) ? 1 : 0;
    }
    if (shared >= 2) {
      continue;  // neighbours across an edge (or a duplicate, reported as such)
    }
    const auto alignment = [&](int r) {
      const double c = shapes.oriented_cosine[r];
      return std::isnan(c) ? -1.0 : std::abs(c);
    };
    const int reference = alignment(s) >= alignment(t) ? s : t;
    const int other = reference == s ? t : s;
    // Orthonormal basis of the reference plane from its longest edge and the apex's offset
    // from that edge (accurate for thin triangles; see area_and_longest_squared).
    const Triangle& r = triangles[reference];
    int k = 0;
    for (int j = 1; j < 3; ++j) {
      if ((points.col(r[(j + 1) % 3]) - points.col(r[j])).squaredNorm() >
          (points.col(r[(k + 1) % 3]) - points.col(r[k])).squaredNorm()) {
        k = j;
      }
    }
    o = points.col(r[k]);
    d = points.col(r[(k + 1) % 3]) - o;
    U.col(0) = d / d.norm();
    d = points.col(r[(k + 2) % 3]) - o;  // the apex
    d -= d.dot(U.col(0)) * U.col(0);
    U.col(1) = d / d.norm();
    for (int j = 0; j < 3; ++j) {
      d = points.col(r[j]) - o;
      a.col(j).noalias() = U.transpose() * d;
      d = points.col(triangles[other][j]) - o;
      b.col(j).noalias() = U.transpose() * d;
    }
    const PlanarOverlap overlap = triangle_intersection(a, b);
    const double smaller_area = std::min(shapes.area[s], shapes.area[t]);
    if (!(overlap.area > options.overlap_area_ratio * smaller_area)) {
      continue;
    }
    Eigen::VectorXd p = lift(o, U, overlap.centroid);
    if (!project_onto_manifold(geometry.problem, p, workspace) || !workspace.is_factored()) {
      continue;  // no point of M to compare at: left unjudged
    }
    const Eigen::MatrixXd& T = workspace.tangent_basis();
    // q₂ = b₀ + E·w on the other triangle's plane with Tᵀ(q₂ − p) = 0.
    const Triangle& o_tri = triangles[other];
    const Eigen::VectorXd b0 = points.col(o_tri[0]);
    Eigen::MatrixXd E(n, 2);
    E.col(0) = points.col(o_tri[1]) - b0;
    E.col(1) = points.col(o_tri[2]) - b0;
    const Eigen::Matrix2d TE = T.transpose() * E;
    if (std::abs(TE.determinant()) <= 1e-3 * 2.0 * shapes.area[other]) {
      continue;  // the other triangle stands across M at p (a flipped triangle if anything)
    }
    const Eigen::Vector2d w = TE.inverse() * (T.transpose() * (p - b0));
    if (std::min({1.0 - w.x() - w.y(), w.x(), w.y()}) < -barycentric_slack) {
      continue;  // M's normal at p misses the other triangle: it does not cover p
    }
    const Eigen::VectorXd q2 = b0 + E * w;
    Eigen::VectorXd p2 = q2;
    if (!project_onto_manifold(geometry.problem, p2, workspace)) {
      continue;
    }
    // The floor is the projection's accuracy (1e-13·(1 + ‖x‖)) with a margin.
    const double floor = 1e-10 * (1.0 + p.lpNorm<Eigen::Infinity>());
    if ((p2 - p).norm() > options.overlap_same_point_ratio * (q2 - p).norm() + floor) {
      continue;  // another sheet of M (close sheets, the far side of a thin tube)
    }
    result.overlapping_triangle_pairs.emplace_back(view.original[s], view.original[t]);
    recorder.record(MeshDefectKind::OverlappingTriangles, [&] {
      std::ostringstream out;
      out.precision(3);
      out << triangle_name(view.original[s], triangles[s]) << " and "
          << triangle_name(view.original[t], triangles[t]) << " both cover M near "
          << describe_point(p) << ": overlap " << 100.0 * overlap.area / smaller_area
          << "% of the smaller" << (shared == 1 ? " (they share one vertex: a folded fan)" : "");
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
  for (int v = 0; v < view.mesh.vertex_count(); ++v) {
    if (!view.is_finite_vertex[v]) {
      continue;  // reported as a non-finite coordinate
    }
    const auto x = points.col(v);
    const double tolerance = options.domain_tolerance_ratio * (1.0 + x.lpNorm<Eigen::Infinity>());
    if (domain.contains(x, tolerance)) {
      continue;
    }
    result.vertices_outside_domain.push_back(v);
    recorder.record(MeshDefectKind::VertexOutsideDomain, [&] {
      const BoundaryDistance nearest = domain.boundary_distance(x);
      const HalfSpace& face = domain.half_spaces()[nearest.nearest_half_space];
      std::ostringstream out;
      out.precision(3);
      out << "vertex " << v << " at " << describe_point(x) << " is " << -nearest.signed_distance
          << " outside the domain ("
          << (face.label.empty() ? "half-space " + std::to_string(nearest.nearest_half_space)
                                 : face.label)
          << ")";
      return out.str();
    });
  }
}

}  // namespace

std::string_view to_string(MeshDefectKind kind) {
  switch (kind) {
    case MeshDefectKind::IndexOutOfRange:
      return "index out of range";
    case MeshDefectKind::RepeatedIndex:
      return "repeated index";
    case MeshDefectKind::DuplicateTriangle:
      return "duplicate triangle";
    case MeshDefectKind::NonManifoldEdge:
      return "non-manifold edge";
    case MeshDefectKind::NonManifoldVertex:
      return "non-manifold vertex";
    case MeshDefectKind::InconsistentOrientation:
      return "inconsistent orientation";
    case MeshDefectKind::UnreferencedVertex:
      return "unreferenced vertex";
    case MeshDefectKind::DegenerateTriangle:
      return "degenerate triangle";
    case MeshDefectKind::NonFiniteCoordinate:
      return "non-finite coordinate";
    case MeshDefectKind::FlippedTriangle:
      return "flipped triangle";
    case MeshDefectKind::OverlappingTriangles:
      return "overlapping triangles";
    case MeshDefectKind::VertexOutsideDomain:
      return "vertex outside domain";
  }
  return "unknown defect";
}

int MeshValidation::count(MeshDefectKind kind) const {
  for (const MeshDefect& defect : defects) {
    if (defect.kind == kind) {
      return defect.count;
    }
  }
  return 0;
}

std::string MeshValidation::report() const {
  std::ostringstream out;
  out << "mesh in R^" << ambient_dimension << ": " << triangle_count << " triangles, "
      << vertex_count << " vertices (" << referenced_vertex_count << " referenced), " << edge_count
      << " edges\n";
  out << "topology: " << component_count << (component_count == 1 ? " component" : " components")
      << ", Euler characteristic " << euler_characteristic << ", ";
  if (is_closed()) {
    out << "closed";
  } else {
    out << boundary_edge_count
        << (boundary_edge_count == 1 ? " boundary edge in " : " boundary edges in ")
        << boundary_loop_count << (boundary_loop_count == 1 ? " loop" : " loops");
    if (!boundary_loop_vertex_counts.empty()) {
      out << " of " << index_list(boundary_loop_vertex_counts, [](int n) { return n; })
          << " vertices";
    }
  }
  if (is_orientable) {
    out << ", orientable";
  } else {
    out << ", non-orientable (" << non_orientable_component_count
        << (non_orientable_component_count == 1 ? " component)" : " components)");
  }
  if (genus >= 0) {
    out << ", genus " << genus;
  }
  out << "\n";
  if (is_geometry_checked) {
    out << "geometry: orientation along M, overlaps on M and the domain checked";
    if (unoriented_triangle_count > 0) {
      out << " (" << unoriented_triangle_count
          << (unoriented_triangle_count == 1 ? " triangle" : " triangles")
          << " not oriented: DF singular at the centroid)";
    }
    out << "\n";
  } else {
    out << "geometry: not checked (no problem given)\n";
  }
  if (is_valid()) {
    out << "valid: no defects\n";
    return out.str();
  }
  out << "invalid:\n";
  for (const MeshDefect& defect : defects) {
    out << "  " << to_string(defect.kind) << ": " << defect.count << "\n";
    for (const std::string& example : defect.examples) {
      out << "    " << example << "\n";
    }
    if (defect.count > static_cast<int>(defect.examples.size())) {
      out << "    ... and " << defect.count - static_cast<int>(defect.examples.size()) << " more\n";
    }
  }
  return out.str();
}

namespace {

void check_options(const ValidationOptions& options) {
  TESSERA_CHECK(options.degenerate_area_ratio >= 0,
                "ValidationOptions::degenerate_area_ratio = " << options.degenerate_area_ratio
                                                              << " must be >= 0");
  TESSERA_CHECK(options.max_examples >= 0,
                "ValidationOptions::max_examples = " << options.max_examples << " must be >= 0");
}

// The combinatorial checks, then the geometric ones if `geometry` is given.
MeshValidation validate_mesh(const TriangleMesh& mesh, const ValidationOptions& options,
                             const GeometricInput* geometry) {
  using Kind = MeshDefectKind;
  DefectRecorder recorder(options.max_examples);
  MeshValidation result;
  const int vertex_count = mesh.vertex_count();
  const std::vector<Triangle>& triangles = mesh.triangles();
  const auto points = mesh.points();
  result.ambient_dimension = mesh.ambient_dimension();
  result.vertex_count = vertex_count;
  result.triangle_count = mesh.triangle_count();
  // " near (x, y, z)": the mean of the given vertices that exist and are finite, so that every
  // message names a place, not only indices ("" if there is none).
  auto near = [&](std::initializer_list<int> vertices) -> std::string {
    Eigen::VectorXd sum = Eigen::VectorXd::Zero(result.ambient_dimension);
    int used = 0;
    for (int v : vertices) {
      if (v >= 0 && v < vertex_count && points.col(v).allFinite()) {
        sum += points.col(v);
        ++used;
      }
    }
    return used == 0 ? std::string() : " near " + describe_point(sum / used);
  };

  // Malformed triangles (index out of range, repeated index) have no well-defined edges; they
  // are reported and left out of the topology. `kept` maps topology triangles back to mesh
  // triangles, and stays empty (the identity) in the common case that all are well-formed.
  std::vector<std::uint8_t> is_referenced(vertex_count, 0);
  std::vector<int> kept;
  bool is_every_triangle_well_formed = true;
  for (int t = 0; t < result.triangle_count; ++t) {
    const Triangle& tri = triangles[t];
    bool is_out_of_range = false;
    int bad_index = 0;  // the first index out of range, which may well be negative
    for (int v : tri) {
      if (v >= 0 && v < vertex_count) {
        is_referenced[v] = 1;
      } else if (!is_out_of_range) {
        is_out_of_range = true;
        bad_index = v;
      }
    }
    const bool is_repeated = tri[0] == tri[1] || tri[1] == tri[2] || tri[2] == tri[0];
    if (is_out_of_range || is_repeated) {
      if (is_every_triangle_well_formed) {
        is_every_triangle_well_formed = false;
        for (int s = 0; s < t; ++s) {
          kept.push_back(s);
        }
      }
    } else if (!is_every_triangle_well_formed) {
      kept.push_back(t);
    }
    if (is_out_of_range) {
      recorder.record(Kind::IndexOutOfRange, [&] {
        std::ostringstream out;
        out << triangle_text(t, tri) << near({tri[0], tri[1], tri[2]}) << " has index " << bad_index
            << " outside [0, " << vertex_count << ")";
        return out.str();
      });
    } else if (is_repeated) {
      recorder.record(Kind::RepeatedIndex, [&] {
        const int v = tri[0] == tri[1] || tri[0] == tri[2] ? tri[0] : tri[1];
        return triangle_text(t, tri) + near({tri[0], tri[1], tri[2]}) + " repeats vertex " +
               std::to_string(v);
      });
    }
  }
  std::vector<Triangle> well_formed;
  if (!is_every_triangle_well_formed) {
    well_formed.reserve(kept.size());
    for (int t : kept) {
      well_formed.push_back(triangles[t]);
    }
  }
  const MeshTopology topology(vertex_count, is_every_triangle_well_formed
                                                ? std::span<const Triangle>(triangles)
                                                : std::span<const Triangle>(well_formed));
  auto original = [&](int t) { return is_every_triangle_well_formed ? t : kept[t]; };
  const std::vector<Triangle>& topology_triangles = topology.triangles();

  result.referenced_vertex_count = topology.referenced_vertex_count();
  result.edge_count = topology.edge_count();
  result.boundary_edge_count = static_cast<int>(topology.boundary_edges().size());
  result.boundary_loop_count = topology.boundary_loop_count();
  for (int i = 0; i < result.boundary_loop_count; ++i) {
    result.boundary_loop_vertex_counts.push_back(
        static_cast<int>(topology.boundary_loop(i).size()));
  }
  result.component_count = topology.component_count();
  result.euler_characteristic = topology.euler_characteristic();

  std::vector<std::uint8_t> is_finite(vertex_count, 1);
  for (int v = 0; v < vertex_count; ++v) {
    if (!points.col(v).allFinite()) {
      is_finite[v] = 0;
      recorder.record(Kind::NonFiniteCoordinate, [&] {
        std::ostringstream out;
        out << "vertex " << v << " = (" << index_list(points.col(v), [](double x) { return x; })
            << ")";
        return out.str();
      });
    }
  }
  for (int v = 0; v < vertex_count; ++v) {
    if (!is_referenced[v]) {
      recorder.record(Kind::UnreferencedVertex, [&] {
        return "vertex " + std::to_string(v) + " at " + describe_point(points.col(v)) +
               " is in no triangle";
      });
    }
  }

  for (int e = 0; e < topology.edge_count(); ++e) {
    if (!topology.is_manifold_edge(e)) {
      recorder.record(Kind::NonManifoldEdge, [&] {
        const auto on_edge = topology.edge_triangles(e);
        std::ostringstream out;
        out << "edge (" << topology.edge(e)[0] << ", " << topology.edge(e)[1] << ")"
            << near({topology.edge(e)[0], topology.edge(e)[1]}) << " has " << on_edge.size()
            << " triangles: " << index_list(on_edge, original);
        return out.str();
      });
    }
  }

  // Two triangles with the same vertex set share all their edges, so comparing each triangle
  // with the earlier triangles on its first edge finds every duplicate in O(N).
  auto sorted = [](Triangle tri) {
    std::sort(tri.begin(), tri.end());
    return tri;
  };
  for (int t = 0; t < topology.triangle_count(); ++t) {
    const Triangle vertices = sorted(topology_triangles[t]);
    for (int u : topology.edge_triangles(topology.triangle_edges(t)[0])) {
      if (u >= t) {
        break;
      }
      if (sorted(topology_triangles[u]) == vertices) {
        recorder.record(Kind::DuplicateTriangle, [&] {
          const Triangle& tri = topology_triangles[t];
          return triangle_text(original(t), tri) + near({tri[0], tri[1], tri[2]}) + " repeats " +
                 triangle_text(original(u), topology_triangles[u]);
        });
        break;
      }
    }
  }

  // Fans: the corners at a vertex are joined across every edge at that vertex that has two or
  // more triangles. A manifold vertex has one fan; a bow tie has two or more.
  CornerSets corners(topology_triangles.size() * 3);
  for (int e = 0; e < topology.edge_count(); ++e) {
    const auto on_edge = topology.edge_triangles(e);
    for (std::size_t i = 1; i < on_edge.size(); ++i) {
      for (int v : topology.edge(e)) {
        corners.unite(corner(topology_triangles, on_edge[0], v),
                      corner(topology_triangles, on_edge[i], v));
      }
    }
  }
  std::vector<int> fan_count(vertex_count, 0);
  for (int c = 0; c < static_cast<int>(topology_triangles.size() * 3); ++c) {
    if (corners.find(c) == c) {
      ++fan_count[topology_triangles[c / 3][c % 3]];
    }
  }
  for (int v = 0; v < vertex_count; ++v) {
    if (fan_count[v] > 1) {
      recorder.record(Kind::NonManifoldVertex, [&] {
        std::vector<std::pair<int, int>> fan_and_triangle;  // only for the few examples
        for (int t : topology.vertex_triangles(v)) {
          fan_and_triangle.emplace_back(corners.find(corner(topology_triangles, t, v)), t);
        }
        std::sort(fan_and_triangle.begin(), fan_and_triangle.end());
        std::ostringstream out;
        out << "vertex " << v << near({v}) << " is shared by " << fan_count[v]
            << " fans of triangles that share no edge there: ";
        for (std::size_t i = 0; i < fan_and_triangle.size(); ++i) {
          const bool is_new_fan =
              i == 0 || fan_and_triangle[i].first != fan_and_triangle[i - 1].first;
          out << (i == 0 ? "{" : (is_new_fan ? "}, {" : ", "))
              << original(fan_and_triangle[i].second);
        }
        out << "}";
        return out.str();
      });
    }
  }

  const OrientationAssignment orientation = topology.orientation_assignment();
  for (std::uint8_t is_orientable : orientation.is_component_orientable) {
    result.non_orientable_component_count += is_orientable ? 0 : 1;
  }
  result.is_orientable = result.non_orientable_component_count == 0;
  for (int e = 0; e < topology.edge_count(); ++e) {
    if (topology.is_orientation_consistent(e)) {
      continue;
    }
    const auto on_edge = topology.edge_triangles(e);
    if (!orientation.is_component_orientable[topology.component_of(on_edge[0])]) {
      continue;  // unavoidable, as on a Möbius strip
    }
    recorder.record(Kind::InconsistentOrientation, [&] {
      const Triangle& tri = topology_triangles[on_edge[0]];
      const auto [a, b] = topology.edge(e);
      const bool is_forward = (tri[0] == a && tri[1] == b) || (tri[1] == a && tri[2] == b) ||
                              (tri[2] == a && tri[0] == b);
      std::ostringstream out;
      out << "triangles " << original(on_edge[0]) << " and " << original(on_edge[1])
          << " both traverse edge (" << a << ", " << b << ")" << near({a, b}) << " from "
          << (is_forward ? a : b) << " to " << (is_forward ? b : a)
          << "; orient_consistently() repairs this";
      return out.str();
    });
  }

  // Per topology triangle, for the geometric checks: area, longest edge, and whether it can be
  // judged at all (finite and not degenerate).
  TriangleShapes shapes(topology.triangle_count());
  for (int t = 0; t < topology.triangle_count(); ++t) {
    const Triangle& tri = topology_triangles[t];
    if (!is_finite[tri[0]] || !is_finite[tri[1]] || !is_finite[tri[2]]) {
      continue;  // reported as a non-finite coordinate
    }
    shapes.is_finite[t] = 1;
    const auto [area, longest_squared] = area_and_longest_squared(points, tri);
    shapes.area[t] = area;
    shapes.longest_edge[t] = std::sqrt(longest_squared);
    shapes.is_degenerate[t] = area <= options.degenerate_area_ratio * longest_squared ? 1 : 0;
    if (shapes.is_degenerate[t]) {
      recorder.record(Kind::DegenerateTriangle, [&] {
        std::ostringstream out;
        out << triangle_text(original(t), tri) << near({tri[0], tri[1], tri[2]}) << " has area "
            << area << " (longest edge " << std::sqrt(longest_squared) << ")";
        return out.str();
      });
    }
  }

  result.index_out_of_range_count = recorder.count(Kind::IndexOutOfRange);
  result.repeated_index_count = recorder.count(Kind::RepeatedIndex);
  result.duplicate_triangle_count = recorder.count(Kind::DuplicateTriangle);
  result.non_manifold_edge_count = recorder.count(Kind::NonManifoldEdge);
  result.non_manifold_vertex_count = recorder.count(Kind::NonManifoldVertex);
  result.inconsistent_orientation_count = recorder.count(Kind::InconsistentOrientation);
  result.unreferenced_vertex_count = recorder.count(Kind::UnreferencedVertex);
  result.degenerate_triangle_count = recorder.count(Kind::DegenerateTriangle);
  result.non_finite_vertex_count = recorder.count(Kind::NonFiniteCoordinate);
  if (geometry != nullptr) {
    std::vector<int> original_index(topology.triangle_count());
    for (int t = 0; t < topology.triangle_count(); ++t) {
      original_index[t] = original(t);
    }
    const MeshView view{mesh, topology, original_index, shapes, is_finite};
    check_orientation(view, *geometry, options, recorder, result);
    check_overlaps(view, *geometry, options, recorder, result);
    check_domain(view, *geometry, options, recorder, result);
    result.is_geometry_checked = true;
    result.flipped_triangle_count = recorder.count(Kind::FlippedTriangle);
    result.overlapping_pair_count = recorder.count(Kind::OverlappingTriangles);
    result.vertex_outside_domain_count = recorder.count(Kind::VertexOutsideDomain);
  }
  result.defects = recorder.take_present();

  // For a closed orientable surface each component has chi_i = 2 - 2 g_i.
  if (result.is_closed() && result.is_orientable && result.is_manifold() &&
      is_every_triangle_well_formed) {
    result.genus = result.component_count - result.euler_characteristic / 2;
  }
  return result;
}

}  // namespace

MeshValidation validate(const TriangleMesh& mesh, const ValidationOptions& options) {
  check_options(options);
  return validate_mesh(mesh, options, nullptr);
}

MeshValidation validate(const TriangleMesh& mesh, const ImplicitProblem& problem,
                        const Domain& domain, const ValidationOptions& options) {
  check_options(options);
  TESSERA_CHECK(options.min_tangent_cosine >= 0 && options.min_tangent_cosine <= 1,
                "ValidationOptions::min_tangent_cosine = " << options.min_tangent_cosine
                                                           << " must lie in [0, 1]");
  TESSERA_CHECK(
      options.overlap_area_ratio >= 0,
      "ValidationOptions::overlap_area_ratio = " << options.overlap_area_ratio << " must be >= 0");
  TESSERA_CHECK(options.overlap_same_point_ratio >= 0,
                "ValidationOptions::overlap_same_point_ratio = " << options.overlap_same_point_ratio
                                                                 << " must be >= 0");
  TESSERA_CHECK(options.domain_tolerance_ratio >= 0,
                "ValidationOptions::domain_tolerance_ratio = " << options.domain_tolerance_ratio
                                                               << " must be >= 0");
  TESSERA_CHECK(mesh.ambient_dimension() == problem.ambient_dimension(),
                "the mesh is in R^" << mesh.ambient_dimension() << " but problem '"
                                    << problem.name() << "' is in R^"
                                    << problem.ambient_dimension());
  TESSERA_CHECK(domain.is_unbounded() || domain.ambient_dimension() == mesh.ambient_dimension(),
                "the domain (" << domain.describe() << ") is in R^" << domain.ambient_dimension()
                               << " but the mesh is in R^" << mesh.ambient_dimension());
  const Eigen::VectorXd weights = metric_weights(problem);
  if (weights.size() > 0) {
    // Judged in the metric's coordinates y = W x, as the covering methods built the mesh: the
    // overlap and same-point tests compare lengths.
    const ScaledProblem scaled(problem, weights);
    const Domain scaled_domain = scale_domain(domain, weights);
    const TriangleMesh scaled_mesh(weights.asDiagonal() * mesh.points(), mesh.triangles());
    const GeometricInput geometry{scaled, scaled_domain};
    return validate_mesh(scaled_mesh, options, &geometry);
  }
  const GeometricInput geometry{problem, domain};
  return validate_mesh(mesh, options, &geometry);
}

}  // namespace tessera
