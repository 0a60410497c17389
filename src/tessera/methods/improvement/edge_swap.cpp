// SPDX-License-Identifier: MIT
#include "tessera/methods/improvement/edge_swap.h"

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>
#include <memory>
#include <cstdint>
#include <numbers>
#include <span>
#include <sstream>
#include <unordered_map>
#include <vector>

#include "tessera/core/ambient_space.h"
#include "tessera/core/corrector.h"
#include "tessera/core/error.h"
#include "tessera/core/linearization.h"
#include "tessera/core/parallel_for.h"
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

// Tangent bases at the mesh's vertices (whose points a swap never moves), kept for the
// vertices seen last: neighbouring quadrilaterals share corners, so most corners are factored
// once per run instead of once per check. Bounded, so that a sweep over a mesh of large n holds
// O(1) n-vectors.
class CornerTangents {
 public:
  explicit CornerTangents(const ImplicitProblem& problem)
      : problem_(problem), space_(problem.space()) {}

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
    if (space_->is_distributed()) {
      align_tangent_basis(T, reference, *space_);  // Tᵀ·reference summed over the ranks
    } else {
      align_tangent_basis(T, reference);
    }
    return true;
  }

 private:
  // At most 256 bases and 32 MB of them (at n = 10⁵ a basis is 1.6 MB).
  static constexpr std::size_t kCapacity = 256;
  static constexpr std::size_t kCapacityBytes = std::size_t{32} << 20;
  void remember(int v, const Eigen::MatrixXd& T) {
    const std::size_t bytes = static_cast<std::size_t>(T.size()) * sizeof(double);
    if (tangents_.size() >= kCapacity || (tangents_.size() + 1) * bytes > kCapacityBytes) {
      tangents_.clear();  // simplest bound; the next checks refill what they need
    }
    tangents_[v] = T;
  }

  const ImplicitProblem& problem_;
  const std::shared_ptr<const AmbientSpace> space_;
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
  const std::shared_ptr<const AmbientSpace> shared_space = problem.space();
  const AmbientSpace& space = *shared_space;
  const Linearization* at_a = corners_tangents.factorisation(mesh, q.a);
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

// What the criterion says of replacing triangles (a, b, c), (b, a, d) by (c, a, d), (d, b, c).
enum class Verdict {
  Improves,  ///< by more than the relative tolerance
  DoesNotImprove,
  ProjectionFailed,  ///< MidpointDistance: the old edge's midpoint could not be projected
};

// The quad's five sides and two diagonals in R^n: ab, bc, ca, ad, db, cd.
constexpr int kQuadSides = 6;
std::array<std::pair<int, int>, 6> quad_sides(const Quad& q) {
  return {{{q.a, q.b}, {q.b, q.c}, {q.c, q.a}, {q.a, q.d}, {q.d, q.b}, {q.c, q.d}}};
}

// Evaluates the criterion alone (no validity check): the angle and normal criteria cost a few
// dot products, far less than the five factorisations of the convexity check. `measured`: the
// quad's kQuadSides lengths if the caller has them (a split mesh measures a sweep's quads at
// once).
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
  if (problem.space()->is_distributed()) {
    check_mesh_of_problem(mesh, problem, "edge swaps");  // a split mesh of the problem's rows
    return;
  }
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
