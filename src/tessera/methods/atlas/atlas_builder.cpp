// SPDX-License-Identifier: MIT
#include "tessera/methods/atlas/atlas_builder.h"

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

#include "tessera/core/corrector.h"
#include "tessera/core/describe.h"
#include "tessera/methods/common/clip_to_domain.h"

namespace tessera::detail {
namespace {

// The initial polygon is a square of this half-width (in radii): it contains the disk, and its
// corners (at 1.7 R) are exterior until neighbours cut them.
constexpr double kInitialHalfWidth = 1.2;
// A chart is processed until its polygon has no exterior vertex; more children than this
// means the cuts do not remove the vertices they should (rounding, or charts on other sheets).
constexpr int kMaxChildrenPerChart = 64;
// Below this dimension the orientation det([J; Tᵀ]) is cheap enough to watch for singular
// crossings at every step (dense problems only; see docs/algorithms/atlas.md).
constexpr int kMaxCrossingTestDimension = 200;

}  // namespace

AtlasBuilder::AtlasBuilder(const ImplicitProblem& problem, const Domain& domain,
                           const AtlasOptions& options)
    : problem_(problem),
      domain_(domain),
      options_(options),
      n_(problem.ambient_dimension()),
      index_(problem.ambient_dimension()),
      watch_crossings_(!problem.has_sparse_jacobian() &&
                       problem.ambient_dimension() <= kMaxCrossingTestDimension) {}

// Henderson's section 2.4: with a(s,t) the offset of M from the tangent plane,
// R = sqrt(2ε/|a_ss|). Instead of second derivatives of F, the quadratic form of a is measured
// where it matters: three points at distance r in directions 0°, 60°, 120° are projected onto
// M orthogonally to the tangent plane (the chord corrector of the chart), and their normal
// offsets a_i give q_i = 2a_i/r² = A + B cos 2θ_i + C sin 2θ_i. The largest |A + B cos 2θ +
// C sin 2θ| over θ is the largest normal curvature κ. If a projection fails, the corrector does
// not converge that far: r is halved (the radius is also "capped by where the corrector
// converges").
bool AtlasBuilder::choose_radius(const Linearization& at_center, double trial, double& radius) {
  const Eigen::VectorXd& x = at_center.point();
  const Eigen::MatrixXd& T = at_center.tangent_basis();
  double r = trial;
  bool remeasured = false;
  Eigen::VectorXd& y = probe_;
  Eigen::VectorXd& predicted = predicted_;
  Eigen::MatrixXd& q = quadratic_;
  q.resize(n_, 3);
  while (r >= min_radius_) {
    bool converged = true;
    static const std::array<Eigen::Vector2d, 3> directions = {
        Eigen::Vector2d(1.0, 0.0), Eigen::Vector2d(0.5, std::sqrt(3.0) / 2),
        Eigen::Vector2d(-0.5, std::sqrt(3.0) / 2)};  // θ = 0°, 60°, 120°
    for (int i = 0; i < 3 && converged; ++i) {
      const Eigen::Vector2d& d = directions[i];
      predicted = x + r * (T * d);
      y = predicted;
      converged = project(at_center, r, y);
      y -= predicted;  // the offset; its tangential part is zero for the chord, not for GN
      const Eigen::Vector2d along = T.transpose() * y;
      q.col(i) = (2.0 / (r * r)) * (y - T * along);
    }
    if (!converged) {
      r *= 0.5;
      continue;
    }
    // q_i = A + B cos 2θ_i + C sin 2θ_i at θ = 0°, 60°, 120°.
    // |A + cos φ B + sin φ C| over φ = 2θ in [0, 2π), with A = mean q, B = q0 − A,
    // C = (q1 − q2)/√3, written as weights of q0, q1, q2 (tabulated once).
    static const std::array<std::array<double, 3>, 24> weights = [] {
      std::array<std::array<double, 3>, 24> w{};
      for (int k = 0; k < 24; ++k) {
        const double phi = k * std::numbers::pi / 12.0;
        const double a = (1.0 - std::cos(phi)) / 3.0;
        w[k] = {a + std::cos(phi), a + std::sin(phi) / std::sqrt(3.0),
                a - std::sin(phi) / std::sqrt(3.0)};
      }
      return w;
    }();
    double curvature = 0.0;
    for (const auto& w : weights) {
      curvature = std::max(curvature, (w[0] * q.col(0) + w[1] * q.col(1) + w[2] * q.col(2)).norm());
    }
    double chosen = std::min(options_.step, r);
    if (curvature > 0) {
      chosen = std::min({chosen, std::sqrt(2.0 * options_.tolerance / curvature),
                         options_.max_turning_angle / curvature});
    }
    if (chosen < 0.5 * r && !remeasured) {
      // Measured far beyond the radius chosen: measure again there, where the quadratic
      // model is accurate (third-order terms shrink by the ratio of the radii).
      remeasured = true;
      r = chosen;
      continue;
    }
    radius = chosen;
    return true;
  }
  return false;
}

// Henderson's pointOnDisk: F(y) = 0 with Tᵀ(y − y_predicted) = 0, by the chord iteration of
// the chart. Across a singular curve the frozen J points the wrong way (F = z·S changes the
// sign of its gradient with z), so a failed chord is retried with full Gauss–Newton, which
// re-evaluates J and lands on the same sheet; its small tangential drift does not matter.
bool AtlasBuilder::project(const Linearization& at_center, double distance, Eigen::VectorXd& y) {
  const Eigen::VectorXd predicted = y;
  if (project_chord(problem_, at_center, y, options_.corrector).is_success()) {
    return true;
  }
  y = predicted;
  CorrectorOptions full = options_.corrector;
  full.max_displacement = 0.5 * distance;
  return project_gauss_newton(problem_, y, full, scratch_).is_success();
}

void AtlasBuilder::evaluate_jacobian(const Eigen::VectorXd& x) {
  jacobian_.resize(n_ - 2, n_);
  problem_.jacobian(x, jacobian_);
}

// σ_min(J) of the last evaluate_jacobian: how far the point is from the singular points of F
// (for codimension 1, |∇F|).
double AtlasBuilder::jacobian_scale() const {
  const int m = n_ - 2;
  const Eigen::MatrixXd& J = jacobian_;
  if (m == 1) {
    return J.norm();
  }
  const Eigen::MatrixXd gram = J * J.transpose();
  return std::sqrt(
      std::max(0.0, Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(gram, Eigen::EigenvaluesOnly)
                        .eigenvalues()(0)));
}

signed char AtlasBuilder::orientation_sign(const Eigen::Ref<const Eigen::MatrixXd>& T) const {
  // sign det([J; Tᵀ]) with J of the last evaluate_jacobian: along one sheet it keeps its sign
  // as long as T stays transversal to ker J; it changes where J loses rank between two
  // points, i.e. at a singular curve.
  const int m = n_ - 2;
  const Eigen::MatrixXd& J = jacobian_;
  double det = 0.0;
  if (n_ == 3) {
    const Eigen::Vector3d t0 = T.col(0);
    const Eigen::Vector3d t1 = T.col(1);
    det = J.row(0).transpose().dot(Eigen::Vector3d(t0.cross(t1)));
  } else {
    Eigen::MatrixXd bordered(n_, n_);
    bordered.topRows(m) = J;
    bordered.bottomRows(2) = T.transpose();
    det = bordered.partialPivLu().determinant();
  }
  return det > 0 ? 1 : (det < 0 ? -1 : 0);
}

int AtlasBuilder::add_chart(const Eigen::VectorXd& x, int parent, Linearization& linearization) {
  Eigen::MatrixXd& parent_tangent = parent_tangent_;
  if (parent >= 0) {
    parent_tangent = tangent(parent);
  }
  if (!linearization.factor(problem_, x, parent >= 0 ? &parent_tangent : nullptr)) {
    return -1;  // DF lost rank: a singular point; the caller moves the centre
  }
  if (parent >= 0 &&
      std::abs((parent_tangent.transpose() * linearization.tangent_basis()).determinant()) <
          options_.min_sheet_cosine) {
    return -1;  // the projection jumped to another sheet; the caller tries another point
  }
  const double trial =
      parent >= 0 ? std::min(options_.step, options_.radius_growth * charts_[parent].radius)
                  : options_.step;
  double radius = 0.0;
  if (!choose_radius(linearization, trial, radius)) {
    return -2;
  }
  const int k = chart_count();
  Chart chart;
  chart.radius = radius;
  chart.polygon = ChartPolygon(kInitialHalfWidth * radius);
  chart.parent = parent;
  if (watch_crossings_) {
    // J at x was evaluated by the caller (the crossing checks); the first chart's here.
    if (parent < 0) {
      evaluate_jacobian(x);
    }
    chart.orientation = orientation_sign(linearization.tangent_basis());
    chart.jacobian_scale = static_cast<float>(jacobian_scale());
  }
  charts_.push_back(std::move(chart));
  centers_.insert(centers_.end(), x.data(), x.data() + n_);
  const Eigen::MatrixXd& T = linearization.tangent_basis();
  tangents_.insert(tangents_.end(), T.data(), T.data() + 2 * n_);
  connect_neighbours(k);
  index_.insert(k, x, radius);
  return k;
}

bool AtlasBuilder::same_sheet(int a, int b, const Eigen::VectorXd& offset) const {
  // Charts on one sheet have nearly parallel tangent planes and each centre lies close to the
  // other's tangent plane; charts of two sheets that cross (section 8) fail the first test,
  // charts of two nearby parallel sheets the second.
  const Eigen::Matrix2d cosines = tangent(a).transpose() * tangent(b);
  if (std::abs(cosines.determinant()) < options_.min_sheet_cosine) {
    return false;
  }
  const Eigen::Vector2d along = tangent(a).transpose() * offset;
  const double normal_part = std::sqrt(std::max(0.0, offset.squaredNorm() - along.squaredNorm()));
  return normal_part <= 0.5 * along.norm();
}

void AtlasBuilder::connect_neighbours(int k) {
  const auto ck = center(k);
  const double rk = charts_[k].radius;
  index_.candidates(ck, rk, candidates_);
  Eigen::VectorXd& offset = offset_;
  std::sort(candidates_.begin(), candidates_.end());  // deterministic cut order
  for (int m : candidates_) {
    const double rm = charts_[m].radius;
    offset = center(m) - ck;
    const double distance = offset.norm();
    if (distance >= rk + rm || distance == 0.0) {
      continue;
    }
    if (!same_sheet(k, m, offset) && m != charts_[k].parent) {
      ++sheet_rejections_;
      continue;
    }
    // Power bisector in each chart's own tangent coordinates: |p|² − R_k² ≤ |p − p_m|² − R_m².
    const Eigen::Vector2d pk = tangent(k).transpose() * offset;
    const Eigen::Vector2d pm = tangent(m).transpose() * (-offset);
    if (pk.norm() > 0) {
      charts_[k].polygon.cut(pk(0) / pk.norm(), pk(1) / pk.norm(),
                             (pk.squaredNorm() + rk * rk - rm * rm) / (2.0 * pk.norm()), m);
    }
    if (pm.norm() > 0 &&
        charts_[m].polygon.cut(pm(0) / pm.norm(), pm(1) / pm.norm(),
                               (pm.squaredNorm() + rm * rm - rk * rk) / (2.0 * pm.norm()), k) &&
        !charts_[m].queued && next_open_vertex(m) >= 0) {
      // (Cuts only shrink a polygon; this re-queues a chart whose corner a cut moved, which
      // matters only for charts that were skipped while the queue held them.)
      enqueue(m);
    }
  }
}

bool AtlasBuilder::is_eligible(int c) const {
  // Charts up to domain_margin radii outside S are completed too, so that every chart whose
  // star can reach into S has all its triangles; the outer ones are cut away by the clipping.
  return domain_.is_unbounded() || domain_.boundary_distance(center(c)).signed_distance >=
                                       -options_.domain_margin * charts_[c].radius;
}

int AtlasBuilder::next_open_vertex(int c) const {
  return is_eligible(c) ? charts_[c].polygon.farthest_exterior_vertex(charts_[c].radius) : -1;
}

// Centres that fall near a face of the domain are moved onto M ∩ face (onto M ∩ both faces
// near a corner), so that the atlas carries a row of charts exactly on ∂S and clipping finds
// the boundary already there instead of cutting slivers. A point already taken by a chart
// (a corner reached twice) is left where it was.
void AtlasBuilder::snap_to_domain_boundary(Eigen::VectorXd& y, double radius) {
  if (domain_.is_unbounded() || options_.boundary_snap <= 0) {
    return;
  }
  std::vector<int> faces;
  for (int k = 0; k < static_cast<int>(domain_.half_spaces().size()); ++k) {
    if (std::abs(domain_.signed_distance(k, y)) < options_.boundary_snap * radius) {
      faces.push_back(k);
    }
  }
  if (faces.empty() || static_cast<int>(faces.size()) > 2 ||
      static_cast<int>(faces.size()) + n_ - 2 > n_) {
    return;
  }
  Eigen::VectorXd snapped = y;
  if (!project_onto_faces(problem_, domain_, faces, snapped, options_.boundary_snap * radius * 2,
                          options_.corrector)) {
    return;
  }
  index_.candidates(snapped, 0.1 * radius, candidates_);
  for (int m : candidates_) {
    if ((center(m) - snapped).norm() < 0.2 * radius) {
      return;
    }
  }
  y = snapped;
}

// Where to centre the chart that covers the uncovered polygon vertex v of chart c, in c's
// tangent coordinates.
//  - Disk (Henderson): on the disk boundary towards v. Neighbouring centres end up R to 2R
//    apart, the triangles' circumradii are mostly well below R, all angles near or above 30°.
//  - Hexagonal: towards the packing in which every polygon vertex lies on three disk
//    boundaries (centres √3·R apart). Next to a neighbour a, the new centre is the apex of the
//    isosceles triangle on c–a with sides hexagonal_side·R; in a gap between two neighbours,
//    at v itself; from a chart with no neighbour yet, hexagonal_side·R towards v.
Eigen::Vector2d AtlasBuilder::child_position(int c, int vertex) const {
  const auto& vertices = charts_[c].polygon.vertices();
  const int m = static_cast<int>(vertices.size());
  const auto& v = vertices[vertex];
  const Eigen::Vector2d at(v.s, v.t);
  const double R = charts_[c].radius;
  if (options_.placement == AtlasPlacement::Disk) {
    return R * at.normalized();
  }
  const double side = options_.hexagonal_side * R;
  const int before = vertices[(vertex + m - 1) % m].edge_label;
  const int after = v.edge_label;
  Eigen::Vector2d p;
  if (before >= 0 && after >= 0) {
    p = at;
  } else if (before >= 0 || after >= 0) {
    const int a = before >= 0 ? before : after;
    const Eigen::Vector2d pa = tangent(c).transpose() * (center(a) - center(c));
    const double spacing = pa.norm();
    const Eigen::Vector2d middle = 0.5 * pa;
    Eigen::Vector2d normal = Eigen::Vector2d(-pa(1), pa(0)).normalized();
    if (normal.dot(at - middle) < 0) {
      normal = -normal;
    }
    const double height =
        spacing < 2 * side ? std::sqrt(side * side - 0.25 * spacing * spacing) : 0.0;
    p = middle + height * normal;
  } else {
    p = side * at.normalized();
  }
  // Disks must overlap their parent's (distance < 2R) and the step must make progress.
  const double distance = p.norm();
  if (distance > 1.9 * R) {
    p *= 1.9 * R / distance;
  } else if (distance < 0.5 * R) {
    p = 0.5 * R * at.normalized();
  }
  return p;
}

void AtlasBuilder::enqueue(int c) {
  charts_[c].queued = true;
  open_.push_back(c);
}

void AtlasBuilder::run(const Eigen::VectorXd& start, CoveringSummary& summary) {
  min_radius_ = options_.step * options_.min_radius_fraction;
  {
    Linearization linearization;
    const int first = add_chart(start, -1, linearization);
    if (first < 0) {
      fail(summary, CoveringTermination::StartFailed,
           "no chart can be centred at the start point " + describe_point(start) +
               (first == -1 ? ": DF is singular there"
                            : ": the corrector does not converge even at radius " +
                                  std::to_string(min_radius_)));
      return;
    }
    enqueue(first);
    factored_.emplace(first, std::move(linearization));
  }
  int next_progress = 1000;
  Eigen::VectorXd y(n_);
  while (!open_.empty() && !stopped_) {
    const int c = open_.front();
    open_.pop_front();
    charts_[c].queued = false;
    auto found = factored_.find(c);
    Linearization at_center;
    if (found != factored_.end()) {
      at_center = std::move(found->second);
      factored_.erase(found);
    } else {
      Eigen::MatrixXd T = tangent(c);
      at_center.factor(problem_, center(c), &T);
      // The stored basis stays the chart's frame (its polygon lives in it).
    }
    const Eigen::MatrixXd Tc = tangent(c);
    const Eigen::VectorXd xc = center(c);
    int children = 0;
    Eigen::Vector2d last_target(std::nan(""), std::nan(""));
    double smallest_child = charts_[c].radius;
    for (int vertex = next_open_vertex(c); vertex >= 0 && !stopped_; vertex = next_open_vertex(c)) {
      if (chart_count() >= options_.max_vertices) {
        fail(summary, CoveringTermination::VertexLimit,
             "stopped at " + std::to_string(chart_count()) + " charts (max_vertices)");
        break;
      }
      // A chart next to much smaller ones needs about (R/r)² of them around it.
      if (++children >
          kMaxChildrenPerChart * std::max(1.0, std::pow(charts_[c].radius / smallest_child, 2))) {
        fail(summary, CoveringTermination::ProjectionFailed,
             "the chart at " + describe_point(xc) +
                 " could not be closed: its neighbours do not "
                 "cut away the uncovered corners of its polygon");
        break;
      }
      const auto& v = charts_[c].polygon.vertices()[vertex];
      const Eigen::Vector2d direction = Eigen::Vector2d(v.s, v.t).normalized();
      // If the last child did not remove its corner (snapping moved it away), the next one is
      // placed where the corner asks, unsnapped.
      const bool target_repeated = Eigen::Vector2d(v.s, v.t).isApprox(last_target, 1e-12);
      last_target = Eigen::Vector2d(v.s, v.t);
      // The new centre goes on the disk boundary towards the uncovered corner (pointOnDisk:
      // projected orthogonally to this chart's tangent plane). Where that fails, or lands on a
      // singular point, nearer and farther points are tried.
      int child = -1;
      Linearization at_child = take_spare();
      // A corner the last child did not remove gets Henderson's placement, which always does.
      const Eigen::Vector2d target =
          target_repeated ? charts_[c].radius * direction : child_position(c, vertex);
      for (double fraction : {1.0, 0.85, 1.1, 0.7, 0.5, 0.35, 0.25}) {
        const Eigen::Vector2d s = fraction * target;
        y = xc + Tc * s;
        if (!project(at_center, s.norm(), y)) {
          continue;
        }
        if (watch_crossings_) {
          evaluate_jacobian(y);  // also used by add_chart for the new chart's orientation
        }
        if (watch_crossings_ && charts_[c].orientation != 0) {
          // Never centre a chart at or next to a singular point: its chord iteration would
          // not converge beyond a tiny radius. σ_min falling tenfold in one step means one.
          if (jacobian_scale() < 0.1 * charts_[c].jacobian_scale) {
            continue;
          }
          const signed char across = orientation_sign(Tc);
          if (across == 0) {
            continue;
          }
          if (across != charts_[c].orientation) {
            ++singular_crossings_;
            if (first_crossing_.empty()) {
              first_crossing_ = describe_point(0.5 * (xc + y));
            }
          }
        }
        if (!target_repeated) {
          snap_to_domain_boundary(y, charts_[c].radius);
        }
        child = add_chart(y, c, at_child);
        if (child >= 0) {
          break;
        }
      }
      if (child < 0) {
        fail(summary, CoveringTermination::ProjectionFailed,
             "no chart could be centred beyond " + describe_point(xc) +
                 " in the direction of its uncovered corner: the corrector does not converge "
                 "or DF is singular there");
        break;
      }
      smallest_child = std::min(smallest_child, charts_[child].radius);
      enqueue(child);
      factored_.emplace(child, std::move(at_child));
    }
    spare_.push_back(std::move(at_center));
    if (options_.progress && chart_count() >= next_progress) {
      next_progress = chart_count() + 1000;
      options_.progress({chart_count(), 0, static_cast<int>(open_.size())});
    }
  }
  summary.charts = chart_count();
  summary.singular_crossings = singular_crossings_;
  summary.sheet_rejections = sheet_rejections_;
  if (singular_crossings_ > 0) {
    summary.notes.push_back("met a singular crossing of M (first near " + first_crossing_ +
                            "): the atlas continued along the sheet it was on, " +
                            std::to_string(sheet_rejections_) +
                            " overlaps with charts of other sheets were kept apart");
  }
}

}  // namespace tessera::detail
