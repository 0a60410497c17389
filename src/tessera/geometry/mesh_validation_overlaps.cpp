// SPDX-License-Identifier: MIT
// The overlap check of validate(): two triangles that share no edge must not cover the same part
// of M (candidates in R^n, then the test on M). The mathematics is in docs/validation.md
// ("Overlap"); the comments here say why each step is sound.
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
#include "tessera/geometry/spatial_hash.h"
#include "tessera/geometry/triangle_intersection.h"

namespace tessera::detail {
namespace {

// Lifts the planar point x (coordinates in the orthonormal basis U at origin o) to R^n.
Eigen::VectorXd lift(const Eigen::VectorXd& o, const Eigen::MatrixXd& U, const Eigen::Vector2d& x) {
  return o + U * x;
}

// What the test on M found for a pair whose projections onto a plane overlap.
struct OverlapOnManifold {
  bool is_overlap = false;
  Eigen::VectorXd point;  // a point of M that both triangles cover
  double area = 0.0;      // of the overlap in the chart (M's tangent plane at `point`)
  double width = 0.0;     // its area / perimeter
  // A point of one triangle lies deeper between two sheets than half its distance to the other
  // triangle (P jumps between them): the triangles reach past where projecting onto M is one
  // to one, and `depth` is that point's distance to M.
  double depth = 0.0;
};

// Do triangles s and t of different components cross where two sheets of M cross
// (ValidationOptions::crossing_plane_cosine)? Only components covered apart meet that way: a
// covering that reaches a crossing keeps to its sheet (the atlas's min_sheet_cosine), and two
// components over one sheet lie in nearly one plane where they meet, so they are judged on M.
bool is_sheet_crossing(const MeshView& view, int s, int t, const ValidationOptions& options) {
  const MeshTopology& topology = view.topology;
  if (topology.component_of(s) == topology.component_of(t)) {
    return false;
  }
  const double along_s = std::abs(view.shapes.oriented_cosine[s]);  // NaN: not judged
  const double along_t = std::abs(view.shapes.oriented_cosine[t]);
  if (!(along_s >= options.crossing_alignment && along_t >= options.crossing_alignment)) {
    return false;
  }
  // |det(U_sᵀU_t)| = |det(EᵀF)| / sqrt(det(EᵀE)·det(FᵀF)) for the edge vectors E of s, F of t.
  const auto points = view.mesh.points();
  const Triangle& a = view.topology.triangles()[s];
  const Triangle& b = view.topology.triangles()[t];
  std::array<Eigen::VectorXd, 4> edge = {
      points.col(a[1]) - points.col(a[0]), points.col(a[2]) - points.col(a[0]),
      points.col(b[1]) - points.col(b[0]), points.col(b[2]) - points.col(b[0])};
  std::array<double, 10> gram;  // the upper triangle of the 4×4 Gram matrix of the edges
  int k = 0;
  for (int i = 0; i < 4; ++i) {
    for (int j = i; j < 4; ++j) {
      gram[static_cast<std::size_t>(k++)] = edge[i].dot(edge[j]);
    }
  }
  view.mesh.space().sum(gram.data(), 10);  // over the ranks of a split mesh (else nothing)
  const auto at = [&](int i, int j) {
    const int lo = std::min(i, j), hi = std::max(i, j);
    return gram[static_cast<std::size_t>(lo * 4 - lo * (lo - 1) / 2 + (hi - lo))];
  };
  const double cross = at(0, 2) * at(1, 3) - at(0, 3) * at(1, 2);
  const double own_s = at(0, 0) * at(1, 1) - at(0, 1) * at(0, 1);
  const double own_t = at(2, 2) * at(3, 3) - at(2, 3) * at(2, 3);
  if (!(own_s > 0.0 && own_t > 0.0)) {
    return false;
  }
  return std::abs(cross) < options.crossing_plane_cosine * std::sqrt(own_s * own_t);
}

// The chart's distortion bound grows with the chord error times the overlap's reach, so for
// coarse triangles (chord error a tenth of M's radius) it exceeds the width even of two triangles
// that cover the same part of M (stress campaign seed 2034, sphere_box front case 664: two
// triangles of edge 1 whose corners lie 0.003 apart). Where the chart's overlap lies deep inside
// both triangles (its centroid at barycentric coordinates ≥ kDeepInside in each), the pair is
// judged without the chart instead: y = P(q₁) is covered by both if each triangle has a point x
// with x − y normal to M at y, inside the triangle, whose projection P(x) is y (not a point of
// another sheet). Such an x projects onto y exactly, so no distortion enters.
constexpr double kDeepInside = 0.02;
// Inside a triangle by more than rounding: its smallest barycentric coordinate.
constexpr double kInsideMargin = 1e-3;
// P(x) returns to y up to Gauss–Newton's O(κ|x − y|²) (its steps are normal to M only to first
// order); from the far side of a thin tube it lands about |x − y| away. A test of its own,
// independent of overlap_same_point_ratio, so that each test on M keeps other sheets apart alone.
constexpr double kFootReturnRatio = 0.25;

// The point x = x₀ + E·w of triangle `tri` with Tᵀ(x − y) = 0 (T: M's tangent basis at y), and
// its smallest barycentric coordinate; -1 where the triangle's plane contains a normal of M.
double normal_foot(const MeshView& view, const Triangle& tri, const Eigen::VectorXd& y,
                   const Eigen::MatrixXd& T, Eigen::VectorXd& foot) {
  const auto points = view.mesh.points();
  Eigen::Matrix<double, 2, 3> image;
  for (int k = 0; k < 3; ++k) {
    image.col(k) = T.transpose() * (points.col(tri[k]) - y);
  }
  view.mesh.space().sum(image.data(), 6);
  Eigen::Matrix2d edges;
  edges.col(0) = image.col(1) - image.col(0);
  edges.col(1) = image.col(2) - image.col(0);
  const double scale = edges.cwiseAbs().maxCoeff();
  if (!(std::abs(edges.determinant()) > 1e-12 * scale * scale)) {
    return -1.0;
  }
  const Eigen::Vector2d w = edges.inverse() * (-image.col(0));
  foot = points.col(tri[0]) + w.x() * (points.col(tri[1]) - points.col(tri[0])) +
         w.y() * (points.col(tri[2]) - points.col(tri[0]));
  return std::min({1.0 - w.x() - w.y(), w.x(), w.y()});
}

// y (a point of M) is the projection of a point inside each triangle (see kDeepInside).
bool projects_from_both(const MeshView& view, const GeometricInput& geometry, const Triangle& first,
                        const Triangle& second, Eigen::VectorXd y, Linearization& workspace) {
  if (!project_onto_manifold(geometry.problem, y, workspace)) {
    return false;  // leaves the workspace at y: DF and M's tangent basis there
  }
  const Eigen::MatrixXd T = workspace.tangent_basis();
  const AmbientSpace& space = view.mesh.space();
  const double floor = 1e-10 * (1.0 + space.maximum(y.lpNorm<Eigen::Infinity>()));
  for (const Triangle* tri : {&first, &second}) {
    Eigen::VectorXd foot;
    if (!(normal_foot(view, *tri, y, T, foot) > kInsideMargin)) {
      return false;
    }
    // y is a point of M nearest to the foot; P(foot) = y unless a nearer sheet takes it.
    Eigen::VectorXd projected = foot;
    if (!project_onto_manifold(geometry.problem, projected, workspace) ||
        space.distance(projected, y) > kFootReturnRatio * space.distance(foot, y) + floor) {
      return false;
    }
  }
  return true;
}

// Do the triangles `first` and `second` cover the same part of M near the point p of M (the
// projection of a point where their planar projections overlap)? Both are mapped into the chart
// Tᵀ(x − p) of M's tangent plane at p. Restricted to M near p this chart is one to one, and a
// point x of a triangle, at distance e from M, lands where its projection P(x) onto M lands up
// to e·|Tᵀν| ≤ e·κ|x − p| (ν: M's normal at P(x)). So the triangles' images overlap where their
// projections onto M do, up to that distortion within the overlap's reach ρ from p: an overlap
// whose width (area / perimeter) exceeds 2·E·κ·ρ, E the larger chord error, survives moving
// every edge inward by the distortion, and is an overlap on M however thin the triangles are
// (crossing needles 0.1° wide overlap in 1e-7 of their area). Then the overlap's centroid c is
// lifted onto each triangle (the points q₁, q₂ whose chart image is c: inside both by
// construction, so no slack in barycentric coordinates, which a needle's width makes
// meaningless) and projected onto M: on the same sheet P(q₁) and P(q₂) coincide up to
// |q₁ − q₂|·κρ; on another sheet (the trough's, the far side of a thin tube) they stay about
// |q₁ − q₂| apart (overlap_same_point_ratio between the two).
OverlapOnManifold overlap_on_manifold(const MeshView& view, const GeometricInput& geometry,
                                      const Triangle& first, const Triangle& second,
                                      Eigen::VectorXd p, Linearization& workspace,
                                      const ValidationOptions& options) {
  OverlapOnManifold found;
  // Two passes: the chart at p (the projection of a point of the planar overlap), then the
  // chart at the projection of the point of `first` over that overlap's centroid, so that the
  // overlap's reach ρ from the chart's origin, which the distortion bound grows with, is about
  // half its diameter.
  for (int pass = 0; pass < 2; ++pass) {
    const auto points = view.mesh.points();
    const AmbientSpace& space = view.mesh.space();
    const Eigen::MatrixXd T = workspace.tangent_basis();  // a copy: the workspace projects again
    // Per corner (three of `first`, then three of `second`): Tᵀ(x − p) and |x − p|².
    Eigen::Matrix<double, 3, 6> measures;
    Eigen::VectorXd d;
    for (int k = 0; k < 6; ++k) {
      d = points.col(k < 3 ? first[k] : second[k - 3]) - p;
      measures(0, k) = T.col(0).dot(d);
      measures(1, k) = T.col(1).dot(d);
      measures(2, k) = d.squaredNorm();
    }
    space.sum(measures.data(), 18);  // over the ranks of a split mesh (else nothing)
    const Eigen::Matrix<double, 2, 3> a = measures.block<2, 3>(0, 0);
    const Eigen::Matrix<double, 2, 3> b = measures.block<2, 3>(0, 3);
    const PlanarOverlap chart = triangle_intersection(a, b);
    if (!(chart.area > 0.0)) {
      return found;
    }
    // The lift of c onto a triangle: x₀ + E·w with Tᵀ(x₀ + E·w − p) = c.
    const auto lift_onto = [&](const Eigen::Matrix<double, 2, 3>& image, const Triangle& tri,
                               Eigen::VectorXd& q, double& inner) {
      Eigen::Matrix2d edges;
      edges.col(0) = image.col(1) - image.col(0);
      edges.col(1) = image.col(2) - image.col(0);
      const double longest = std::max(
          {edges.col(0).norm(), edges.col(1).norm(), (image.col(2) - image.col(1)).norm()});
      if (!(std::abs(edges.determinant()) > 1e-12 * longest * longest)) {
        return false;  // the triangle stands across M at p (a flipped triangle if anything)
      }
      const Eigen::Vector2d w = edges.inverse() * (chart.centroid - image.col(0));
      inner = std::min({1.0 - w.x() - w.y(), w.x(), w.y()});
      q = points.col(tri[0]) + w.x() * (points.col(tri[1]) - points.col(tri[0])) +
          w.y() * (points.col(tri[2]) - points.col(tri[0]));
      return true;
    };
    Eigen::VectorXd q1, q2;
    double inner1 = 0.0, inner2 = 0.0;
    if (!lift_onto(a, first, q1, inner1) || !lift_onto(b, second, q2, inner2)) {
      return found;
    }
    Eigen::VectorXd p1 = q1, p2 = q2;
    if (!project_onto_manifold(geometry.problem, p1, workspace)) {
      return found;  // left unjudged
    }
    if (pass == 0) {
      p = p1;
      continue;
    }
    if (!project_onto_manifold(geometry.problem, p2, workspace)) {
      return found;
    }
    const double floor = 1e-10 * (1.0 + space.maximum(p.lpNorm<Eigen::Infinity>()));
    const double apart = space.distance(q1, q2);
    // Another sheet of M (close sheets, the far side of a thin tube): P(q₁) and P(q₂) far apart,
    // and each of q₁, q₂ nearer to M than to the other. A point that lies deeper than that
    // (0.065 inside a tube of radius 0.07, 0.056 below its neighbour: a triangle that spans the
    // tube, the stress campaign's thin_torus front case 1108) follows no sheet; its triangle
    // covers the part of M its neighbour covers, whatever P(q₂) says.
    const double deepest = std::max(space.distance(q1, p1), space.distance(q2, p2));
    if (space.distance(p1, p2) > options.overlap_same_point_ratio * apart + floor) {
      if (deepest < options.overlap_sheet_depth_ratio * apart) {
        return found;  // another sheet
      }
      // No chart at p maps both triangles onto M (the distortion bound below assumes each lies
      // along M): the two cover the same part of M as far as any projection can tell.
      found.is_overlap = true;
      found.point = std::move(p1);
      found.area = chart.area;
      found.width = chart.width();
      found.depth = deepest;
      return found;
    }
    // M's curvature near p from the corners' heights over the chart (height ≈ κr²/2), and the
    // larger chord error: measured at q₁, q₂, or κh²/8 for the triangles' longest edge h.
    double curvature = 0.0;
    double longest_squared = 0.0;
    for (int k = 0; k < 6; ++k) {
      longest_squared =
          std::max(longest_squared, (measures.col(k).head<2>() -
                                     measures.col(k < 3 ? (k + 1) % 3 : 3 + (k + 1) % 3).head<2>())
                                        .squaredNorm());
    }
    for (int k = 0; k < 6; ++k) {
      const double r_squared = measures.col(k).head<2>().squaredNorm();
      if (r_squared >= 0.01 * longest_squared && r_squared > 0.0) {
        const double height = std::sqrt(std::max(0.0, measures(2, k) - r_squared));
        curvature = std::max(curvature, 2.0 * height / r_squared);
      }
    }
    // Each triangle's image moves by at most its chord error times κρ: at most the larger of the
    // error measured over the overlap's centroid and κh²/8 for its own longest edge h.
    double distortion = 0.0;
    for (int k = 0; k < 2; ++k) {
      double longest = 0.0;
      for (int j = 0; j < 3; ++j) {
        longest = std::max(longest, (measures.col(3 * k + j).head<2>() -
                                     measures.col(3 * k + (j + 1) % 3).head<2>())
                                        .squaredNorm());
      }
      const double chord_error = std::max(k == 0 ? space.distance(q1, p1) : space.distance(q2, p2),
                                          curvature * longest / 8.0);
      distortion += chord_error * curvature * chart.reach;
    }
    const double rounding = 1e-12 * (1.0 + space.maximum(p.lpNorm<Eigen::Infinity>()));
    if (!(chart.width() > distortion + rounding) &&
        !(std::min(inner1, inner2) >= kDeepInside &&
          projects_from_both(view, geometry, first, second, p1, workspace))) {
      return found;
    }
    found.is_overlap = true;
    found.point = std::move(p1);
    found.area = chart.area;
    found.width = chart.width();
    return found;
  }
  return found;
}

// `pairs` (s, t), s < count, each once, in the order of (s, t): by a counting sort on s and a sort
// of each s's few partners on threads (std::sort of 10⁷ pairs was 0.4 s of one thread).
void sort_by_first_triangle(std::vector<std::pair<int, int>>& pairs, int count) {
  std::vector<std::size_t> start(static_cast<std::size_t>(count) + 1, 0);
  for (const auto& pair : pairs) {
    ++start[static_cast<std::size_t>(pair.first) + 1];
  }
  for (int s = 0; s < count; ++s) {
    start[static_cast<std::size_t>(s) + 1] += start[static_cast<std::size_t>(s)];
  }
  std::vector<std::pair<int, int>> sorted(pairs.size());
  std::vector<std::size_t> next(start.begin(), start.end() - 1);
  for (const auto& pair : pairs) {
    sorted[next[static_cast<std::size_t>(pair.first)]++] = pair;
  }
  pairs = std::vector<std::pair<int, int>>();  // its memory back before the partners' sorts
  parallel_for(count, thread_count(), [&](int s) {
    std::sort(sorted.begin() + static_cast<std::ptrdiff_t>(start[static_cast<std::size_t>(s)]),
              sorted.begin() + static_cast<std::ptrdiff_t>(start[static_cast<std::size_t>(s) + 1]));
  });
  pairs = std::move(sorted);
}

}  // namespace

// 2. Overlap. Two triangles that share no edge must not cover the same part of M. Candidates:
// every pair within 0.25·(longest edge) of each other in R^n (nearby_triangle_pairs, expected
// linear time); 0.25·h exceeds the chord errors of both triangles (≤ κh²/8), so two triangles
// on opposite sides of M are found too. A candidate pair is projected onto the plane of the
// better aligned of the two (larger |s_t|), needing no factorisation, and the planar
// intersection is clipped exactly; any overlap beyond rounding (overlap_area_ratio) is judged
// on M by overlap_on_manifold, in M's own tangent plane.
void check_overlaps(const MeshView& view, const GeometricInput& geometry,
                    const ValidationOptions& options, CheckStop& stop, DefectRecorder& recorder,
                    MeshValidation& result) {
  const MeshTopology& topology = view.topology;
  const std::vector<Triangle>& triangles = topology.triangles();
  const TriangleShapes& shapes = view.shapes;
  const auto points = view.mesh.points();
  const AmbientSpace& space = view.mesh.space();
  const bool split = space.is_distributed();  // SPMD: reduce over the ranks
  const int count = topology.triangle_count();
  const int n = view.mesh.ambient_dimension();  // rows held here
  std::vector<double> margins(count, -1.0);
  for (int t = 0; t < count; ++t) {
    if (shapes.is_finite[t] && !shapes.is_degenerate[t]) {
      margins[t] = 0.25 * shapes.longest_edge[t];
    }
  }
  std::vector<std::pair<int, int>> pairs =
      nearby_triangle_pairs(points, triangles, margins, split ? view.mesh.shared_space() : nullptr);
  sort_by_first_triangle(pairs, count);
  // The planar test runs for every candidate pair (about ten per triangle), and at large n its
  // cost is the passes over n-vectors: the reference triangle's frame (origin, orthonormal U,
  // its own corners in U) is kept for the last two references (pairs come sorted by their first
  // triangle, which is preferred as the reference, so one of the two recurs), and so are the
  // coordinates in it of the vertices projected so far (the other triangles of a fan share
  // vertices). What is kept only saves work: each value is the same computed again.
  struct ReferenceFrame {
    int triangle = -1;
    Eigen::VectorXd origin;
    Eigen::MatrixXd U;
    Eigen::Matrix<double, 2, 3> corners;
    std::vector<std::pair<int, Eigen::Vector2d>> projected;  // (vertex, its coordinates in U)
  };
  // One planar tester per block of pairs (its own frames), so that blocks run on threads.
  struct PlanarTester {
    std::array<ReferenceFrame, 2> frames;
    int newest_frame = 0;
    Eigen::VectorXd d;
  };
  const auto frame_of = [&](PlanarTester& tester, int reference) -> ReferenceFrame& {
    for (ReferenceFrame& frame : tester.frames) {
      if (frame.triangle == reference) {
        return frame;
      }
    }
    tester.newest_frame = 1 - tester.newest_frame;
    ReferenceFrame& frame = tester.frames[static_cast<std::size_t>(tester.newest_frame)];
    frame.triangle = reference;
    frame.projected.clear();
    Eigen::VectorXd& d = tester.d;
    // Orthonormal basis of the reference plane from its longest edge and the apex's offset
    // from that edge (accurate for thin triangles; see triangle_area_and_longest_squared).
    const Triangle& r = triangles[reference];
    std::array<double, 3> squared_length;
    for (int j = 0; j < 3; ++j) {
      squared_length[j] = (points.col(r[(j + 1) % 3]) - points.col(r[j])).squaredNorm();
    }
    if (split) {
      space.sum(squared_length.data(), 3);
    }
    int k = 0;
    for (int j = 1; j < 3; ++j) {
      if (squared_length[j] > squared_length[k]) {
        k = j;
      }
    }
    frame.origin = points.col(r[k]);
    frame.U.resize(n, 2);
    d = points.col(r[(k + 1) % 3]) - frame.origin;
    frame.U.col(0) = d / (split ? space.norm(d) : d.norm());
    d = points.col(r[(k + 2) % 3]) - frame.origin;  // the apex
    d -= (split ? space.dot(d, frame.U.col(0)) : d.dot(frame.U.col(0))) * frame.U.col(0);
    frame.U.col(1) = d / (split ? space.norm(d) : d.norm());
    for (int j = 0; j < 3; ++j) {
      d = points.col(r[j]) - frame.origin;
      frame.corners.col(j).noalias() = frame.U.transpose() * d;
    }
    if (split) {
      space.sum(frame.corners.data(), 6);
    }
    return frame;
  };
  // Pairs the fan check (check_fan_arcs) has reported already.
  const std::set<std::pair<int, int>> known(result.overlapping_triangle_pairs.begin(),
                                            result.overlapping_triangle_pairs.end());
  // A pair whose projections onto the reference plane overlap beyond rounding: judged on M.
  struct PlanarOverlapFound {
    std::size_t pair = 0;
    int shared = 0;          // vertices the two triangles share
    Eigen::VectorXd lifted;  // the planar overlap's centroid, lifted into R^n
  };
  const auto test_in_plane = [&](PlanarTester& tester, std::size_t k,
                                 std::vector<PlanarOverlapFound>& found) {
    const auto [s, t] = pairs[k];
    if (known.count({std::min(view.original[s], view.original[t]),
                     std::max(view.original[s], view.original[t])}) > 0) {
      return;
    }
    int shared = 0;
    for (int v : triangles[s]) {
      shared += (v == triangles[t][0] || v == triangles[t][1] || v == triangles[t][2]) ? 1 : 0;
    }
    if (shared == 3) {
      return;  // a duplicate, reported as such
    }
    // Neighbours across an edge are judged too: their images touch along the edge unless the
    // pair is folded, which the orientation check decides from the corners' tangent planes and
    // cannot for a cap (three corners nearly along a curve of M, a 175° angle: the planes at
    // its corners disagree), whose fold over its neighbour is an overlap on M.
    const auto alignment = [&](int r) {
      const double c = shapes.oriented_cosine[r];
      return std::isnan(c) ? -1.0 : std::abs(c);
    };
    // The better aligned of the two planes is the reference; s by a margin of 10 %, so that
    // its frame and projections serve its next pairs too.
    const int reference = alignment(s) >= 0.9 * alignment(t) ? s : t;
    const int other = reference == s ? t : s;
    ReferenceFrame& frame = frame_of(tester, reference);
    const Eigen::VectorXd& o = frame.origin;
    const Eigen::MatrixXd& U = frame.U;
    const Eigen::Matrix<double, 2, 3>& a = frame.corners;
    Eigen::Matrix<double, 2, 3> b;
    for (int j = 0; j < 3; ++j) {
      const int v = triangles[other][j];
      const auto cached = std::find_if(frame.projected.begin(), frame.projected.end(),
                                       [v](const auto& entry) { return entry.first == v; });
      if (cached != frame.projected.end()) {
        b.col(j) = cached->second;
        continue;
      }
      const auto q = points.col(v);
      Eigen::Vector2d projected = {(U.col(0).array() * (q - o).array()).sum(),
                                   (U.col(1).array() * (q - o).array()).sum()};
      if (split) {
        space.sum(projected.data(), 2);
      }
      frame.projected.emplace_back(v, projected);
      b.col(j) = projected;
    }
    const PlanarOverlap overlap = triangle_intersection(a, b);
    const double smaller_area = std::min(shapes.area[s], shapes.area[t]);
    if (overlap.area > options.overlap_area_ratio * smaller_area) {
      found.push_back({k, shared, lift(o, U, overlap.centroid)});
    }
  };
  // The planar tests on threads, by blocks of pairs (a split mesh's are sums over the ranks:
  // one thread, in order); the few pairs that overlap in the plane are then judged on M here,
  // in the pairs' order, so that the defects are recorded as one loop records them.
  // A stop request is polled between rounds of blocks and per pair judged on M, on this thread
  // (CheckStop is not thread-safe, and on a split mesh every rank must poll at the same place):
  // at large n a pair's planar test is a few passes over n-vectors, so blocks hold fewer pairs.
  const std::size_t pairs_per_block = std::clamp<std::size_t>(
      (std::size_t{1} << 24) / static_cast<std::size_t>(std::max(n, 1)), 64, 8192);
  const std::size_t blocks = (pairs.size() + pairs_per_block - 1) / pairs_per_block;
  const int threads = split ? 1 : thread_count();
  std::vector<std::vector<PlanarOverlapFound>> found(blocks);
  std::size_t tested_pairs = 0;
  for (std::size_t round = 0; round < blocks && !stop.is_stopped();
       round += static_cast<std::size_t>(threads)) {
    const std::size_t round_blocks = std::min(blocks - round, static_cast<std::size_t>(threads));
    parallel_for(static_cast<int>(round_blocks), threads, [&](int i) {
      const std::size_t block = round + static_cast<std::size_t>(i);
      PlanarTester tester;
      tester.d.resize(n);
      const std::size_t first = block * pairs_per_block;
      for (std::size_t k = first; k < std::min(pairs.size(), first + pairs_per_block); ++k) {
        test_in_plane(tester, k, found[block]);
      }
    });
    tested_pairs = std::min(pairs.size(), (round + round_blocks) * pairs_per_block);
  }
  std::size_t unjudged_pairs = pairs.size() - tested_pairs;
  Linearization workspace;
  for (const std::vector<PlanarOverlapFound>& block : found) {
    for (const PlanarOverlapFound& candidate : block) {
      if (stop.is_stopped()) {
        ++unjudged_pairs;  // overlaps in the plane, not judged on M
        continue;
      }
      const auto [s, t] = pairs[candidate.pair];
      if (is_sheet_crossing(view, s, t, options)) {
        ++result.crossing_pair_count;
        continue;
      }
      Eigen::VectorXd p = candidate.lifted;
      if (!project_onto_manifold(geometry.problem, p, workspace) || !workspace.is_factored()) {
        continue;  // no point of M to compare at: left unjudged
      }
      const OverlapOnManifold on_m =
          overlap_on_manifold(view, geometry, triangles[s], triangles[t], p, workspace, options);
      if (!on_m.is_overlap) {
        continue;
      }
      p = on_m.point;
      const double smaller_area = std::min(shapes.area[s], shapes.area[t]);
      result.overlapping_triangle_pairs.emplace_back(view.original[s], view.original[t]);
      recorder.record(MeshDefectKind::OverlappingTriangles, [&] {
        std::ostringstream out;
        out.precision(3);
        out << triangle_name(view.original[s], triangles[s]) << " and "
            << triangle_name(view.original[t], triangles[t]) << " both cover M near "
            << describe_point(p, space) << ": overlap " << 100.0 * on_m.area / smaller_area
            << "% of the smaller, " << on_m.width << " wide"
            << (candidate.shared == 1 ? " (they share one vertex: a folded fan)" : "");
        if (on_m.depth > 0.0) {
          out << "; a point of one lies " << on_m.depth
              << " from M, deeper than half its distance to the other: it follows no sheet of M";
        }
        return out.str();
      });
    }
  }
  if (unjudged_pairs > 0) {
    result.checks_cut_short.push_back("overlaps on M: " + std::to_string(unjudged_pairs) + " of " +
                                      std::to_string(pairs.size()) +
                                      " pairs of nearby triangles not judged");
  }
  check_thin_triangles(view, geometry, pairs, stop, recorder, result);
}

}  // namespace tessera::detail
