// SPDX-License-Identifier: MIT
#include "tessera/methods/improvement/edge_swap.h"

#include "tessera/methods/improvement/detail/swap_quad.h"

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>
#include <memory>
#include <cstdint>
#include <numbers>
#include <sstream>
#include <unordered_map>
#include <vector>

#include "tessera/core/ambient_space.h"
#include "tessera/core/corrector.h"
#include "tessera/core/error.h"
#include "tessera/core/linearization.h"
#include "tessera/geometry/mesh_quality.h"
#include "tessera/geometry/mesh_topology.h"

namespace tessera {

using detail::check_dimensions;
using detail::check_quad_geometry;
using detail::CornerTangents;
using detail::orient_quad;
using detail::Quad;

namespace {

constexpr double kRadiansToDegrees = 180.0 / std::numbers::pi;

std::int64_t edge_key(int u, int v) {
  const auto low = static_cast<std::int64_t>(std::min(u, v));
  const auto high = static_cast<std::int64_t>(std::max(u, v));
  return (low << 32) | high;
}

}  // namespace

namespace detail {

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

}  // namespace detail

namespace {

// Signed area of the triangle (p, q, r) of points in R².
double signed_area(const Eigen::Vector2d& p, const Eigen::Vector2d& q, const Eigen::Vector2d& r) {
  return 0.5 * ((q.x() - p.x()) * (r.y() - p.y()) - (q.y() - p.y()) * (r.x() - p.x()));
}

// True if the quadrilateral a, d, b, c is strictly convex in the plane through `origin` spanned
// by the orthonormal n×2 basis T: each of the four triangles abc, bad (old) and cad, dbc (new)
// has signed area > min_area_ratio·(longest side or diagonal)² times `sign`. If `sign` is 0 on
// entry it is set to the sign of abc; all four with one sign is the same as: the diagonals ab
// and cd cross. On a split mesh the four corners' coordinates are summed over the ranks at once.
bool is_strictly_convex_in_plane(const TriangleMesh& mesh, const AmbientSpace& space, const Quad& q,
                                 const Eigen::MatrixXd& T, const Eigen::VectorXd& origin,
                                 const ImprovementOptions& options, double& sign) {
  const auto in_plane = [&](int v) -> Eigen::Vector2d {
    return T.transpose() * (mesh.point(v) - origin);
  };
  Eigen::Matrix<double, 2, 4> corners;  // pa, pb, pc, pd
  corners.col(0) = in_plane(q.a);
  corners.col(1) = in_plane(q.b);
  corners.col(2) = in_plane(q.c);
  corners.col(3) = in_plane(q.d);
  if (space.is_distributed()) {
    space.sum(corners.data(), 8);
  }
  const Eigen::Vector2d pa = corners.col(0);
  const Eigen::Vector2d pb = corners.col(1);
  const Eigen::Vector2d pc = corners.col(2);
  const Eigen::Vector2d pd = corners.col(3);
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
  corrector.max_displacement = problem.space()->distance(mesh.point(u), mesh.point(v));
  return project_gauss_newton(problem, x, corrector, linearization).is_success();
}

}  // namespace

namespace detail {

const Linearization* CornerTangents::factorisation(const TriangleMesh& mesh, int v,
                                                   double edge_length) {
  if (factored_vertex_ != v) {
    factored_vertex_ = v;
    Linearization next;
    if (lenders_.borrow(problem_, mesh.point(v), edge_length, next)) {
      linearization_ = std::move(next);
      is_factored_ = true;
    } else if (!problem_.has_sparse_jacobian() || sharing_ != 1) {
      // Not (yet) shared: in place, as before sharing (a sparse factorisation's border follows
      // the last one's basis), so that such runs keep their meshes and counts.
      is_factored_ = linearization_.factor(problem_, mesh.point(v));
      if (is_factored_ && sharing_ < 0 && problem_.has_sparse_jacobian()) {
        sharing_ = worth_sharing(linearization_) ? 1 : 0;
      }
    } else {
      Linearization own;
      is_factored_ = own.factor(problem_, mesh.point(v));
      if (is_factored_) {
        lenders_.keep(problem_, std::move(own), linearization_);
      }
    }
    if (is_factored_) {
      remember(v, linearization_.tangent_basis());
    }
  }
  return is_factored_ ? &linearization_ : nullptr;
}

bool CornerTangents::tangent(const TriangleMesh& mesh, int v, const Eigen::MatrixXd& reference,
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
  } else if (const Linearization* at_v = factorisation(
                 mesh, v,
                 is_factored_ ? space_->distance(mesh.point(v), linearization_.point()) : 0.0)) {
    T = at_v->tangent_basis();
  } else {
    return false;
  }
  if (space_->is_distributed()) {
    align_tangent_basis(T, reference, *space_);  // Tᵀ·reference summed over the ranks
  } else {
    align_tangent_basis(T, reference);
  }
  return true;
}

void CornerTangents::remember(int v, const Eigen::MatrixXd& T) {
  const std::size_t bytes = static_cast<std::size_t>(T.size()) * sizeof(double);
  if (tangents_.size() >= kCapacity || (tangents_.size() + 1) * bytes > kCapacityBytes) {
    tangents_.clear();  // simplest bound; the next checks refill what they need
  }
  tangents_[v] = T;
}

SwapCheck check_quad_geometry(const TriangleMesh& mesh, const ImplicitProblem& problem,
                              const Quad& q, const ImprovementOptions& options,
                              Linearization& workspace, CornerTangents& corners_tangents) {
  const std::shared_ptr<const AmbientSpace> shared_space = problem.space();
  const AmbientSpace& space = *shared_space;
  const Linearization* at_a = corners_tangents.factorisation(
      mesh, q.a, space.distance(mesh.point(q.a), mesh.point(q.b)));
  if (at_a == nullptr) {
    return SwapCheck::ProjectionFailed;
  }
  // The midpoint must project onto M within the edge's length: farther means the edge has
  // left the neighbourhood of M it belongs to (another sheet), where nothing can be judged.
  Eigen::VectorXd x = 0.5 * (mesh.point(q.a) + mesh.point(q.b));
  CorrectorOptions corrector;
  corrector.max_displacement = space.distance(mesh.point(q.a), mesh.point(q.b));
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
  if (!is_strictly_convex_in_plane(mesh, space, q, T, Eigen::VectorXd(mesh.point(q.a)), options,
                                   sign)) {
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
    if (!is_strictly_convex_in_plane(mesh, space, q, corner_tangent,
                                     Eigen::VectorXd(mesh.point(v)), options, corner_sign)) {
      return SwapCheck::NonConvex;
    }
  }
  return SwapCheck::Allowed;
}

}  // namespace detail

namespace {

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

// The same angle on a split mesh, from the Gram matrix G = EᵀE of E = (b − a, c − a, d − a)
// (summed over the ranks once for the four triangles of a quad): a corner is a coefficient
// vector k (k_a = 0, k_b = e₁, …), an edge q − p is E(k_q − k_p), and Gram–Schmidt in the inner
// product xᵀGy gives the planes' bases as E·C. Then Q1ᵀQ2 = C1ᵀ G C2. For n = 3 the normals'
// cosine is det(Q1ᵀQ2) (Binet–Cauchy).
double plane_angle_from_gram(const Eigen::Matrix3d& G, const Quad& q, const Triangle& first,
                             const Triangle& second, int n) {
  const auto coefficients = [&](int v) {
    Eigen::Vector3d k = Eigen::Vector3d::Zero();
    if (v != q.a) {
      k(v == q.b ? 0 : (v == q.c ? 1 : 2)) = 1.0;
    }
    return k;
  };
  const auto basis = [&](const Triangle& t) {
    Eigen::Matrix<double, 3, 2> C;
    // As Eigen's normalized(): a zero vector stays zero (a degenerate triangle).
    const auto normalize = [&](int j) {
      const double squared = C.col(j).dot(G * C.col(j));
      if (squared > 0) {
        C.col(j) /= std::sqrt(squared);
      }
    };
    C.col(0) = coefficients(t[1]) - coefficients(t[0]);
    normalize(0);
    C.col(1) = coefficients(t[2]) - coefficients(t[0]);
    C.col(1) -= C.col(1).dot(G * C.col(0)) * C.col(0);
    normalize(1);
    return C;
  };
  const Eigen::Matrix2d M = basis(first).transpose() * G * basis(second);
  if (n == 3) {
    const double cosine = M.determinant();
    return std::atan2(std::sqrt(std::max(0.0, 1.0 - cosine * cosine)), cosine);
  }
  const double smallest = Eigen::JacobiSVD<Eigen::Matrix2d>(M).singularValues()(1);
  return std::acos(std::clamp(smallest, 0.0, 1.0));
}

}  // namespace

namespace detail {

Verdict judge_swap(const TriangleMesh& mesh, const ImplicitProblem& problem, const Quad& q,
                   const ImprovementOptions& options, Linearization& workspace,
                   const double* measured) {
  const double tolerance = options.relative_tolerance;
  const std::shared_ptr<const AmbientSpace> shared_space = problem.space();
  const AmbientSpace& space = *shared_space;
  switch (options.criterion) {
    case ImprovementCriterion::MaxMinAngle: {
      // The quad's five sides and two diagonals, each measured once in R^n.
      std::array<double, kQuadSides> side{};
      if (measured != nullptr) {
        std::copy(measured, measured + kQuadSides, side.begin());
      } else {
        const auto pairs = quad_sides(q);
        for (std::size_t i = 0; i < pairs.size(); ++i) {
          side[i] = space.distance(mesh.point(pairs[i].first), mesh.point(pairs[i].second));
        }
      }
      const auto [ab, bc, ca, ad, db, cd] = side;
      const double before = std::min(min_angle_of_sides(ab, bc, ca), min_angle_of_sides(ab, ad, db));
      const double after = std::min(min_angle_of_sides(ca, ad, cd), min_angle_of_sides(cd, db, bc));
      return after > before * (1.0 + tolerance) ? Verdict::Improves : Verdict::DoesNotImprove;
    }
    case ImprovementCriterion::NormalAngle: {
      double before = 0.0;
      double after = 0.0;
      if (space.is_distributed()) {
        Eigen::MatrixXd E(mesh.ambient_dimension(), 3);
        E.col(0) = mesh.point(q.b) - mesh.point(q.a);
        E.col(1) = mesh.point(q.c) - mesh.point(q.a);
        E.col(2) = mesh.point(q.d) - mesh.point(q.a);
        const Eigen::Matrix3d G = space.products(E, E);  // one reduction
        const int n = space.dimension();
        before = plane_angle_from_gram(G, q, {q.a, q.b, q.c}, {q.b, q.a, q.d}, n);
        after = plane_angle_from_gram(G, q, {q.c, q.a, q.d}, {q.d, q.b, q.c}, n);
      } else {
        before = plane_angle(mesh, {q.a, q.b, q.c}, {q.b, q.a, q.d});
        after = plane_angle(mesh, {q.c, q.a, q.d}, {q.d, q.b, q.c});
      }
      return after < before * (1.0 - tolerance) ? Verdict::Improves : Verdict::DoesNotImprove;
    }
    case ImprovementCriterion::MidpointDistance: {
      Eigen::VectorXd old_projection;
      if (!project_edge_midpoint(mesh, problem, q.a, q.b, workspace, old_projection)) {
        return Verdict::ProjectionFailed;
      }
      const double before =
          space.is_distributed()
              ? space.distance(old_projection, 0.5 * (mesh.point(q.a) + mesh.point(q.b)))
              : (old_projection - 0.5 * (mesh.point(q.a) + mesh.point(q.b))).norm();
      Eigen::VectorXd new_projection;
      // A new diagonal whose midpoint cannot be projected is no improvement.
      if (!project_edge_midpoint(mesh, problem, q.c, q.d, workspace, new_projection)) {
        return Verdict::DoesNotImprove;
      }
      const double after =
          space.is_distributed()
              ? space.distance(new_projection, 0.5 * (mesh.point(q.c) + mesh.point(q.d)))
              : (new_projection - 0.5 * (mesh.point(q.c) + mesh.point(q.d))).norm();
      return after < before * (1.0 - tolerance) ? Verdict::Improves : Verdict::DoesNotImprove;
    }
  }
  return Verdict::DoesNotImprove;
}

}  // namespace detail

namespace {

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

}  // namespace

namespace detail {

void check_dimensions(const TriangleMesh& mesh, const ImplicitProblem& problem) {
  if (problem.space()->is_distributed()) {
    check_mesh_of_problem(mesh, problem, "edge swaps");  // a split mesh of the problem's rows
    return;
  }
  TESSERA_CHECK(mesh.ambient_dimension() == problem.ambient_dimension(),
                "the mesh lives in R^" << mesh.ambient_dimension() << " but problem '"
                                       << problem.name() << "' in R^"
                                       << problem.ambient_dimension());
}

}  // namespace detail

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

}  // namespace tessera
