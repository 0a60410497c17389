// SPDX-License-Identifier: MIT
#include "tessera/methods/folds/fold_curves.h"

#include <Eigen/SparseCore>
#include <chrono>
#include <cmath>
#include <memory>
#include <optional>
#include <utility>

#include "tessera/core/error.h"
#include "tessera/core/linearization.h"
#include "tessera/core/metric_problem.h"
#include "tessera/geometry/mesh_topology.h"
#include "tessera/methods/common/zero_set_curves.h"

namespace tessera {

int FoldCurves::point_count() const {
  int count = 0;
  for (const FoldCurve& curve : curves) {
    count += static_cast<int>(curve.points.size());
  }
  return count;
}

namespace {

double determinant(const Eigen::Matrix2d& B) { return B(0, 0) * B(1, 1) - B(0, 1) * B(1, 0); }

// DF at one point, sparse or dense as the problem prefers; only products with vectors are needed.
class JacobianAt {
 public:
  void evaluate(const ImplicitProblem& problem, const Eigen::Ref<const Eigen::VectorXd>& y) {
    if (problem.has_sparse_jacobian()) {
      problem.sparse_jacobian(y, sparse_);
      is_sparse_ = true;
    } else {
      dense_.resize(problem.equation_count(), problem.ambient_dimension());
      problem.jacobian(y, dense_);
      is_sparse_ = false;
    }
  }
  Eigen::VectorXd times(const Eigen::Ref<const Eigen::VectorXd>& v) const {
    return is_sparse_ ? Eigen::VectorXd(sparse_ * v) : Eigen::VectorXd(dense_ * v);
  }

 private:
  bool is_sparse_ = false;
  Eigen::SparseMatrix<double> sparse_;
  Eigen::MatrixXd dense_;
};

// The quantities of the fold condition at one point y (in the metric's coordinates):
// T the oriented tangent basis, G = Dπ, B = G·T, g = det B, and the derivative of g along M's
// tangent directions, q = (dg[T₁], dg[T₂]) (the gradient of g on M in tangent coordinates).
struct FoldState {
  Eigen::MatrixXd T;
  Eigen::Matrix2d B;
  double g = 0.0;
  Eigen::Vector2d q;
  Eigen::VectorXd F;
  Eigen::MatrixXd G;
};

// The fold computation on the problem seen in its metric (ScaledProblem): lengths, tolerances
// and minimum-norm corrections are those of the metric, as for the covering.
class FoldSolver {
 public:
  FoldSolver(const ImplicitProblem& problem, const ParameterPlane& plane, const FoldOptions& options)
      : plane_(plane), options_(options), metric_(problem) {}

  const CountedProblem& problem() const { return metric_.counted(); }
  WorkCounts work() const { return metric_.work(); }
  Eigen::VectorXd to_metric(const Eigen::Ref<const Eigen::VectorXd>& x) const {
    return metric_.to_metric(x);
  }
  Eigen::VectorXd from_metric(const Eigen::Ref<const Eigen::VectorXd>& y) const {
    return metric_.from_metric(y);
  }

  // G = Dπ with respect to y = W x: the columns of Dπ(x) divided by the weights.
  void plane_gradient(const Eigen::Ref<const Eigen::VectorXd>& y, Eigen::MatrixXd& G) const {
    G.resize(2, y.size());
    plane_.gradient(from_metric(y), G);
    if (metric_.weights().size() > 0) {
      G = G * metric_.weights().cwiseInverse().asDiagonal();
    }
  }

  // det(Dπ·T) at a vertex with T oriented like the triangles around it (det(Tᵀ·[e₁ e₂]) > 0 for
  // their edges from y): the quantity whose sign changes across the fold curve; and ‖Dπ‖²
  // (Frobenius), its scale.
  std::optional<std::pair<double, double>> vertex_determinant(
      const Eigen::VectorXd& y, const std::vector<Eigen::Matrix<double, -1, 2>>& edges) {
    if (!linearization_.factor(metric_.counted(), y)) {
      return std::nullopt;
    }
    Eigen::MatrixXd T = linearization_.tangent_basis();
    orient(T, edges);
    Eigen::MatrixXd G;
    plane_gradient(y, G);
    return std::make_pair(determinant(G * T), G.squaredNorm());
  }

  // Flips T's second column unless Σ det(Tᵀ·[e₁ e₂]) over the given oriented edge pairs is > 0.
  static void orient(Eigen::MatrixXd& T, const std::vector<Eigen::Matrix<double, -1, 2>>& edges) {
    double sum = 0.0;
    for (const auto& pair : edges) {
      const Eigen::Matrix2d in_tangent = T.transpose() * pair;
      sum += determinant(in_tangent);
    }
    if (sum < 0.0) {
      T.col(1) = -T.col(1);
    }
  }

  // Newton's method on F(y) = 0, g(y) = det(Dπ(y)·T(y)) = 0 from y, minimum-norm corrections.
  // `orientation` orients the first tangent basis (later ones follow the previous one).
  // On success y is on the fold curve and `curve_tangent` is the unit tangent of the fold curve
  // at y (n-vector, sign arbitrary) and `image_tangent` = Dπ·curve_tangent.
  struct Refined {
    bool converged = false;
    int iterations = 0;
    double residual = std::numeric_limits<double>::quiet_NaN();
    double determinant = std::numeric_limits<double>::quiet_NaN();
    Eigen::VectorXd curve_tangent;
    Eigen::Vector2d image_tangent = Eigen::Vector2d::Zero();
  };
  Refined refine(Eigen::VectorXd& y, const std::vector<Eigen::Matrix<double, -1, 2>>& orientation,
                 double max_displacement) {
    Refined result;
    const Eigen::VectorXd start = y;
    Eigen::MatrixXd reference;
    FoldState state;
    for (int iteration = 1; iteration <= options_.max_iterations; ++iteration) {
      result.iterations = iteration;
      if (!evaluate_state(y, reference.size() > 0 ? &reference : nullptr, orientation, state)) {
        return result;
      }
      reference = state.T;
      const double q_norm = state.q.norm();
      if (!(q_norm > 0.0) || !std::isfinite(q_norm)) {
        return result;  // g has no gradient on M here: not a regular fold point
      }
      // dy = dy_p + T a: dy_p = −DF⁺F (⟂ T) corrects F; a, of minimum norm, corrects g to first
      // order: dg[dy_p] + q·a = −g.
      Eigen::VectorXd dy_p(y.size());
      linearization_.solve_minimum_norm(-state.F, dy_p);
      const double rhs = -state.g - derivative_of_g(state, dy_p);
      const Eigen::Vector2d a = (rhs / (q_norm * q_norm)) * state.q;
      const Eigen::VectorXd dy = dy_p + state.T * a;
      // The fold curve's tangent: the tangent direction along which g does not change.
      result.curve_tangent = state.T * Eigen::Vector2d(-state.q(1), state.q(0)) / q_norm;
      result.image_tangent = state.G * result.curve_tangent;
      y += dy;
      if (!y.allFinite() || (y - start).norm() > max_displacement) {
        return result;
      }
      if (dy.norm() <= options_.tolerance * (1.0 + y.norm()) &&
          state.F.norm() <= options_.residual_tolerance) {
        Eigen::VectorXd F(metric_.counted().equation_count());
        metric_.counted().evaluate(y, F);
        result.residual = F.norm();
        result.determinant = state.g;
        result.converged = F.allFinite() && result.residual <= options_.residual_tolerance;
        return result;
      }
    }
    return result;
  }

 private:
  // Factors DF at y and computes the fold quantities; the second derivatives come from central
  // differences of DF along T₁ and T₂ (four Jacobians), because D²F[δ]·T = [D_{T₁}DF·δ, D_{T₂}DF·δ]
  // by the symmetry of second derivatives.
  bool evaluate_state(const Eigen::VectorXd& y, const Eigen::MatrixXd* reference,
                      const std::vector<Eigen::Matrix<double, -1, 2>>& orientation,
                      FoldState& state) {
    if (!linearization_.factor(metric_.counted(), y, reference)) {
      return false;
    }
    state.T = linearization_.tangent_basis();
    if (reference == nullptr) {
      orient(state.T, orientation);
    }
    state.F.resize(metric_.counted().equation_count());
    metric_.counted().evaluate(y, state.F);
    if (!state.F.allFinite()) {
      return false;
    }
    plane_gradient(y, state.G);
    state.B = state.G * state.T;
    state.g = determinant(state.B);
    step_ = options_.difference_step * (1.0 + y.lpNorm<Eigen::Infinity>());
    for (int j = 0; j < 2; ++j) {
      plus_[j].evaluate(metric_.counted(), y + step_ * state.T.col(j));
      minus_[j].evaluate(metric_.counted(), y - step_ * state.T.col(j));
    }
    point_ = y;
    state.q = Eigen::Vector2d(derivative_of_g(state, state.T.col(0)),
                              derivative_of_g(state, state.T.col(1)));
    return state.q.allFinite();
  }

  // dg[δ] = tr(adj(B)·dB[δ]) with dB[δ] = Dπ·dT[δ] + D²π[δ]·T and dT[δ] = −DF⁺·D²F[δ]·T (the
  // part of dT in span T rotates the orthonormal basis and leaves det B unchanged).
  double derivative_of_g(const FoldState& state, const Eigen::VectorXd& delta) {
    const int n = static_cast<int>(delta.size());
    Eigen::Matrix2d dB = Eigen::Matrix2d::Zero();
    Eigen::VectorXd column(n);
    for (int j = 0; j < 2; ++j) {
      const Eigen::VectorXd second = (plus_[j].times(delta) - minus_[j].times(delta)) / (2 * step_);
      linearization_.solve_minimum_norm(second, column);
      dB.col(j) = -(state.G * column);
    }
    if (!plane_.is_linear()) {
      Eigen::MatrixXd G_plus;
      Eigen::MatrixXd G_minus;
      plane_gradient(point_ + step_ * delta, G_plus);
      plane_gradient(point_ - step_ * delta, G_minus);
      dB += (G_plus - G_minus) * state.T / (2 * step_);
    }
    const Eigen::Matrix2d& B = state.B;
    // adj(B) = [B₁₁ −B₀₁; −B₁₀ B₀₀]; tr(adj(B)·dB) = Σ adj_ik dB_ki.
    return B(1, 1) * dB(0, 0) - B(0, 1) * dB(1, 0) - B(1, 0) * dB(0, 1) + B(0, 0) * dB(1, 1);
  }

  const ParameterPlane& plane_;
  FoldOptions options_;
  MetricProblem metric_;
  Linearization linearization_;
  JacobianAt plus_[2];
  JacobianAt minus_[2];
  double step_ = 0.0;
  Eigen::VectorXd point_;
};

// Positive or not, as the zero set's marching counts signs (0 is positive): for the orientations
// of the projected triangles that seed it.
bool is_positive(double value) { return value >= 0.0; }

}  // namespace

FoldCurves find_fold_curves(const ImplicitProblem& problem, const TriangleMesh& mesh,
                            const ParameterPlane& plane, const FoldOptions& options) {
  const auto started = std::chrono::steady_clock::now();
  const int n = problem.ambient_dimension();
  TESSERA_CHECK(mesh.ambient_dimension() == n,
                "fold curves: the mesh lies in R^" << mesh.ambient_dimension() << ", problem '"
                                                   << problem.name() << "' in R^" << n);
  TESSERA_CHECK(plane.ambient_dimension() == n,
                "fold curves: the parameter plane takes points of R^"
                    << plane.ambient_dimension() << ", problem '" << problem.name() << "' has n = "
                    << n);
  FoldCurves result;
  if (mesh.triangle_count() == 0) {
    return result;
  }
  const MeshTopology topology(mesh);
  for (int e = 0; e < topology.edge_count(); ++e) {
    TESSERA_CHECK(!topology.is_manifold_edge(e) || topology.is_orientation_consistent(e),
                  "fold curves need a consistently oriented mesh: edge ("
                      << topology.edge(e)[0] << ", " << topology.edge(e)[1]
                      << ") is traversed in the same direction by both its triangles");
  }
  FoldSolver solver(problem, plane, options);
  const int vertex_count = mesh.vertex_count();
  const auto& triangles = mesh.triangles();
  auto y_of = [&](int v) { return solver.to_metric(mesh.point(v)); };

  // The orientation of the projected triangles: sign of det(π(b) − π(a), π(c) − π(a)), which
  // approximates that of det(Dπ·T) over the triangle. Where it changes between neighbours, a
  // fold curve passes nearby.
  std::vector<Eigen::Vector2d> projected(static_cast<std::size_t>(vertex_count));
  for (int v = 0; v < vertex_count; ++v) {
    projected[static_cast<std::size_t>(v)] = plane.value(mesh.point(v));
  }
  std::vector<double> triangle_orientation(triangles.size());
  for (std::size_t t = 0; t < triangles.size(); ++t) {
    const auto& [a, b, c] = triangles[t];
    const Eigen::Vector2d ab = projected[static_cast<std::size_t>(b)] - projected[static_cast<std::size_t>(a)];
    const Eigen::Vector2d ac = projected[static_cast<std::size_t>(c)] - projected[static_cast<std::size_t>(a)];
    triangle_orientation[t] = ab(0) * ac(1) - ab(1) * ac(0);
  }

  // The edges from v of each triangle around it, in the triangle's order: orient T at v.
  auto edges_around = [&](int v) {
    std::vector<Eigen::Matrix<double, -1, 2>> edges;
    const Eigen::VectorXd y = y_of(v);
    for (const int t : topology.vertex_triangles(v)) {
      const Triangle& tri = triangles[static_cast<std::size_t>(t)];
      const int k = tri[0] == v ? 0 : tri[1] == v ? 1 : 2;
      Eigen::Matrix<double, -1, 2> pair(n, 2);
      pair.col(0) = y_of(tri[static_cast<std::size_t>((k + 1) % 3)]) - y;
      pair.col(1) = y_of(tri[static_cast<std::size_t>((k + 2) % 3)]) - y;
      edges.push_back(std::move(pair));
    }
    return edges;
  };
  auto triangle_edges = [&](int t) {
    const Triangle& tri = triangles[static_cast<std::size_t>(t)];
    Eigen::Matrix<double, -1, 2> pair(n, 2);
    const Eigen::VectorXd y0 = y_of(tri[0]);
    pair.col(0) = y_of(tri[1]) - y0;
    pair.col(1) = y_of(tri[2]) - y0;
    return std::vector<Eigen::Matrix<double, -1, 2>>{std::move(pair)};
  };

  // det(Dπ·T) at the vertices the marching reaches; where DF cannot be factored, the mean
  // orientation of the projected triangles around the vertex stands in (its sign is what
  // matters).
  // Vertices where det(Dπ·T) vanishes to rounding (|det| ≤ 10⁻¹⁰‖Dπ‖²): on a generic fold
  // curve only by a coincidence of 10⁻¹⁰ of an edge; where Dπ·T is singular on a whole region
  // (a plane M does not fold over along curves, e.g. a cylinder seen along its axis) at
  // every vertex there.
  std::vector<char> is_singular(static_cast<std::size_t>(vertex_count), 0);
  auto vertex_value = [&](int v) {
    ++result.tangent_evaluations;
    if (const auto exact = solver.vertex_determinant(y_of(v), edges_around(v))) {
      is_singular[static_cast<std::size_t>(v)] = std::abs(exact->first) <= 1e-10 * exact->second;
      return exact->first;
    }
    double sum = 0.0;
    for (const int t : topology.vertex_triangles(v)) {
      sum += triangle_orientation[static_cast<std::size_t>(t)];
    }
    return sum;
  };

  // The marching starts from the triangles whose orientation differs from a neighbour's, and
  // those around their corners: the exact sign change lies within.
  ZeroSetOptions marching;
  marching.seed_triangles.emplace();
  for (int t = 0; t < static_cast<int>(triangles.size()); ++t) {
    bool changes = false;
    for (int k = 0; k < 3; ++k) {
      const int neighbour = topology.adjacent_triangle(t, k);
      if (neighbour >= 0 && is_positive(triangle_orientation[static_cast<std::size_t>(t)]) !=
                                is_positive(triangle_orientation[static_cast<std::size_t>(neighbour)])) {
        changes = true;
      }
    }
    if (!changes) {
      continue;
    }
    for (const int v : triangles[static_cast<std::size_t>(t)]) {
      for (const int around : topology.vertex_triangles(v)) {
        marching.seed_triangles->push_back(around);
      }
    }
  }
  // The signs there are rounding: no curve to follow.
  marching.skip_triangle = [&](int t) {
    const Triangle& tri = triangles[static_cast<std::size_t>(t)];
    return is_singular[static_cast<std::size_t>(tri[0])] &&
           is_singular[static_cast<std::size_t>(tri[1])] &&
           is_singular[static_cast<std::size_t>(tri[2])];
  };
  const ZeroSetCurves zero_set = find_zero_set_curves(mesh, topology, vertex_value, marching);
  result.crossing_count = zero_set.crossing_count;
  result.singular_triangle_count = zero_set.skipped_triangle_count;
  const std::vector<ZeroSetCrossing>& crossings = zero_set.crossings;

  // Each crossing: the zero of the linear interpolant on its edge, refined by Newton.
  auto estimate = [&](int c) {
    const ZeroSetCrossing& crossing = crossings[static_cast<std::size_t>(c)];
    const Eigen::VectorXd ya = y_of(crossing.vertices[0]);
    return Eigen::VectorXd(ya + crossing.fraction * (y_of(crossing.vertices[1]) - ya));
  };
  auto edge_length = [&](int c) {
    const ZeroSetCrossing& crossing = crossings[static_cast<std::size_t>(c)];
    return (y_of(crossing.vertices[1]) - y_of(crossing.vertices[0])).norm();
  };

  for (const ZeroSetChain& zero_set_chain : zero_set.chains) {
    const std::vector<int>& chain = zero_set_chain.crossings;
    const bool is_closed = zero_set_chain.is_closed;
    FoldCurve curve;
    curve.is_closed = is_closed;
    const int m = static_cast<int>(chain.size());
    std::vector<Eigen::VectorXd> estimates;
    for (const int c : chain) {
      estimates.push_back(estimate(c));
    }
    // The image tangent Dπ·t of the fold curve at each point, t oriented along the chain.
    std::vector<Eigen::Vector2d> image_tangents(static_cast<std::size_t>(m), Eigen::Vector2d::Zero());
    std::vector<Eigen::VectorXd> points_y(static_cast<std::size_t>(m));
    for (int i = 0; i < m; ++i) {
      const int c = chain[static_cast<std::size_t>(i)];
      Eigen::VectorXd y = estimates[static_cast<std::size_t>(i)];
      const auto refined =
          solver.refine(y, triangle_edges(crossings[static_cast<std::size_t>(c)].triangle),
                        options.max_displacement_in_edges * edge_length(c));
      result.newton_iterations += refined.iterations;
      FoldPoint point;
      if (refined.converged) {
        point.is_refined = true;
        point.residual = refined.residual;
        point.determinant = refined.determinant;
        result.max_residual = std::max(result.max_residual, refined.residual);
        // Orient along the chain by the neighbours' estimates.
        const int previous = i > 0 ? i - 1 : (is_closed ? m - 1 : i);
        const int next = i + 1 < m ? i + 1 : (is_closed ? 0 : i);
        const Eigen::VectorXd along =
            estimates[static_cast<std::size_t>(next)] - estimates[static_cast<std::size_t>(previous)];
        const double sign = refined.curve_tangent.dot(along) < 0.0 ? -1.0 : 1.0;
        image_tangents[static_cast<std::size_t>(i)] = sign * refined.image_tangent;
      } else {
        y = estimates[static_cast<std::size_t>(i)];
        ++result.unrefined_count;
      }
      points_y[static_cast<std::size_t>(i)] = y;
      point.x = solver.from_metric(y);
      curve.points.push_back(std::move(point));
    }
    // Cusps: the image curve's tangent reverses between two refined neighbours.
    std::vector<std::pair<int, FoldPoint>> cusps;  // insert after index
    for (int i = 0; i + 1 < m || (is_closed && i < m && m > 2); ++i) {
      const int j = (i + 1) % m;
      if (!curve.points[static_cast<std::size_t>(i)].is_refined ||
          !curve.points[static_cast<std::size_t>(j)].is_refined) {
        continue;
      }
      const Eigen::Vector2d& w_lo = image_tangents[static_cast<std::size_t>(i)];
      const Eigen::Vector2d& w_hi = image_tangents[static_cast<std::size_t>(j)];
      if (!(w_lo.dot(w_hi) < 0.0)) {
        continue;
      }
      // Regula falsi (Illinois) on κ(s) = Dπ·t(s) · u over the chord from point i to point j,
      // each trial point refined onto the fold curve; u the image direction at point i.
      const Eigen::VectorXd& lo = points_y[static_cast<std::size_t>(i)];
      const Eigen::VectorXd chord = points_y[static_cast<std::size_t>(j)] - lo;
      const Eigen::Vector2d u = w_lo.normalized();
      double s_lo = 0.0;
      double s_hi = 1.0;
      double k_lo = w_lo.dot(u);
      double k_hi = w_hi.dot(u);
      int side = 0;
      double previous_s = -1.0;
      FoldPoint cusp;
      Eigen::VectorXd best;
      const auto orientation =
          triangle_edges(crossings[static_cast<std::size_t>(chain[static_cast<std::size_t>(i)])].triangle);
      for (int iteration = 0; iteration < 60; ++iteration) {
        const double s = (s_lo * k_hi - s_hi * k_lo) / (k_hi - k_lo);
        Eigen::VectorXd y = lo + s * chord;
        const auto refined = solver.refine(y, orientation, options.max_displacement_in_edges * chord.norm());
        result.newton_iterations += refined.iterations;
        if (!refined.converged) {
          break;
        }
        const double sign = refined.curve_tangent.dot(chord) < 0.0 ? -1.0 : 1.0;
        const double k = sign * refined.image_tangent.dot(u);
        cusp.x = solver.from_metric(y);
        cusp.is_refined = true;
        cusp.residual = refined.residual;
        cusp.determinant = refined.determinant;
        best = y;
        if (k > 0.0) {
          s_lo = s;
          k_lo = k;
          if (side == 1) {
            k_hi /= 2;
          }
          side = 1;
        } else {
          s_hi = s;
          k_hi = k;
          if (side == -1) {
            k_lo /= 2;
          }
          side = -1;
        }
        const double resolution = options.tolerance * (1.0 + y.norm());
        if ((s_hi - s_lo) * chord.norm() <= resolution ||
            std::abs(s - previous_s) * chord.norm() <= resolution || k == 0.0) {
          break;
        }
        previous_s = s;
      }
      cusp.is_cusp = true;
      if (cusp.is_refined) {
        ++result.cusp_count;
        result.max_residual = std::max(result.max_residual, cusp.residual);
      } else {
        ++result.unrefined_cusp_count;
        cusp.x = solver.from_metric(lo + 0.5 * chord);
      }
      cusps.emplace_back(i, std::move(cusp));
    }
    for (auto it = cusps.rbegin(); it != cusps.rend(); ++it) {
      curve.points.insert(curve.points.begin() + it->first + 1, std::move(it->second));
    }
    result.curves.push_back(std::move(curve));
  }
  result.work = solver.work();
  result.seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  return result;
}

}  // namespace tessera
