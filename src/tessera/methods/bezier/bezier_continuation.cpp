// SPDX-License-Identifier: MIT
// Hohmann's adaptive continuation (ZIB SC 91-20, Algorithm 1 with sections 2–5). The free edges
// of the triangulation are processed smallest front angle first; for each, an imaginary
// triangle is predicted on the nine-parameter interpolant of its real triangle with the step of
// section 5, and realised either by connecting it to an existing front vertex (section 4/5:
// softened barycentric overlap tests, connection sector S) or by a new Gauss–Newton solution.
// Every deviation from the paper is listed with its reason in docs/algorithms/bezier.md.
#include "tessera/methods/bezier/bezier_continuation.h"

#include "tessera/methods/bezier/bezier_builder.h"
#include "tessera/methods/bezier/bezier_plane_geometry.h"

#include <Eigen/Dense>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <optional>
#include <queue>
#include <sstream>
#include <unordered_map>

#include "tessera/core/ambient_space.h"
#include "tessera/core/corrector.h"
#include "tessera/core/counted_problem.h"
#include "tessera/core/describe.h"
#include "tessera/core/error.h"
#include "tessera/core/face_projection.h"
#include "tessera/core/linearization.h"
#include "tessera/methods/common/point_grid.h"
#include "tessera/methods/start_point.h"

namespace tessera {

void BezierOptions::validate() const {
  validate_common("BezierOptions");
  TESSERA_CHECK(std::isfinite(max_step) && max_step >= 0,
                "BezierOptions::max_step = " << max_step << " must be >= 0 (0: 8 × step)");
  TESSERA_CHECK(max_step == 0 || max_step >= step,
                "BezierOptions::max_step = " << max_step << " must be >= step = " << step);
  TESSERA_CHECK(
      min_step_fraction > 0 && min_step_fraction < 1,
      "BezierOptions::min_step_fraction = " << min_step_fraction << " must lie in (0, 1)");
  TESSERA_CHECK(target_contraction > 0 && target_contraction < max_contraction,
                "BezierOptions::target_contraction = " << target_contraction
                                                       << " must lie in (0, max_contraction = "
                                                       << max_contraction << ")");
  TESSERA_CHECK(max_contraction > 0 && max_contraction < 1,
                "BezierOptions::max_contraction = " << max_contraction << " must lie in (0, 1)");
  TESSERA_CHECK(max_step_growth >= 1,
                "BezierOptions::max_step_growth = " << max_step_growth << " must be >= 1");
  TESSERA_CHECK(
      min_tangent_cosine > 0 && min_tangent_cosine < 1,
      "BezierOptions::min_tangent_cosine = " << min_tangent_cosine << " must lie in (0, 1)");
  TESSERA_CHECK(overlap_safety >= 0 && overlap_safety < 1,
                "BezierOptions::overlap_safety = " << overlap_safety << " must lie in [0, 1)");
  TESSERA_CHECK(connection_sector >= 0,
                "BezierOptions::connection_sector = " << connection_sector << " must be >= 0");
  TESSERA_CHECK(
      edge_length_factor > 0 && edge_length_factor <= 3,
      "BezierOptions::edge_length_factor = " << edge_length_factor << " must lie in (0, 3]");
  TESSERA_CHECK(step_reduction > 0 && step_reduction < 1,
                "BezierOptions::step_reduction = " << step_reduction << " must lie in (0, 1)");
  TESSERA_CHECK(
      close_vertex_fraction >= 0 && close_vertex_fraction < 1,
      "BezierOptions::close_vertex_fraction = " << close_vertex_fraction << " must lie in [0, 1)");
  TESSERA_CHECK(boundary_snap_fraction >= 0 && boundary_snap_fraction < 0.5,
                "BezierOptions::boundary_snap_fraction = " << boundary_snap_fraction
                                                           << " must lie in [0, 0.5)");
  TESSERA_CHECK(max_vertices >= 3,
                "BezierOptions::max_vertices = " << max_vertices << " must be >= 3");
}

namespace detail {
namespace {

// An edge whose imaginary triangle could not be realised is retried after the other edges
// (their triangles may resolve the conflict); after this many failures the run stops.
constexpr int kMaxEdgeFailures = 3;
// A connection to a front neighbour along the domain's boundary makes a new edge of at most
// this many times the larger step of its ends.
constexpr double kMaxBoundaryConnection = 2.0;
}  // namespace

double BezierBuilder::predicted_step(int a, int b) const {
  // Section 5: s = min(√(θ̄/θ_j) s_j, √(θ̄/θ_k) s_k), the factor capped at max_step_growth.
  const auto grown = [&](int v) {
    const VertexData& data = vertices_[v];
    double factor = options_.max_step_growth;
    if (data.theta > 0) {
      factor = std::min(factor, std::sqrt(options_.target_contraction / data.theta));
    }
    return std::min({factor * data.step, data.step_limit, data.band_limit});
  };
  return std::clamp(std::min(grown(a), grown(b)), min_step_, max_step_);
}

bool BezierBuilder::project_onto_faces(Eigen::VectorXd& y, std::vector<int>& faces,
                                       double& theta) const {
  // Example 3: on a face the point is computed for F restricted to it, i.e. Gauss–Newton on
  // F(x) = 0, b·(x − p) = 0 with minimum-norm corrections (for a box face b = ±e_i it fixes
  // x_i); the shared corrector does this with DF's own factorisation, dense or sparse.
  return tessera::project_onto_faces(problem_, domain_, faces, y,
                                     std::numeric_limits<double>::infinity(), corrector_, &theta);
}

std::optional<NewPoint> BezierBuilder::compute_point(const Eigen::VectorXd& prediction, double s,
                                                     const Eigen::MatrixXd& reference,
                                                     StepFailure& failure) {
  NewPoint point;
  Eigen::VectorXd y = prediction;
  // First Gauss–Newton step and the simplified correction with the same factorisation give
  // Deuflhard's θ₀ = ‖Δ̄y¹‖/‖Δy⁰‖ exactly as in (2.3)/(2.4).
  Eigen::VectorXd F(n_ - 2), dx0(n_), dx_bar(n_);
  problem_.evaluate(y, F);
  if (!F.allFinite() || !point.linearization.factor(problem_, y, &reference)) {
    failure = {"F is not finite or DF is rank deficient at the predicted point " +
                   describe_point(prediction),
               0.5};
    return std::nullopt;
  }
  point.linearization.solve_minimum_norm(-F, dx0);
  y += dx0;
  problem_.evaluate(y, F);
  if (!F.allFinite()) {
    failure = {
        "F is not finite after the first Gauss–Newton step from " + describe_point(prediction),
        0.5};
    return std::nullopt;
  }
  point.linearization.solve_minimum_norm(-F, dx_bar);
  const double norm0 = dx0.norm();
  const double theta =
      norm0 > options_.corrector.tolerance * (1.0 + y.norm()) ? dx_bar.norm() / norm0 : 0.0;
  const auto reduction = [&](double th) {
    return std::clamp(std::sqrt(options_.target_contraction / th), 0.25, 0.7);
  };
  if (theta > options_.max_contraction) {
    std::ostringstream why;
    why << "Gauss–Newton from " << describe_point(prediction)
        << " fails the monotonicity test: θ₀ = " << theta << " > " << options_.max_contraction;
    failure = {why.str(), reduction(theta)};
    return std::nullopt;
  }
  const CorrectorSummary summary =
      project_gauss_newton(problem_, y, corrector_, point.linearization);
  if (!summary.is_success()) {
    failure = {"Gauss–Newton from " + describe_point(prediction) + ": " + summary.brief_report(),
               summary.contraction > 0 ? reduction(summary.contraction) : 0.5};
    return std::nullopt;
  }
  // A corrector that travels farther than the step has left the neighbourhood of the
  // prediction (e.g. onto another sheet): not a neighbour of the edge.
  if ((y - prediction).norm() > 0.75 * s) {
    std::ostringstream why;
    why << "Gauss–Newton from " << describe_point(prediction) << " moved "
        << (y - prediction).norm() << " > 0.75 × step " << s;
    failure = {why.str(), 0.5};
    return std::nullopt;
  }
  point.vertex.theta = theta;
  point.vertex.step = s;
  if (!domain_.is_unbounded()) {
    const double snap = options_.boundary_snap_fraction * s;
    // All faces nearer than the snap distance, nearest first (at most n − 1 constraints in all,
    // so that M ∩ faces is not overdetermined).
    std::vector<std::pair<double, int>> near_faces;
    for (int k = 0; k < static_cast<int>(domain_.half_spaces().size()); ++k) {
      const double distance = domain_.signed_distance(k, y);
      if (distance < snap) {
        near_faces.emplace_back(distance, k);
      }
    }
    std::sort(near_faces.begin(), near_faces.end());
    if (static_cast<int>(near_faces.size()) > 2) {
      near_faces.resize(2);
    }
    if (!near_faces.empty()) {
      const Eigen::VectorXd unconstrained = y;
      // The face sets tried, in order: both near faces (a corner of the box), the nearest, the
      // other. Two near faces need not meet on M, and M need not meet a near face nearby (on
      // the CSTR, Da ≈ x1 near x1 = 0.02: the faces x1 = 0.02 and Da = 0 are both near but
      // M ∩ {Da = 0} lies outside the box).
      std::vector<std::vector<int>> attempts;
      if (near_faces.size() == 2) {
        attempts.push_back({near_faces[0].second, near_faces[1].second});
      }
      for (const auto& [distance, k] : near_faces) {
        attempts.push_back({k});
      }
      bool projected = false;
      for (std::size_t attempt = 0; attempt < attempts.size() && !projected; ++attempt) {
        std::vector<int> faces = attempts[attempt];
        for (int round = 0; round < 2 && !projected; ++round) {
          Eigen::VectorXd z = unconstrained;
          double face_theta = 0.0;
          if (!project_onto_faces(z, faces, face_theta)) {
            break;
          }
          // Another face may now be violated (near an edge of the box): add it and redo.
          const BoundaryDistance other = domain_.boundary_distance(z);
          if (other.signed_distance < -1e-9 * (1.0 + z.norm()) && faces.size() < 2 &&
              std::find(faces.begin(), faces.end(), other.nearest_half_space) == faces.end()) {
            faces.push_back(other.nearest_half_space);
            continue;
          }
          // Moving onto the faces must keep the point inside all the others, and near the edge.
          if (domain_.contains(z, 1e-9 * (1.0 + z.norm())) && (z - unconstrained).norm() <= s) {
            y = z;
            projected = true;
          }
        }
      }
      if (!projected && domain_.contains(unconstrained)) {
        // Snapping is cosmetic for a point inside: when M does not meet the near face there
        // (on the CSTR, Da ≥ 0 is near everywhere but M ∩ {Da = 0} lies outside the box),
        // keep the point where it is instead of shrinking the step.
        y = unconstrained;
        projected = true;
      }
      if (!projected) {
        failure = {"the point " + describe_point(y) +
                       " near the domain boundary could not be moved onto M ∩ boundary",
                   0.5};
        return std::nullopt;
      }
      if (!point.linearization.factor(problem_, y, &reference)) {
        failure = {"DF is rank deficient at the boundary point " + describe_point(y), 0.5};
        return std::nullopt;
      }
    }
  }
  point.vertex.x = y;
  point.vertex.T = point.linearization.tangent_basis();
  align_tangent_basis(point.vertex.T, reference);
  point.vertex.faces = faces_of(y);
  return point;
}

bool BezierBuilder::realize(int a, int b, std::string& why) {
  const int t = edge_triangle_.at(edge_key(a, b));
  const int c = third_vertex(t, a, b);
  // The front neighbours of the edge are always candidates for a close overlap (figure 2).
  const std::optional<int> previous = previous_on_front(a, b, c);
  const std::optional<int> next = next_on_front(a, b, c);
  const Triangle tri = triangles_[t];
  const CubicBezierPatch patch = patches_[t];
  int la = 0, lb = 0, lc = 0;
  for (int i = 0; i < 3; ++i) {
    la = tri[i] == a ? i : la;
    lb = tri[i] == b ? i : lb;
    lc = tri[i] == c ? i : lc;
  }
  // A front loop of three edges is a hole that only one triangle can close; it is closed
  // whatever its shape (a needle is better than a hole, and the topology requires it).
  if (previous && previous == next && *previous != c && !has_edge(a, *previous) &&
      !has_edge(*previous, b)) {
    add_triangle(b, a, *previous);
    ++connections_;
    return true;
  }
  // Copies: adding a vertex may reallocate vertices_.
  const Eigen::VectorXd ya = vertices_[a].x;
  const Eigen::VectorXd yb = vertices_[b].x;
  const Eigen::VectorXd yc = vertices_[c].x;
  const double base = (yb - ya).norm();
  const Eigen::VectorXd midpoint = 0.5 * (ya + yb);
  // Parameter plane <T> of section 5: e1 along the edge, e2 towards c.
  const PlaneFrame parameter_plane(ya, yb, yc);
  TESSERA_ASSERT(parameter_plane.valid);
  const double gamma = parameter_plane.project(yc)(1);
  const double beta_c = parameter_plane.project(yc)(0);
  const Eigen::Vector3d corner_a = Eigen::Vector3d::Unit(la);
  const Eigen::Vector3d corner_b = Eigen::Vector3d::Unit(lb);
  const double rho = options_.overlap_safety;
  const double beta = options_.connection_sector;
  double s = predicted_step(a, b);
  int overlap_reductions = 0;
  std::vector<int> refused;  // connections refused because of the tolerance
  for (int attempt = 0; s >= min_step_ * (1.0 - 1e-12); ++attempt) {
    if (attempt > 0) {
      ++step_reductions_;
    }
    // ỹ = ȳ + s·t on the outward normal of the edge in <T>, in barycentric coordinates.
    const double x1 = 0.5 * base;
    const double x2 = -s;
    const double lambda_c = x2 / gamma;
    const double lambda_b = (x1 - beta_c * lambda_c) / base;
    Eigen::Vector3d lambda = Eigen::Vector3d::Zero();
    lambda(lc) = lambda_c;
    lambda(lb) = lambda_b;
    lambda(la) = 1.0 - lambda_b - lambda_c;
    const Eigen::VectorXd predicted = patch.evaluate(lambda);
    // The imaginary tangents t̂_ij of section 5 from the Bézier net of T̂ = (y_a, y_b, ŷ),
    // i.e. the derivatives of p at the corners of T̂ along its edges.
    double worst_angle = 0.0;
    for (const Eigen::Vector3d& corner : {corner_a, corner_b}) {
      const Eigen::VectorXd t1 = patch.derivative(corner, lambda - corner);
      const Eigen::VectorXd t2 = patch.derivative(lambda, corner - lambda);
      const double norms = t1.norm() * t2.norm();
      const double cosine = norms > 0 ? std::abs(t1.dot(t2)) / norms : 0.0;
      worst_angle = std::max(worst_angle, std::acos(std::min(1.0, cosine)));
    }
    if (std::cos(worst_angle) < options_.min_tangent_cosine) {
      // The tangent angle grows about linearly with the edge: shrink s in proportion.
      s *= std::clamp(0.95 * std::acos(options_.min_tangent_cosine) / worst_angle, 0.25, 0.9);
      continue;
    }
    // Overlaps (section 4), in the plane of the imaginary triangle, apex 0 = ŷ, 1 = a, 2 = b.
    const PlaneFrame plane(ya, yb, predicted);
    if (!plane.valid) {
      s *= options_.step_reduction;
      continue;
    }
    const Eigen::Vector2d A = plane.project(ya), B = plane.project(yb),
                          Y = plane.project(predicted);
    bool overlap = false;
    std::vector<std::pair<double, int>> connectable;  // (distance to ŷ, vertex)
    const double radius = 1.2 * (s + 0.5 * base);
    std::vector<int> candidates = front_vertices_near(midpoint, radius);
    for (const std::optional<int>& neighbour : {previous, next}) {
      if (neighbour &&
          std::find(candidates.begin(), candidates.end(), *neighbour) == candidates.end()) {
        candidates.push_back(*neighbour);
      }
    }
    for (int v : candidates) {
      if (v == a || v == b) {
        continue;
      }
      const Eigen::VectorXd& yv = vertices_[v].x;
      const Eigen::Vector2d pv = plane.project(yv);
      // The plane model is local: vertices far from the plane (another sheet) do not count.
      if (plane.offset(yv) > 0.5 * std::max((pv - 0.5 * (A + B)).norm(), base)) {
        continue;
      }
      // Connecting v must respect α_min on the edges (a, v) and (b, v) that are new. For a front
      // neighbour (close overlap, figure 2) the new edge spans two edges that each satisfy
      // it, so the angle bound is doubled: otherwise a last hole of four vertices on a curved
      // region could not be closed at all (tessera's relaxation; the paper is silent).
      const bool is_neighbour = v == previous || v == next;
      const double min_cosine = is_neighbour
                                    ? std::cos(2.0 * std::acos(options_.min_tangent_cosine))
                                    : options_.min_tangent_cosine;
      if (is_neighbour) {
        // A front neighbour along the domain's boundary (the edge to it lies on a face) can lie
        // far ahead: connecting it then makes a sliver whose long new edge is the next free
        // edge, and one vertex fans out along the face with ever longer edges (bratu2d N = 10
        // at its ignition fold near ε = 0: 2.1, 3.0, 3.6, 4.3, 5.1 with steps ≤ 0.8, until an
        // edge too long to realise stops the run). Such a connection is taken only while its
        // new edge is at most kMaxBoundaryConnection times the steps of its ends.
        const int shared = v == next ? b : a;
        const int other = shared == b ? a : b;
        const double local_step = std::max(vertices_[other].step, vertices_[v].step);
        if (is_boundary_edge(shared, v) &&
            (vertices_[other].x - yv).norm() > kMaxBoundaryConnection * local_step) {
          continue;
        }
      }
      bool compatible = true;
      for (int end : {a, b}) {
        if (has_edge(v, end) || has_edge(end, v)) {
          continue;
        }
        const Eigen::VectorXd t1 = edge_tangent(vertices_[end].T, vertices_[end].x, yv);
        const Eigen::VectorXd t2 = edge_tangent(vertices_[v].T, yv, vertices_[end].x);
        compatible = compatible && std::abs(t1.dot(t2)) >= min_cosine;
      }
      if (!compatible) {
        continue;
      }
      const Eigen::Vector3d l = barycentric(pv, Y, A, B);
      // Softened containment (section 5, ρ) on the sides through ŷ; on the base line the
      // crisp test, since a vertex behind the edge can neither overlap T̂ nor be connected.
      const bool inside = l(0) > 0 && l(1) >= -rho && l(2) >= -rho;
      const bool close = (yv - predicted).norm() < options_.close_vertex_fraction * s;
      overlap = overlap || inside || close;
      const bool in_sector = l(0) >= 0 && l(2) >= beta * (l(1) - 1) && l(1) >= beta * (l(2) - 1);
      if ((in_sector || is_neighbour) && l(0) > 0) {
        connectable.emplace_back((pv - Y).norm(), v);
      }
    }
    // ŷ inside (softened) a triangle at a front vertex nearby: a close or distant overlap.
    if (!overlap) {
      for (int v : front_vertices_near(predicted, radius)) {
        for (int q : vertex_triangles_[v]) {
          if (q == t || overlap) {
            continue;
          }
          const Triangle& other = triangles_[q];
          const PlaneFrame other_plane(vertices_[other[0]].x, vertices_[other[1]].x,
                                       vertices_[other[2]].x);
          if (!other_plane.valid) {
            continue;
          }
          const double size = std::max({(vertices_[other[1]].x - vertices_[other[0]].x).norm(),
                                        (vertices_[other[2]].x - vertices_[other[1]].x).norm(),
                                        (vertices_[other[0]].x - vertices_[other[2]].x).norm()});
          if (other_plane.offset(predicted) > 0.5 * std::max(size, s)) {
            continue;
          }
          const Eigen::Vector3d l = barycentric(other_plane.project(predicted),
                                                other_plane.project(vertices_[other[0]].x),
                                                other_plane.project(vertices_[other[1]].x),
                                                other_plane.project(vertices_[other[2]].x));
          overlap = l.minCoeff() >= -rho;
        }
      }
    }
    std::sort(connectable.begin(), connectable.end());
    // With a tolerance, a connection whose new edges are farther from M than it is taken only
    // when the step cannot be reduced further for this edge (a smaller imaginary triangle may
    // avoid the overlap and give a new point instead).
    const bool strict = options_.tolerance > 0 && overlap_reductions < 2;
    const auto connect = [&]() {
      for (const auto& [distance, v] : connectable) {
        if (strict && !(new_edges_distance(a, b, v) <= options_.tolerance)) {
          continue;
        }
        if (is_admissible(a, b, c, v, vertices_[v].x)) {
          add_triangle(b, a, v);
          ++connections_;
          return true;
        }
      }
      return false;
    };
    if (overlap) {
      if (connect()) {
        return true;
      }
      if (strict) {
        // Remember the connections refused for the tolerance: the last resort below.
        for (const auto& candidate : connectable) {
          refused.push_back(candidate.second);
        }
      }
      if (++overlap_reductions > 2) {
        for (int v : refused) {
          if (is_admissible(a, b, c, v, vertices_[v].x)) {
            add_triangle(b, a, v);
            ++connections_;
            return true;
          }
        }
        std::ostringstream message;
        message << "the imaginary triangle at edge (" << a << ", " << b << ") between "
                << describe_point(ya) << " and " << describe_point(yb)
                << " overlaps the mesh and no vertex in its connection sector can be connected";
        why = message.str();
        return false;
      }
      s *= options_.step_reduction;
      continue;
    }
    // Realise T̂ by a new solution.
    StepFailure failure;
    std::optional<NewPoint> point = compute_point(predicted, s, vertices_[a].T, failure);
    if (!point) {
      why = failure.why;
      s *= failure.factor;
      continue;
    }
    if (const auto angle = worst_tangent_angle(a, *point, b)) {
      s *= std::clamp(0.95 * std::acos(options_.min_tangent_cosine) / *angle, 0.25, 0.9);
      std::ostringstream message;
      message << "the tangent planes at the ends of a new edge differ by " << *angle * 180 / std::numbers::pi
              << "° at " << describe_point(point->vertex.x);
      why = message.str();
      continue;
    }
    if (options_.tolerance > 0) {
      // Distance of the midpoints of the new edges to M by one simplified Gauss–Newton step.
      double distance = 0.0;
      Eigen::VectorXd F(n_ - 2), dx(n_);
      for (int end : {a, b}) {
        const Eigen::VectorXd mid = 0.5 * (vertices_[end].x + point->vertex.x);
        problem_.evaluate(mid, F);
        point->linearization.solve_minimum_norm(-F, dx);
        distance = std::max(distance, dx.norm());
      }
      if (distance > options_.tolerance) {
        s *= std::clamp(0.9 * std::sqrt(options_.tolerance / distance), 0.25, 0.9);
        std::ostringstream message;
        message << "new edges at " << describe_point(point->vertex.x) << " are " << distance
                << " from M, more than the tolerance " << options_.tolerance;
        why = message.str();
        continue;
      }
      point->vertex.step_limit =
          s * std::min(options_.max_step_growth,
                       0.9 * std::sqrt(options_.tolerance / std::max(distance, 1e-300)));
    }
    // The real triangle must not overlap the mesh, and must not end next to a front vertex.
    bool near_vertex = false;
    for (int v : front_vertices_near(point->vertex.x, options_.close_vertex_fraction * s)) {
      near_vertex = near_vertex || (v != a && v != b);
    }
    if (near_vertex || !is_admissible(a, b, c, -1, point->vertex.x)) {
      if (connect()) {
        return true;
      }
      s *= options_.step_reduction;
      why = "the new triangle at " + describe_point(point->vertex.x) + " would overlap the mesh";
      continue;
    }
    const int v = add_vertex(std::move(point->vertex));
    add_triangle(b, a, v);
    return true;
  }
  std::ostringstream message;
  message << "cannot realise the imaginary triangle at edge (" << a << ", " << b << ") between "
          << describe_point(ya) << " and " << describe_point(yb) << " even with step " << min_step_
          << (why.empty() ? "" : "; last reason: ") << why;
  why = message.str();
  return false;
}

void BezierBuilder::build_initial_triangle(const StartPoint& start) {
  VertexData first;
  first.x = start.x;
  first.T = start.linearization.tangent_basis();
  first.step = options_.step;
  // The start's own contraction reflects the user's guess, not the surface: use θ̄, so the
  // first predicted steps are the initial step itself.
  first.theta = options_.target_contraction;
  first.faces = faces_of(first.x);
  const Eigen::MatrixXd T0 = first.T;
  const Eigen::VectorXd y0 = first.x;
  add_vertex(std::move(first));
  // Tangent continuation in two directions 60° apart (the paper: "two linearly independent
  // tangents"; 60° gives an equilateral start).
  double s = options_.step;
  std::string why;
  for (int attempt = 0; attempt < 24; ++attempt) {
    std::vector<NewPoint> points;
    bool ok = true;
    for (double angle : {0.0, std::numbers::pi / 3}) {
      const Eigen::VectorXd direction = T0 * Eigen::Vector2d(std::cos(angle), std::sin(angle));
      StepFailure failure;
      auto point = compute_point(y0 + s * direction, s, T0, failure);
      if (!point) {
        why = failure.why;
        ok = false;
        break;
      }
      points.push_back(std::move(*point));
    }
    if (ok) {
      for (const NewPoint& p : points) {
        ok = ok && !worst_tangent_angle(0, p, -1);
      }
      const Eigen::VectorXd t12 =
          edge_tangent(points[0].vertex.T, points[0].vertex.x, points[1].vertex.x);
      const Eigen::VectorXd t21 =
          edge_tangent(points[1].vertex.T, points[1].vertex.x, points[0].vertex.x);
      ok = ok && std::abs(t12.dot(t21)) >= options_.min_tangent_cosine;
      const PlaneFrame plane(y0, points[0].vertex.x, points[1].vertex.x);
      ok = ok && plane.valid;
      if (!ok) {
        why = "the tangent planes of the initial triangle differ by more than arccos(α_min)";
      }
    }
    double reduction = options_.step_reduction;
    if (ok && options_.tolerance > 0) {
      // The tolerance holds for the initial triangle's edges too: every later edge is at least
      // half as long as the edge it grows from, so a too long first edge could never be fixed.
      const std::array<Eigen::VectorXd, 3> corners{y0, points[0].vertex.x, points[1].vertex.x};
      double distance = 0.0;
      Eigen::VectorXd F(n_ - 2), dx(n_);
      for (int e = 0; e < 3; ++e) {
        const Eigen::VectorXd mid = 0.5 * (corners[e] + corners[(e + 1) % 3]);
        problem_.evaluate(mid, F);
        points[0].linearization.solve_minimum_norm(-F, dx);
        distance = std::max(distance, dx.norm());
      }
      if (distance > options_.tolerance) {
        ok = false;
        reduction = std::clamp(0.9 * std::sqrt(options_.tolerance / distance), 0.25, 0.9);
        why = "the initial triangle's edges are farther from M than the tolerance";
      }
    }
    if (ok) {
      const int v1 = add_vertex(std::move(points[0].vertex));
      const int v2 = add_vertex(std::move(points[1].vertex));
      add_triangle(0, v1, v2);
      return;
    }
    s *= reduction;
  }
  throw ComputationFailed("the initial triangle at " + describe_point(y0) +
                          " could not be built: " + why);
}

void BezierBuilder::run() {
  while (!queue_.empty()) {
    const QueueEntry entry = queue_.top();
    queue_.pop();
    if (!is_free(entry.a, entry.b) || is_boundary_edge(entry.a, entry.b)) {
      continue;
    }
    const double key = front_angle(entry.a, entry.b);
    if (key > entry.key + 1e-12) {
      queue_.push({key, entry.a, entry.b});
      continue;
    }
    std::string why;
    if (realize(entry.a, entry.b, why)) {
      continue;
    }
    // Retry later: the triangles added at the other edges may resolve the conflict, and an
    // edge is pushed again whenever a triangle is added at one of its ends.
    int& failures = failures_[edge_key(entry.a, entry.b)];
    if (failures == 0) {
      failure_messages_.emplace_back(edge_key(entry.a, entry.b), why);
    }
    if (++failures < kMaxEdgeFailures) {
      queue_.push({front_angle(entry.a, entry.b), entry.a, entry.b});
    }
  }
  // Edges that are still free (and not on the domain boundary) could not be realised.
  for (const auto& [key, message] : failure_messages_) {
    const int a = static_cast<int>(key >> 32);
    const int b = static_cast<int>(key & 0xffffffffu);
    if (is_free(a, b) && !is_boundary_edge(a, b)) {
      throw StopRun{CoveringTermination::FrontCollision, message};
    }
  }
}

}  // namespace detail

using detail::BezierBuilder;
using detail::StopRun;

CoveringResult triangulate_by_bezier_continuation(const ImplicitProblem& problem,
                                                  const Eigen::VectorXd& start,
                                                  const Domain& domain,
                                                  const BezierOptions& options) {
  options.validate();
  // Its continuation works on whole n-vectors; only the atlas reduces over split points.
  TESSERA_CHECK(!problem.space()->is_distributed(),
                "method bezier: the problem's points are split over MPI ranks, which only method "
                "atlas supports (docs/cluster.md); use --method atlas");
  return run_covering("bezier", problem, start, domain, options,
                      [&options](CoveringContext& context, CoveringResult& result) {
                        result.summary.step = options.step;
                        result.patch_edge_length_factor = options.edge_length_factor;
                        BezierBuilder builder(context.problem, context.domain, options);
                        try {
                          builder.build_initial_triangle(context.start);
                        } catch (const ComputationFailed& failure) {
                          result.summary.termination = CoveringTermination::StartFailed;
                          result.summary.message = failure.what();
                          return;
                        } catch (const StopRun& stop) {
                          // A stop request (or the vertex limit) before the first triangle
                          // was made: an outcome with an empty mesh, not an escaping throw.
                          result.summary.termination = stop.termination;
                          result.summary.message = stop.message;
                          return;
                        }
                        try {
                          builder.run();
                        } catch (const StopRun& stop) {
                          result.summary.termination = stop.termination;
                          result.summary.message = stop.message;
                        }
                        builder.extract(result);
                        detail::repair_shapes(context.problem, options, result);
                        result.summary.merges = builder.connections();
                        result.summary.step_reductions = builder.step_reductions();
                      });
}

}  // namespace tessera
