// SPDX-License-Identifier: MIT
#include "tessera/methods/improvement/edge_swap.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <sstream>
#include <unordered_map>
#include <unordered_set>
#include <vector>

#include "tessera/core/corrector.h"
#include "tessera/core/error.h"
#include "tessera/core/linearization.h"
#include "tessera/geometry/mesh_quality.h"
#include "tessera/geometry/mesh_topology.h"

namespace tessera {
namespace {

constexpr double kRadiansToDegrees = 180.0 / std::numbers::pi;

std::int64_t edge_key(int u, int v) {
  const auto low = static_cast<std::int64_t>(std::min(u, v));
  const auto high = static_cast<std::int64_t>(std::max(u, v));
  return (low << 32) | high;
}

// The edge {a, b} with its two triangles: t1 = (a, b, c) traverses it a -> b, t2 = (b, a, d).
struct Quad {
  int t1 = -1;
  int t2 = -1;
  int a = -1;
  int b = -1;
  int c = -1;
  int d = -1;
};

// Fills a, b, c, d from the two triangles of an edge {u, v}; false if they traverse it alike.
bool orient_quad(const std::vector<Triangle>& triangles, int t1, int t2, int u, int v, Quad& q) {
  const Triangle& first = triangles[t1];
  const Triangle& second = triangles[t2];
  for (int k = 0; k < 3; ++k) {
    const int p = first[k];
    const int r = first[(k + 1) % 3];
    if ((p == u && r == v) || (p == v && r == u)) {
      q.t1 = t1;
      q.t2 = t2;
      q.a = p;
      q.b = r;
      q.c = first[(k + 2) % 3];
    }
  }
  for (int j = 0; j < 3; ++j) {
    if (second[j] == q.b && second[(j + 1) % 3] == q.a) {
      q.d = second[(j + 2) % 3];
      return q.c != q.d;
    }
  }
  return false;
}

// Signed area of the triangle (p, q, r) of points in R².
double signed_area(const Eigen::Vector2d& p, const Eigen::Vector2d& q, const Eigen::Vector2d& r) {
  return 0.5 * ((q.x() - p.x()) * (r.y() - p.y()) - (q.y() - p.y()) * (r.x() - p.x()));
}

// True if the quadrilateral a, d, b, c is strictly convex in the plane through `origin` spanned
// by the orthonormal n×2 basis T: each of the four triangles abc, bad (old) and cad, dbc (new)
// has signed area > min_area_ratio·(longest side or diagonal)² times `sign`. If `sign` is 0 on
// entry it is set to the sign of abc; all four with one sign is the same as: the diagonals ab
// and cd cross.
bool is_strictly_convex_in_plane(const TriangleMesh& mesh, const Quad& q, const Eigen::MatrixXd& T,
                                 const Eigen::VectorXd& origin, const ImprovementOptions& options,
                                 double& sign) {
  const auto in_plane = [&](int v) -> Eigen::Vector2d {
    return T.transpose() * (mesh.point(v) - origin);
  };
  const Eigen::Vector2d pa = in_plane(q.a);
  const Eigen::Vector2d pb = in_plane(q.b);
  const Eigen::Vector2d pc = in_plane(q.c);
  const Eigen::Vector2d pd = in_plane(q.d);
  const double longest_squared =
      std::max({(pa - pb).squaredNorm(), (pa - pc).squaredNorm(), (pa - pd).squaredNorm(),
                (pb - pc).squaredNorm(), (pb - pd).squaredNorm(), (pc - pd).squaredNorm()});
  const double threshold = options.min_area_ratio * longest_squared;
  const double areas[4] = {signed_area(pa, pb, pc), signed_area(pb, pa, pd),
                           signed_area(pc, pa, pd), signed_area(pd, pb, pc)};
  if (sign == 0.0) {
    sign = areas[0] >= 0 ? 1.0 : -1.0;
  }
  for (const double area : areas) {
    if (!(sign * area > threshold)) {
      return false;
    }
  }
  return true;
}

// Projects the midpoint m of u and v onto M: on success x = P(m). A projection that goes
// farther than the edge is long has left the neighbourhood of the edge (another sheet of M);
// what M looks like there says nothing about this edge.
bool project_edge_midpoint(const TriangleMesh& mesh, const ImplicitProblem& problem, int u, int v,
                           Linearization& linearization, Eigen::VectorXd& x) {
  x = 0.5 * (mesh.point(u) + mesh.point(v));
  CorrectorOptions corrector;
  corrector.max_displacement = (mesh.point(u) - mesh.point(v)).norm();
  return project_gauss_newton(problem, x, corrector, linearization).is_success();
}

// Tangent bases at the mesh's vertices (whose points a swap never moves), kept for the
// vertices seen last: neighbouring quadrilaterals share corners, so most corners are factored
// once per run instead of once per check. Bounded, so that a sweep over a mesh of large n holds
// O(1) n-vectors.
class CornerTangents {
 public:
  explicit CornerTangents(const ImplicitProblem& problem) : problem_(problem) {}

  /// The factorisation at vertex v, made now unless v was the last one factored.
  const Linearization* factorisation(const TriangleMesh& mesh, int v) {
    if (factored_vertex_ != v) {
      factored_vertex_ = v;
      is_factored_ = linearization_.factor(problem_, mesh.point(v));
      if (is_factored_) {
        remember(v, linearization_.tangent_basis());
      }
    }
    return is_factored_ ? &linearization_ : nullptr;
  }

  /// T at vertex v (n×2, orthonormal), oriented like `reference`; false where DF is rank
  /// deficient.
  bool tangent(const TriangleMesh& mesh, int v, const Eigen::MatrixXd& reference,
               Eigen::MatrixXd& T) {
    const auto found = tangents_.find(v);
    if (found != tangents_.end()) {
      T = found->second;
    } else if (problem_.has_sparse_jacobian() && is_factored_ &&
               tangent_basis_near(problem_, linearization_, mesh.point(v), T)) {
      // The corners of a quadrilateral are a neighbour's neighbours: the chord from the last
      // factorisation (one DF, a few solves) gives v's tangent plane without a factorisation
      // of its own (at n = 10⁵, a third of a second each, three per swap checked).
      remember(v, T);
    } else if (const Linearization* at_v = factorisation(mesh, v)) {
      T = at_v->tangent_basis();
    } else {
      return false;
    }
    align_tangent_basis(T, reference);
    return true;
  }

 private:
  static constexpr std::size_t kCapacity = 256;
  void remember(int v, const Eigen::MatrixXd& T) {
    if (tangents_.size() >= kCapacity) {
      tangents_.clear();  // simplest bound; the next checks refill what they need
    }
    tangents_[v] = T;
  }

  const ImplicitProblem& problem_;
  Linearization linearization_;
  int factored_vertex_ = -1;
  bool is_factored_ = false;
  std::unordered_map<int, Eigen::MatrixXd> tangents_;
};

// Projects the midpoint of a and b onto M (the chord frozen at a, Gauss–Newton where it does
// not contract) and checks that the quadrilateral a, d, b, c is strictly convex, with the old
// triangles' orientation, in the tangent planes at its four corners.
SwapCheck check_quad_geometry(const TriangleMesh& mesh, const ImplicitProblem& problem,
                              const Quad& q, const ImprovementOptions& options,
                              Linearization& workspace, CornerTangents& corners_tangents) {
  const Linearization* at_a = corners_tangents.factorisation(mesh, q.a);
  if (at_a == nullptr) {
    return SwapCheck::ProjectionFailed;
  }
  // The midpoint must project onto M within the edge's length: farther means the edge has
  // left the neighbourhood of M it belongs to (another sheet), where nothing can be judged.
  Eigen::VectorXd x = 0.5 * (mesh.point(q.a) + mesh.point(q.b));
  CorrectorOptions corrector;
  corrector.max_displacement = (mesh.point(q.a) - mesh.point(q.b)).norm();
  const Eigen::VectorXd midpoint = x;
  if (!project_chord(problem, *at_a, x, corrector).is_success()) {
    x = midpoint;
    if (!project_gauss_newton(problem, x, corrector, workspace).is_success()) {
      return SwapCheck::ProjectionFailed;
    }
  }
  // T: n×2 orthonormal tangent basis at a; coordinates in the tangent plane are Tᵀ(y − a).
  const Eigen::MatrixXd T = at_a->tangent_basis();
  double sign = 0.0;
  if (!is_strictly_convex_in_plane(mesh, q, T, Eigen::VectorXd(mesh.point(q.a)), options, sign)) {
    return SwapCheck::NonConvex;
  }
  // One plane alone can be fooled where M curves across a large quadrilateral: a swap could
  // then fold the mesh over (a triangle reversed relative to M's normal at its corners), and a
  // folded region can never be unfolded by convex swaps. So the quadrilateral must be strictly
  // convex, with the same orientation, in the tangent plane at each of its corners (the corner
  // bases are aligned with T, so "same orientation" is meaningful).
  Eigen::MatrixXd corner_tangent;
  for (const int v : {q.b, q.c, q.d}) {
    if (!corners_tangents.tangent(mesh, v, T, corner_tangent)) {
      return SwapCheck::ProjectionFailed;
    }
    double corner_sign = sign;
    if (!is_strictly_convex_in_plane(mesh, q, corner_tangent, Eigen::VectorXd(mesh.point(v)),
                                     options, corner_sign)) {
      return SwapCheck::NonConvex;
    }
  }
  return SwapCheck::Allowed;
}

// n×2 orthonormal basis of the oriented 2-plane of triangle (p, q, r) (Gram–Schmidt).
Eigen::MatrixXd plane_basis(const TriangleMesh& mesh, int p, int q, int r) {
  Eigen::MatrixXd Q(mesh.ambient_dimension(), 2);
  Q.col(0) = (mesh.point(q) - mesh.point(p)).normalized();
  Eigen::VectorXd w = mesh.point(r) - mesh.point(p);
  w -= w.dot(Q.col(0)) * Q.col(0);
  Q.col(1) = w.normalized();
  return Q;
}

// Angle between the planes of triangles (p1, q1, r1) and (p2, q2, r2): see ImprovementCriterion.
double plane_angle(const TriangleMesh& mesh, const Triangle& first, const Triangle& second) {
  const Eigen::MatrixXd Q1 = plane_basis(mesh, first[0], first[1], first[2]);
  const Eigen::MatrixXd Q2 = plane_basis(mesh, second[0], second[1], second[2]);
  if (mesh.ambient_dimension() == 3) {
    const Eigen::Vector3d n1 = Eigen::Vector3d(Q1.col(0)).cross(Eigen::Vector3d(Q1.col(1)));
    const Eigen::Vector3d n2 = Eigen::Vector3d(Q2.col(0)).cross(Eigen::Vector3d(Q2.col(1)));
    return std::atan2(n1.cross(n2).norm(), n1.dot(n2));
  }
  // The cosines of the principal angles are the singular values of Q1ᵀQ2.
  const Eigen::Matrix2d M = Q1.transpose() * Q2;
  const double smallest = Eigen::JacobiSVD<Eigen::Matrix2d>(M).singularValues()(1);
  return std::acos(std::clamp(smallest, 0.0, 1.0));
}

// What the criterion says of replacing triangles (a, b, c), (b, a, d) by (c, a, d), (d, b, c).
enum class Verdict {
  Improves,  ///< by more than the relative tolerance
  DoesNotImprove,
  ProjectionFailed,  ///< MidpointDistance: the old edge's midpoint could not be projected
};

// Evaluates the criterion alone (no validity check): the angle and normal criteria cost a few
// dot products, far less than the five factorisations of the convexity check.
Verdict judge_swap(const TriangleMesh& mesh, const ImplicitProblem& problem, const Quad& q,
                   const ImprovementOptions& options, Linearization& workspace) {
  const double tolerance = options.relative_tolerance;
  switch (options.criterion) {
    case ImprovementCriterion::MaxMinAngle: {
      // The quad's five sides and two diagonals, each measured once in R^n.
      const auto length = [&](int u, int v) { return (mesh.point(u) - mesh.point(v)).norm(); };
      const double ab = length(q.a, q.b), bc = length(q.b, q.c), ca = length(q.c, q.a);
      const double ad = length(q.a, q.d), db = length(q.d, q.b), cd = length(q.c, q.d);
      const double before = std::min(min_angle_of_sides(ab, bc, ca), min_angle_of_sides(ab, ad, db));
      const double after = std::min(min_angle_of_sides(ca, ad, cd), min_angle_of_sides(cd, db, bc));
      return after > before * (1.0 + tolerance) ? Verdict::Improves : Verdict::DoesNotImprove;
    }
    case ImprovementCriterion::NormalAngle: {
      const double before = plane_angle(mesh, {q.a, q.b, q.c}, {q.b, q.a, q.d});
      const double after = plane_angle(mesh, {q.c, q.a, q.d}, {q.d, q.b, q.c});
      return after < before * (1.0 - tolerance) ? Verdict::Improves : Verdict::DoesNotImprove;
    }
    case ImprovementCriterion::MidpointDistance: {
      Eigen::VectorXd old_projection;
      if (!project_edge_midpoint(mesh, problem, q.a, q.b, workspace, old_projection)) {
        return Verdict::ProjectionFailed;
      }
      const double before = (old_projection - 0.5 * (mesh.point(q.a) + mesh.point(q.b))).norm();
      Eigen::VectorXd new_projection;
      // A new diagonal whose midpoint cannot be projected is no improvement.
      if (!project_edge_midpoint(mesh, problem, q.c, q.d, workspace, new_projection)) {
        return Verdict::DoesNotImprove;
      }
      const double after = (new_projection - 0.5 * (mesh.point(q.c) + mesh.point(q.d))).norm();
      return after < before * (1.0 - tolerance) ? Verdict::Improves : Verdict::DoesNotImprove;
    }
  }
  return Verdict::DoesNotImprove;
}

// Finds the two triangles of edge {u, v} by a linear scan (for the single-edge entry points).
SwapCheck find_quad(const std::vector<Triangle>& triangles, int u, int v, Quad& q) {
  std::vector<int> found;
  for (int t = 0; t < static_cast<int>(triangles.size()); ++t) {
    const Triangle& tri = triangles[t];
    const bool has_u = tri[0] == u || tri[1] == u || tri[2] == u;
    const bool has_v = tri[0] == v || tri[1] == v || tri[2] == v;
    if (has_u && has_v) {
      found.push_back(t);
    }
  }
  if (found.empty()) {
    return SwapCheck::NotAnEdge;
  }
  if (found.size() == 1) {
    return SwapCheck::BoundaryEdge;
  }
  if (found.size() > 2) {
    return SwapCheck::NonManifoldEdge;
  }
  if (!orient_quad(triangles, found[0], found[1], u, v, q)) {
    return SwapCheck::InconsistentOrientation;
  }
  for (const Triangle& tri : triangles) {
    for (int k = 0; k < 3; ++k) {
      if (edge_key(tri[k], tri[(k + 1) % 3]) == edge_key(q.c, q.d)) {
        return SwapCheck::ExistingEdge;
      }
    }
  }
  return SwapCheck::Allowed;
}

void check_dimensions(const TriangleMesh& mesh, const ImplicitProblem& problem) {
  TESSERA_CHECK(mesh.ambient_dimension() == problem.ambient_dimension(),
                "the mesh lives in R^" << mesh.ambient_dimension() << " but problem '"
                                       << problem.name() << "' in R^"
                                       << problem.ambient_dimension());
}

}  // namespace

const char* to_string(ImprovementCriterion criterion) {
  switch (criterion) {
    case ImprovementCriterion::MaxMinAngle:
      return "angle";
    case ImprovementCriterion::NormalAngle:
      return "normal";
    case ImprovementCriterion::MidpointDistance:
      return "distance";
  }
  return "?";
}

const char* to_string(SwapCheck check) {
  switch (check) {
    case SwapCheck::Allowed:
      return "allowed";
    case SwapCheck::NotAnEdge:
      return "not an edge";
    case SwapCheck::BoundaryEdge:
      return "boundary edge";
    case SwapCheck::NonManifoldEdge:
      return "non-manifold edge";
    case SwapCheck::InconsistentOrientation:
      return "inconsistent orientation";
    case SwapCheck::ExistingEdge:
      return "the other diagonal is already an edge";
    case SwapCheck::NonConvex:
      return "quadrilateral not strictly convex in the tangent plane";
    case SwapCheck::ProjectionFailed:
      return "edge midpoint could not be projected onto M";
  }
  return "?";
}

void ImprovementOptions::validate() const {
  TESSERA_CHECK(max_sweeps >= 1,
                "ImprovementOptions::max_sweeps = " << max_sweeps << " must be >= 1");
  TESSERA_CHECK(
      relative_tolerance >= 0 && relative_tolerance < 1,
      "ImprovementOptions::relative_tolerance = " << relative_tolerance << " must be in [0, 1)");
  TESSERA_CHECK(
      min_area_ratio >= 0 && min_area_ratio < 0.5,
      "ImprovementOptions::min_area_ratio = " << min_area_ratio << " must be in [0, 0.5)");
}

std::string ImprovementSummary::brief_report() const {
  std::ostringstream out;
  out << swaps << " swaps in " << sweeps << " sweeps (" << (converged ? "converged" : "sweep cap")
      << "); min angle " << min_angle_degrees_before << "° -> " << min_angle_degrees_after << "°";
  return out.str();
}

SwapCheck check_edge_swap(const TriangleMesh& mesh, const ImplicitProblem& problem, int a, int b,
                          const ImprovementOptions& options) {
  check_dimensions(mesh, problem);
  options.validate();
  Quad q;
  const SwapCheck combinatorial = find_quad(mesh.triangles(), a, b, q);
  if (combinatorial != SwapCheck::Allowed) {
    return combinatorial;
  }
  Linearization workspace;
  CornerTangents corner_tangents(problem);
  return check_quad_geometry(mesh, problem, q, options, workspace, corner_tangents);
}

SwapCheck swap_edge(TriangleMesh& mesh, const ImplicitProblem& problem, int a, int b,
                    const ImprovementOptions& options) {
  check_dimensions(mesh, problem);
  options.validate();
  Quad q;
  SwapCheck check = find_quad(mesh.triangles(), a, b, q);
  if (check == SwapCheck::Allowed) {
    Linearization workspace;
    CornerTangents corner_tangents(problem);
    check = check_quad_geometry(mesh, problem, q, options, workspace, corner_tangents);
  }
  if (check == SwapCheck::Allowed) {
    std::vector<Triangle> triangles = mesh.triangles();
    triangles[q.t1] = {q.c, q.a, q.d};
    triangles[q.t2] = {q.d, q.b, q.c};
    mesh.set_triangles(std::move(triangles));
  }
  return check;
}

ImprovementSummary improve_by_edge_swaps(TriangleMesh& mesh, const ImplicitProblem& problem,
                                         const ImprovementOptions& options) {
  check_dimensions(mesh, problem);
  options.validate();
  ImprovementSummary summary;
  const MeshQuality shape_before = measure_shape(mesh);
  summary.min_angle_degrees_before = shape_before.min_angle_degrees;
  summary.fraction_angles_below_30_before = shape_before.fraction_angles_below_30;

  std::vector<Triangle> triangles = mesh.triangles();
  std::unordered_set<std::int64_t> edges;
  for (const Triangle& tri : triangles) {
    for (int k = 0; k < 3; ++k) {
      edges.insert(edge_key(tri[k], tri[(k + 1) % 3]));
    }
  }
  CornerTangents corner_tangents(problem);
  Linearization workspace;
  std::vector<std::uint8_t> is_changed;
  while (summary.sweeps < options.max_sweeps) {
    ++summary.sweeps;
    // The topology is rebuilt once per sweep. A swap changes only its two triangles: edges of
    // changed triangles are skipped for the rest of the sweep (their incidences are stale) and
    // visited again in the next one.
    const MeshTopology topology(mesh.vertex_count(), triangles);
    is_changed.assign(triangles.size(), 0);
    int swaps_in_sweep = 0;
    int interior_edges = 0;
    for (int e = 0; e < topology.edge_count(); ++e) {
      const auto incident = topology.edge_triangles(e);
      if (incident.size() != 2) {
        continue;  // boundary edges are never swapped; non-manifold edges are left alone
      }
      ++interior_edges;
      if (is_changed[incident[0]] || is_changed[incident[1]]) {
        continue;
      }
      const auto& edge = topology.edge(e);
      Quad q;
      if (!orient_quad(triangles, incident[0], incident[1], edge[0], edge[1], q)) {
        continue;
      }
      if (edges.count(edge_key(q.c, q.d)) != 0) {
        ++summary.rejected_existing_edge;
        continue;
      }
      if (options.stop_requested && options.stop_requested()) {
        summary.interrupted = true;
        break;
      }
      // The criterion first: most edges of a reasonable mesh do not want a swap, and for them
      // the projection and the five factorisations of the validity check would be wasted.
      const Verdict verdict = judge_swap(mesh, problem, q, options, workspace);
      if (verdict == Verdict::ProjectionFailed) {
        ++summary.rejected_projection_failed;
        continue;
      }
      if (verdict == Verdict::DoesNotImprove) {
        continue;
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
      triangles[q.t1] = {q.c, q.a, q.d};
      triangles[q.t2] = {q.d, q.b, q.c};
      // The mesh's triangles are read by the criteria (through the mesh points only), so they
      // are written back at the end of the sweep.
      edges.erase(edge_key(q.a, q.b));
      edges.insert(edge_key(q.c, q.d));
      is_changed[q.t1] = 1;
      is_changed[q.t2] = 1;
      ++swaps_in_sweep;
    }
    summary.interior_edges = interior_edges;
    summary.swaps += swaps_in_sweep;
    if (summary.interrupted) {
      break;
    }
    if (swaps_in_sweep == 0) {
      summary.converged = true;
      break;
    }
  }
  mesh.set_triangles(std::move(triangles));
  const MeshQuality shape_after = measure_shape(mesh);
  summary.min_angle_degrees_after = shape_after.min_angle_degrees;
  summary.fraction_angles_below_30_after = shape_after.fraction_angles_below_30;
  return summary;
}

}  // namespace tessera
