// SPDX-License-Identifier: MIT
// The atlas's measurement of M around a chart: the radius of its disk (Henderson's section 2.4)
// and pointOnDisk, the projection of a point of the disk onto M along the chart's normal space.
#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

#include "tessera/core/corrector.h"
#include "tessera/methods/atlas/atlas_builder.h"

namespace tessera::detail {
namespace {

// pointOnDisk by full Gauss–Newton (where the chord fails) is accepted if it moved the point
// along the chart's tangent plane by at most this fraction of the distance from the centre.
constexpr double kMaxTangentialDrift = 0.1;
// choose_radius probes M at r and at this fraction of r: the slope between them is the
// turning of the tangent plane near the rim of the disk.
constexpr double kInnerProbe = 0.75;
// A radius probe is projected until its offset is known to this fraction of the tolerance: an
// error δ in an offset of about ε (the offset at the chosen radius) changes the radius by δ/(2ε),
// here 0.05 %. Two or three chord steps where the solver's tolerance (1e-10) took five or six.
constexpr double kProbeAccuracy = 1e-3;
// Where probes are full projections, the first measurement is made at this multiple of the
// parent's radius (the radius a chart most likely gets), not at the graded bound
// radius_growth·R_parent (1.5): measured at 1.5 R the parent's radius is below the acceptance
// ratio 0.7, and every chart of a smooth surface was measured twice (torus at 1e-3: 2.0
// measurements, 136 evaluations of F per chart). 1.4 is just below 1/0.7: a radius down to
// 0.98 R_parent is accepted at once, a smaller one measured again at its size as before; one that
// wants to grow beyond 1.4 R_parent is measured again there, up to the bound.
constexpr double kExpectedSlack = 1.4;

}  // namespace

// Henderson's section 2.4: with a(s,t) the offset of M from the tangent plane,
// R = sqrt(2ε/|a_ss|). Instead of second derivatives of F, the offset is measured where it
// matters: six points at distance r in directions 0°, 60°, …, 300° are projected onto M
// orthogonally to the tangent plane (the chord corrector of the chart, pointOnDisk).
//  - The even part of the offsets, q_i = (a(θ_i) + a(θ_i + π))/r² = A + B cos 2θ_i +
//    C sin 2θ_i (exactly for the quadratic and cubic parts of a), gives the quadratic form;
//    the largest |A + B cos 2θ + C sin 2θ| over θ is the largest normal curvature κ_q.
//  - Each offset alone gives the secant curvature 2|a(θ_j)|/r², which also sees the cubic
//    (odd) part: where the curvature grows across the disk (towards a thin part of M, a fold,
//    the turn of the trough), the disk is sized by the largest curvature it contains.
// κ is the larger of the two. The radius R = min(r, sqrt(2ε/κ), max_turning_angle/κ) is then
// measured again at R, until the disk the measurement covered is not much larger than the
// disk chosen (R ≥ 0.7 r): a radius is only accepted if M was seen across the whole disk.
// The radius is also capped where M is not a graph of slope ≤ 1 over the disk of radius r, or
// the corrector does not converge that far (r is halved): the disk then reaches past a
// turn of M or onto another part of it, so its tangent-plane projection is not one-to-one.
bool AtlasBuilder::choose_radius(Linearization& at_center, double trial, double expected,
                                 double& radius, RadiusCap& cap) {
  const Eigen::VectorXd& x = at_center.point();
  const Eigen::MatrixXd& T = at_center.tangent_basis();
  double r = trial;
  // (Full projections only: the first-step probes of large n are left as they were.)
  bool from_expected = !first_step_probes_ && expected > 0 && kExpectedSlack * expected < trial;
  if (from_expected) {
    r = kExpectedSlack * expected;
  }
  int measurements = 0;
  bool halved = false;  // the corrector or the graph test refused a larger disk
  bool turned = false;  // a remeasurement was asked for by the curvature cap
  Eigen::VectorXd& y = probe_;
  Eigen::VectorXd& predicted = predicted_;
  Eigen::MatrixXd& a = quadratic_;
  a.resize(rows_, 12);  // columns 0–5: a(θ_i) at r; 6–11: a(θ_i) at kInnerProbe·r
  // Sparse (large n) problems: each probe is the chord's first step only, −J⁺F at the predicted
  // point, which is the offset to second order; and the inner ring is left out. 6 evaluations of
  // F and 6 solves per measurement instead of 12 projections of 3–5 steps each: at large n a
  // solve costs a fair part of a factorisation. What the inner ring and the full projections
  // guard against (curvature growing towards the rim, a disk past a turn of M) is checked
  // where it matters, when a child is projected onto the disk's rim (run()), and the tolerance
  // is checked on every triangle afterwards.
  const int probes = first_step_probes_ ? 6 : 12;
  Eigen::MatrixXd& F = probe_residuals_;
  Eigen::MatrixXd& step = probe_steps_;
  while (r >= min_radius_) {
    bool is_graph = true;
    if (first_step_probes_) {
      // The six first steps share one multi-column solve.
      F.resize(space_->local_equations(), 6);
      step.resize(rows_, 6);
      for (int i = 0; i < 6 && is_graph; ++i) {
        const double theta = i * std::numbers::pi / 3.0;
        predicted = x + r * (T * Eigen::Vector2d(std::cos(theta), std::sin(theta)));
        problem_.evaluate(predicted, F.col(i));
        is_graph = space_->all_finite(F.col(i));
      }
      if (is_graph) {
        F = -F;
        at_center.solve_minimum_norm_columns(F, step);
      }
      for (int i = 0; i < 6 && is_graph; ++i) {
        // The offset: the chord's step is normal to the tangent plane.
        const Eigen::Vector2d along = space_->tangent_coordinates(T, step.col(i));
        a.col(i) = step.col(i) - T * along;
        // Slope above 1 across the disk: the probe found a far part of M, not a graph.
        is_graph = space_->norm(a.col(i)) <= r;
      }
    }
    std::array<double, 6> contraction{};  // of the outer probes' chords (−1: not a chord)
    for (int i = 0; i < probes && is_graph && !first_step_probes_; ++i) {  // full projections
      const double theta = (i % 6) * std::numbers::pi / 3.0;
      const double distance = i < 6 ? r : kInnerProbe * r;
      predicted = x + distance * (T * Eigen::Vector2d(std::cos(theta), std::sin(theta)));
      y = predicted;
      if (i < 6) {
        is_graph = probe(at_center, distance, y, -1.0, -1.0, &contraction[i]);
      } else {
        // The inner probe starts from the outer one's offset scaled as a quadratic (still on
        // the normal space of the chart, so pointOnDisk is the same point), off by the cubic
        // part only; the outer chord's contraction, larger than the inner one's, bounds its
        // remainder from the first step on: one step where it took two or three.
        y += kInnerProbe * kInnerProbe * a.col(i - 6);
        is_graph = probe(at_center, distance, y, contraction[i - 6],
                         kInnerProbe * kInnerProbe * space_->norm(a.col(i - 6)));
      }
      y -= predicted;  // the offset; its tangential part is zero for the chord, not for GN
      const Eigen::Vector2d along = space_->tangent_coordinates(T, y);
      a.col(i) = y - T * along;
      // Slope above 1 across the disk: the projection found a far part of M, not a graph.
      is_graph = is_graph && space_->norm(a.col(i)) <= distance;
    }
    if (!is_graph) {
      r *= 0.5;
      halved = true;
      continue;
    }
    ++measurements;
    // q_i = A + B cos 2θ_i + C sin 2θ_i at θ = 0°, 60°, 120°.
    // |A + cos φ B + sin φ C| over φ = 2θ in [0, 2π), with A = mean q, B = q0 − A,
    // C = (q1 − q2)/√3, written as weights of q0, q1, q2 (tabulated once).
    static const std::array<std::array<double, 3>, 24> weights = [] {
      std::array<std::array<double, 3>, 24> w{};
      for (int k = 0; k < 24; ++k) {
        const double phi = k * std::numbers::pi / 12.0;
        const double c = (1.0 - std::cos(phi)) / 3.0;
        w[k] = {c + std::cos(phi), c + std::sin(phi) / std::sqrt(3.0),
                c - std::sin(phi) / std::sqrt(3.0)};
      }
      return w;
    }();
    // Largest ‖Q(θ)‖ over θ of the form through the values at three directions 60° apart
    // (split over ranks: the 24 squared norms summed in one call).
    const auto largest = [&](const auto& q0, const auto& q1, const auto& q2) {
      double value = 0.0;
      if (!space_->is_distributed()) {
        for (const auto& w : weights) {
          value = std::max(value, (w[0] * q0 + w[1] * q1 + w[2] * q2).norm());
        }
        return value;
      }
      std::array<double, 24> squares{};
      for (std::size_t k = 0; k < weights.size(); ++k) {
        const auto& w = weights[k];
        squares[k] = (w[0] * q0 + w[1] * q1 + w[2] * q2).squaredNorm();
      }
      space_->sum(squares.data(), static_cast<int>(squares.size()));
      for (double square : squares) {
        value = std::max(value, std::sqrt(square));
      }
      return value;
    };
    // Each half of the disk (θ = 0°, 60°, 120° and θ = 180°, 240°, 300°) gets its own form, so
    // that a curvature growing towards one side is not averaged with the other side.
    const double scale = 2.0 / (r * r);
    const double curvature = scale * std::max(largest(a.col(0), a.col(1), a.col(2)),
                                              largest(a.col(3), a.col(4), a.col(5)));
    // The turning of the tangent plane near the rim of the disk, from the slope of a between
    // the inner and outer probes, also as a form over the directions: on a circle of
    // curvature κ the slope is tan(κ·(mean of the two radii)).
    const double step = (1.0 - kInnerProbe) * r;
    const double slope =
        first_step_probes_
            ? 0.0
            : std::max(largest(a.col(0) - a.col(6), a.col(1) - a.col(7), a.col(2) - a.col(8)),
                       largest(a.col(3) - a.col(9), a.col(4) - a.col(10), a.col(5) - a.col(11))) /
                  step;
    const double rim_curvature = std::atan(slope) / (0.5 * (1.0 + kInnerProbe) * r);
    const double for_tolerance =
        curvature > 0 ? std::sqrt(2.0 * options_.tolerance / curvature) : options_.step;
    // Where the curvature grows towards the rim (a thin part or a turn of M ahead), the
    // turning measured there exceeds κ·r: the disk is then sized by it.
    const double largest_curvature = std::max(curvature, rim_curvature);
    const double for_turning = largest_curvature > 0
                                   ? options_.max_turning_angle / largest_curvature
                                   : options_.step;
    const double wanted = std::min({options_.step, for_tolerance, for_turning});
    const double chosen = std::min(r, wanted);
    if (from_expected && !halved && wanted > 1.01 * r && measurements < 4) {
      // Measured at the expected radius, M allows a larger disk: measured again there (up to
      // the graded bound), so that a radius may grow as before.
      from_expected = false;
      r = std::min(trial, wanted);
      continue;
    }
    if (chosen < 0.7 * r && measurements < 4) {
      // Measured beyond the radius chosen: measure again there, where the quadratic model
      // is accurate (third-order terms shrink by the ratio of the radii), and so that the
      // secant sees the largest curvature inside the chosen disk, not a larger one.
      turned = turned || for_turning <= chosen;
      r = chosen;
      continue;
    }
    radius = chosen;
    // Capped: smaller than the tolerance (and max_radius) would allow, by the curvature
    // (κR ≤ max_turning_angle: the local feature size), by the corrector or the graph test,
    // or else by the trial radius (the grading of the radii between neighbouring charts).
    if (chosen < 0.99 * std::min(options_.step, for_tolerance)) {
      cap = turned || for_turning <= chosen ? RadiusCap::Curvature
            : halved                        ? RadiusCap::NotAGraph
                                            : RadiusCap::Grading;
    } else {
      cap = RadiusCap::None;
    }
    return true;
  }
  return false;
}

// pointOnDisk for a radius probe: the chart's chord, stopped once the offset is known to
// kProbeAccuracy·min(ε, offset), `offset` its expected size (< 0: the first step's). The
// remainder of a chord contracting by θ after a step dx is at most θ/(1 − θ)·‖dx‖, θ the largest
// ratio of successive steps seen, at least `known_contraction` where that is ≥ 0 (then the first
// step may suffice). `contraction` (may be null) receives the θ used, −1 where the chord was not
// used. Where the chord does not contract, project() decides, as for any other point.
bool AtlasBuilder::probe(Linearization& at_center, double distance, Eigen::VectorXd& y,
                         double known_contraction, double offset, double* contraction) {
  double accuracy = kProbeAccuracy * options_.tolerance;
  if (offset >= 0.0) {
    accuracy = std::min(accuracy, kProbeAccuracy * offset);
  }
  const CorrectorOptions& corrector = options_.corrector;
  probe_start_ = y;
  probe_residual_.resize(space_->local_equations());
  probe_step_.resize(rows_);
  double previous = 0.0;
  // θ: the largest ratio of successive steps, or the one the caller knows to bound this chord's.
  const bool is_known = known_contraction >= 0.0 && known_contraction <= corrector.max_contraction;
  double theta = is_known ? known_contraction : 0.0;
  if (contraction != nullptr) {
    *contraction = -1.0;
  }
  for (int k = 0; k < corrector.max_iterations; ++k) {
    problem_.evaluate(y, probe_residual_);
    if (!space_->all_finite(probe_residual_)) {
      break;
    }
    probe_residual_ = -probe_residual_;
    at_center.solve_minimum_norm(probe_residual_, probe_step_);
    const double correction = space_->norm(probe_step_);
    if (k == 0 && offset < 0.0) {
      // The first step is the offset to first order: where it is below ε (a disk held small by
      // the curvature or the reach), the accuracy follows it.
      accuracy = std::min(accuracy, kProbeAccuracy * correction);
    }
    y += probe_step_;
    if (correction <= corrector.tolerance * (1.0 + space_->norm(y))) {
      if (contraction != nullptr) {
        *contraction = theta;
      }
      return true;  // the solver's own criterion (reached first where ε is tiny)
    }
    if (k > 0) {
      theta = std::max(theta, correction / previous);
      if (theta > corrector.max_contraction) {
        break;
      }
    }
    if ((k > 0 || is_known) && theta / (1.0 - theta) * correction <= accuracy) {
      if (contraction != nullptr) {
        *contraction = theta;
      }
      return true;
    }
    previous = correction;
  }
  y = probe_start_;
  return project(at_center, distance, y);
}

// Henderson's pointOnDisk: F(y) = 0 with Tᵀ(y − y_predicted) = 0, by the chord iteration of
// the chart. Across a singular curve the frozen J points the wrong way (F = z·S changes the
// sign of its gradient with z), so a failed chord is retried with full Gauss–Newton, which
// re-evaluates J and lands on the same sheet. Its tangential drift must stay small: a large
// one means the line through y normal to the chart misses M (the disk reaches past a turn of
// M) and Gauss–Newton found the nearest point of M instead, which is not pointOnDisk's point:
// a radius measured there is meaningless and a chart centred there would not cut away the
// corner it was placed for.
bool AtlasBuilder::project(Linearization& at_center, double distance, Eigen::VectorXd& y) {
  const Eigen::VectorXd predicted = y;
  if (project_chord(problem_, at_center, y, options_.corrector).is_success()) {
    return true;
  }
  // A chord from a borrowed factorisation contracts more slowly: before Gauss–Newton (a
  // factorisation per step) the chart factors its own, once, and the chord is tried again.
  if (factor_own(at_center)) {
    y = predicted;
    if (project_chord(problem_, at_center, y, options_.corrector).is_success()) {
      return true;
    }
  }

  y = predicted;
  CorrectorOptions full = options_.corrector;
  full.max_displacement = 0.5 * distance;
  full.reuse_factorisation = true;  // scratch_ is not used afterwards
  // Guided by the chart's basis, not by what scratch_ held last: the projection then depends on
  // its inputs only, which a resumed build (atlas_checkpoint.h) needs to repeat it.
  full.first_reference = &at_center.tangent_basis();
  if (!project_gauss_newton(problem_, y, full, scratch_).is_success()) {
    return false;
  }
  const Eigen::Vector2d drift =
      space_->tangent_coordinates(at_center.tangent_basis(), y - predicted);
  return drift.norm() <= kMaxTangentialDrift * distance;
}

bool AtlasBuilder::factor_own(Linearization& at_center) {
  if (!at_center.solves_from_elsewhere()) {
    return false;
  }
  Linearization own;
  if (!own.factor(problem_, at_center.point(), &at_center.tangent_basis())) {
    return false;
  }
  lenders_.lend(problem_, own);
  return at_center.borrow(problem_, own, at_center.point(), at_center.tangent_basis());
}

}  // namespace tessera::detail
