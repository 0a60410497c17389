// SPDX-License-Identifier: MIT
#include "tessera/methods/common/triangle_samples.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <unordered_set>

#include "tessera/core/face_projection.h"
#include "tessera/core/parallel_for.h"

namespace tessera::detail {

std::uint64_t unordered_edge_key(int a, int b) {
  if (a > b) {
    std::swap(a, b);
  }
  return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(a)) << 32) |
         static_cast<std::uint32_t>(b);
}

std::vector<int> shared_faces(const Eigen::Ref<const Eigen::VectorXd>& distance_a,
                              const Eigen::Ref<const Eigen::VectorXd>& distance_b,
                              double tolerance) {
  std::vector<int> faces;
  for (int k = 0; k < static_cast<int>(distance_a.size()); ++k) {
    if (std::abs(distance_a(k)) <= tolerance && std::abs(distance_b(k)) <= tolerance) {
      faces.push_back(k);
    }
  }
  return faces;
}

std::vector<int> corner_faces(const Eigen::Ref<const Eigen::VectorXd>& distance_a,
                              const Eigen::Ref<const Eigen::VectorXd>& distance_b,
                              double tolerance) {
  std::vector<int> on_a, on_b;
  for (int k = 0; k < static_cast<int>(distance_a.size()); ++k) {
    if (std::abs(distance_a(k)) <= tolerance) {
      on_a.push_back(k);
    }
    if (std::abs(distance_b(k)) <= tolerance) {
      on_b.push_back(k);
    }
  }
  if (on_a.size() == 1 && on_b.size() == 1 && on_a[0] != on_b[0]) {
    return {on_a[0], on_b[0]};
  }
  return {};
}

void SampleState::freeze_at(const ImplicitProblem& problem, const TriangleMesh& mesh, int v,
                            double edge_length) {
  if (v == frozen_at) {
    return;
  }
  Linearization next;
  if (lenders.borrow(problem, mesh.point(v), edge_length, next)) {
    frozen = std::move(next);
    frozen_ok = true;
    frozen_at = v;
    return;
  }
  freeze_own_at(problem, mesh, v);
}

void SampleState::freeze_own_at(const ImplicitProblem& problem, const TriangleMesh& mesh, int v) {
  frozen_at = v;
  if (!problem.has_sparse_jacobian() || sharing != 1) {  // not (yet) shared: in place
    frozen_ok = frozen.factor(problem, mesh.point(v));
    if (frozen_ok && sharing < 0 && problem.has_sparse_jacobian()) {
      sharing = worth_sharing(frozen) ? 1 : 0;
      if (sharing == 1) {
        lenders.keep(problem, std::move(frozen), frozen);
      }
    }
    return;
  }
  Linearization own;
  frozen_ok = own.factor(problem, mesh.point(v));
  if (frozen_ok) {
    lenders.keep(problem, std::move(own), frozen);
  }
}

bool project_patiently(const ImplicitProblem& problem, Eigen::VectorXd& x,
                       const SampleSettings& settings, Linearization& workspace) {
  // (Only points come out of these projections, not their workspace: Gauss–Newton may keep its
  // factorisation while it contracts, on sparse problems.)
  const Eigen::VectorXd start = x;
  if (project_gauss_newton(problem, x, settings.gauss_newton, workspace).is_success()) {
    return true;
  }
  x = start;
  return project_gauss_newton(problem, x, settings.patient, workspace).is_success();
}

TriangleSampler::TriangleSampler(const ImplicitProblem& problem, const Domain& domain,
                                 const TriangleMesh& mesh, const SampleSettings& settings,
                                 SampleState& shared, std::function<bool()> is_stop_requested)
    : problem_(problem),
      domain_(domain),
      mesh_(mesh),
      settings_(settings),
      shared_(shared),
      is_stop_requested_(std::move(is_stop_requested)) {}

bool TriangleSampler::has_circumcentre(const Gram& g, double& beta, double& gamma) const {
  const double uu = g[0], ww = g[1], uw = g[2];
  const double det = 2.0 * (uu * ww - uw * uw);
  if (!(det > 0)) {
    return false;
  }
  beta = ww * (uu - uw) / det;
  gamma = uu * (ww - uw) / det;
  return beta >= 0 && gamma >= 0 && beta + gamma <= 1;
}

// Where the anchor's chord does not contract at a point: a corner of the triangle (one already
// factored if any, the last few are kept, else its first), and last a patient Gauss–Newton
// projection.
double TriangleSampler::distance_without_anchor(const Eigen::VectorXd& point, const Triangle& tri,
                                                SampleState& state) const {
  if (state.frozen_at != tri[0] && state.frozen_at != tri[1] && state.frozen_at != tri[2]) {
    const Linearization* corner = nullptr;
    bool is_cached = false;
    for (int v : tri) {
      if (const Linearization* factored = state.corners.find(v)) {
        corner = factored->is_factored() ? factored : nullptr;
        is_cached = true;
        break;
      }
    }
    if (!is_cached) {
      corner = state.corners.factor(tri[0], problem_, mesh_.point(tri[0]));
    }
    const double bound = corner != nullptr
                             ? chord_distance_bound(problem_, *corner, point, settings_.accuracy,
                                                    settings_.chord, settings_.clear_below)
                             : std::numeric_limits<double>::infinity();
    if (std::isfinite(bound)) {
      return bound;
    }
  }
  Eigen::VectorXd x = point;
  if (!project_patiently(problem_, x, settings_, state.workspace)) {
    return std::numeric_limits<double>::infinity();
  }
  return mesh_.space().distance(x, point);
}

// Boundary edges on ∂S: the mesh ends at the chord, M ∩ S at the curve M ∩ face, which bulges
// beyond the chord within M by its geodesic curvature·L²/8, a part of M ∩ S that no triangle
// covers and no sample of a triangle sees (on cstr's face Da = 0.3, 0.012 at a tolerance of
// 0.008). So each boundary edge on a face also samples the gap: the distance from its midpoint
// to M ∩ face, where its split would put the new vertex (0 for an edge on no face).
double TriangleSampler::gap(int u, int v, SampleState& state) const {
  const AmbientSpace& space = mesh_.space();
  const std::vector<int> ends = {u, v};
  const Eigen::MatrixXd distance = domain_.signed_distances(mesh_.points(), ends);
  std::vector<int> faces = shared_faces(distance.col(0), distance.col(1), settings_.face_tolerance);
  if (faces.empty()) {
    faces = corner_faces(distance.col(0), distance.col(1), settings_.face_tolerance);
  }
  if (faces.empty() || faces.size() > 2) {
    return 0.0;
  }
  const Eigen::VectorXd midpoint = 0.5 * (mesh_.point(u) + mesh_.point(v));
  Eigen::VectorXd x = midpoint;
  const double length = space.distance(mesh_.point(u), mesh_.point(v));
  // A midpoint that cannot be put on M ∩ face is left to the triangle samples (its edge is then
  // unsplittable anyway). The chord from the triangle's anchor first: at large n no
  // factorisation at all.
  if (project_onto_faces(problem_, domain_, faces, x, length, settings_.gauss_newton, nullptr,
                         state.frozen_ok ? &state.frozen : nullptr)) {
    return space.distance(x, midpoint);
  }
  return 0.0;
}

// The samples: the centroid, the midpoints it measures for both its triangles and, on a surface
// of constant curvature the farthest point, the circumcentre (when it lies inside the
// triangle), which makes the estimate nearly exact. All are measured from the anchor in
// lockstep (one multi-column solve per chord step); those where its chord does not contract,
// another way.
void TriangleSampler::measure(int anchor, int t, Claims claims, const std::vector<Gram>& gram,
                              SampleState& state, Measured& out) const {
  const Triangle tri = mesh_.triangle(t);
  const Eigen::VectorXd a = mesh_.point(tri[0]);
  const Eigen::VectorXd b = mesh_.point(tri[1]);
  const Eigen::VectorXd c = mesh_.point(tri[2]);
  // The triangle's longest edge is the local edge length for a borrowed factorisation.
  const Gram& g = gram[static_cast<std::size_t>(t)];
  state.freeze_at(problem_, mesh_, anchor, std::sqrt(std::max({g[0], g[1], g[3]})));
  Eigen::MatrixXd samples(a.size(), 5);
  Eigen::Index count = 0;
  samples.col(count++) = (a + b + c) / 3.0;
  for (int e = 0; e < 3; ++e) {
    if (claims.midpoints & (1u << e)) {
      samples.col(count++) = 0.5 * (mesh_.point(tri[e]) + mesh_.point(tri[(e + 1) % 3]));
    }
  }
  double beta = 0.0, gamma = 0.0;
  out.has_circumcentre = has_circumcentre(gram[static_cast<std::size_t>(t)], beta, gamma);
  if (out.has_circumcentre) {
    const Eigen::VectorXd ab = b - a;
    const Eigen::VectorXd ac = c - a;
    samples.col(count++) = a + beta * ab + gamma * ac;
  }
  const auto points = samples.leftCols(count);
  const auto from_anchor = [&] {
    return state.frozen_ok ? chord_distance_bounds(problem_, state.frozen, points,
                                                   settings_.accuracy, settings_.chord,
                                                   settings_.clear_below)
                           : std::vector<double>(static_cast<std::size_t>(count),
                                                 std::numeric_limits<double>::infinity());
  };
  std::vector<double> distance = from_anchor();
  // A borrowed factorisation is farther from the samples than the anchor's own: where its
  // chord does not contract, the anchor factors its own (once, for the rest of its group), as
  // it did before borrowing, and not every corner or Gauss–Newton step on its own.
  if (state.frozen_ok && state.frozen.solves_from_elsewhere() &&
      std::any_of(distance.begin(), distance.end(), [](double d) { return !std::isfinite(d); })) {
    state.freeze_own_at(problem_, mesh_, anchor);
    distance = from_anchor();
  }
  out.count = static_cast<int>(count);
  for (Eigen::Index j = 0; j < count; ++j) {
    double d = distance[static_cast<std::size_t>(j)];
    if (!std::isfinite(d)) {
      d = distance_without_anchor(points.col(j), tri, state);
    }
    out.distance[static_cast<std::size_t>(j)] = d;
  }
  for (int e = 0; e < 3; ++e) {
    if (claims.gaps & (1u << e)) {
      out.gap[static_cast<std::size_t>(e)] = gap(tri[e], tri[(e + 1) % 3], state);
    }
  }
}

PassSamples TriangleSampler::sample(const std::vector<std::pair<int, int>>& pairs,
                                    const std::vector<Gram>& gram,
                                    const std::unordered_map<std::uint64_t, int>& triangles_at_edge,
                                    bool may_stop) {
  const int count = static_cast<int>(pairs.size());
  PassSamples found;
  // Phase 0, in order: which triangle measures each midpoint not measured before (the first of
  // the pass that has it, as a serial pass would) and each boundary edge's gap (its one
  // triangle).
  std::vector<Claims> claims(pairs.size());
  std::unordered_set<std::uint64_t> claimed;
  // Reserved: growing these by rehashing was a third of the serial phases at 10⁶ vertices.
  claimed.reserve(2 * pairs.size());
  midpoint_distance_.reserve(midpoint_distance_.size() + 2 * pairs.size());
  for (int k = 0; k < count; ++k) {
    const Triangle& tri = mesh_.triangle(pairs[static_cast<std::size_t>(k)].second);
    Claims& claim = claims[static_cast<std::size_t>(k)];
    for (int e = 0; e < 3; ++e) {
      const std::uint64_t key = unordered_edge_key(tri[e], tri[(e + 1) % 3]);
      if (!midpoint_distance_.contains(key) && claimed.insert(key).second) {
        claim.midpoints |= static_cast<std::uint8_t>(1u << e);
      }
      const auto uses = triangles_at_edge.find(key);
      if (uses != triangles_at_edge.end() && uses->second == 1 && !boundary_gap_.contains(key)) {
        claim.gaps |= static_cast<std::uint8_t>(1u << e);
      }
    }
  }
  // Phase 1: the measurements. A sparse problem's in order on this thread with the shared
  // state (one task); a dense problem's by anchor group, each group with a state of its own,
  // on threads. The groups, not the threads, decide what shares a factorisation, so the
  // distances are the same whatever the thread count.
  const bool is_sparse = problem_.has_sparse_jacobian();
  std::vector<int> task_start{0};
  for (int k = 1; k < count && !is_sparse; ++k) {
    if (pairs[static_cast<std::size_t>(k)].first != pairs[static_cast<std::size_t>(k - 1)].first) {
      task_start.push_back(k);
    }
  }
  task_start.push_back(count);
  const int tasks = static_cast<int>(task_start.size()) - 1;
  const int threads = threads_for(problem_);
  (void)mesh_.space();  // made on first use, which is not thread-safe
  std::vector<Measured> measured(pairs.size());
  const auto run_task = [&](int task) {
    SampleState own;
    SampleState& state = is_sparse ? shared_ : own;
    for (int k = task_start[static_cast<std::size_t>(task)];
         k < task_start[static_cast<std::size_t>(task) + 1]; ++k) {
      // On one thread, a stop request is polled before every triangle (at large n the samples
      // are minutes of chord steps); never on another thread (it may be a collective call).
      if (may_stop && threads == 1 && is_stop_requested_()) {
        found.interrupted = true;
        return;
      }
      const auto [anchor, t] = pairs[static_cast<std::size_t>(k)];
      measure(anchor, t, claims[static_cast<std::size_t>(k)], gram, state,
              measured[static_cast<std::size_t>(k)]);
    }
  };
  // On several threads the stop request is polled before every block of groups: 1024 groups
  // a thread, some 30 ms at n = 3. Each block ends at a barrier, where a thread that the
  // machine's other work has descheduled holds all up for a time slice: small blocks made two
  // threads slower than one on a loaded machine (bench/RESULTS.md, "Threads").
  const int tasks_per_poll = 1024 * threads;
  for (int first = 0; first < tasks && !found.interrupted; first += tasks_per_poll) {
    if (may_stop && threads > 1 && is_stop_requested_()) {
      found.interrupted = true;
      break;
    }
    const int size = std::min(tasks_per_poll, tasks - first);
    parallel_for(size, threads, [&](int i) {
      if (!found.interrupted) {
        run_task(first + i);
      }
    });
  }
  if (found.interrupted) {
    return found;
  }
  // Phase 2, in order: what the triangles measured for the others, then each one judged.
  for (int k = 0; k < count; ++k) {
    const Triangle& tri = mesh_.triangle(pairs[static_cast<std::size_t>(k)].second);
    const Measured& m = measured[static_cast<std::size_t>(k)];
    int column = 1;
    for (int e = 0; e < 3; ++e) {
      const std::uint64_t key = unordered_edge_key(tri[e], tri[(e + 1) % 3]);
      if (claims[static_cast<std::size_t>(k)].midpoints & (1u << e)) {
        midpoint_distance_.emplace(key, m.distance[static_cast<std::size_t>(column++)]);
      }
      if (claims[static_cast<std::size_t>(k)].gaps & (1u << e)) {
        boundary_gap_.emplace(key, m.gap[static_cast<std::size_t>(e)]);
      }
    }
  }
  found.worst.resize(pairs.size());
  found.worst_edge.resize(pairs.size());
  found.worst_sample.resize(pairs.size());
  // Each triangle judged on its own (the maps are only read now): on threads.
  parallel_for(count, thread_count(), [&](int k) {
    const Triangle& tri = mesh_.triangle(pairs[static_cast<std::size_t>(k)].second);
    const Measured& m = measured[static_cast<std::size_t>(k)];
    // The worst sample, the first of equals in the order centroid, midpoints, circumcentre.
    double worst = -1.0;
    int worst_sample = -1;
    const auto consider = [&](int which, double d) {
      if (!(d <= worst)) {
        worst = d;
        worst_sample = which;
      }
    };
    consider(0, m.distance[0]);
    std::array<double, 3> at_midpoint{};
    for (int e = 0; e < 3; ++e) {
      at_midpoint[static_cast<std::size_t>(e)] =
          midpoint_distance_.at(unordered_edge_key(tri[e], tri[(e + 1) % 3]));
      consider(1 + e, at_midpoint[static_cast<std::size_t>(e)]);
    }
    // Between the samples: a flat triangle's distance to M vanishes at its corners and is, to
    // leading order, quadratic in the barycentric coordinates λ (exactly so on a sphere), so
    // the midpoints' distances a_e fix 4·Σ λ_i λ_j a_ij and the centroid's a cubic bubble
    // b·λ₀λ₁λ₂ on top. Its largest value on a grid of the triangle (arithmetic only) bounds
    // the distance where the samples miss it: beside the longest edge of an obtuse triangle
    // where M's curvature varies (bezier's triangles were up to 1.3 % beyond the tolerance
    // between these samples).
    if (std::isfinite(m.distance[0]) && std::isfinite(at_midpoint[0]) &&
        std::isfinite(at_midpoint[1]) && std::isfinite(at_midpoint[2])) {
      const auto quadratic = [&](double l0, double l1, double l2) {
        return 4.0 *
               (l0 * l1 * at_midpoint[0] + l1 * l2 * at_midpoint[1] + l2 * l0 * at_midpoint[2]);
      };
      const double bubble = 27.0 * (m.distance[0] - quadratic(1.0 / 3, 1.0 / 3, 1.0 / 3));
      constexpr int kGrid = 8;
      double model = -1.0;
      for (int i = 1; i < kGrid; ++i) {
        for (int j = 1; i + j < kGrid; ++j) {
          const double l0 = static_cast<double>(i) / kGrid;
          const double l1 = static_cast<double>(j) / kGrid;
          const double l2 = 1.0 - l0 - l1;
          model = std::max(model, quadratic(l0, l1, l2) + bubble * l0 * l1 * l2);
        }
      }
      consider(5, model);
    }
    if (m.has_circumcentre) {
      consider(4, m.distance[static_cast<std::size_t>(m.count - 1)]);
    }
    int worst_edge = -1;
    for (int e = 0; e < 3 && !triangles_at_edge.empty(); ++e) {
      const std::uint64_t key = unordered_edge_key(tri[e], tri[(e + 1) % 3]);
      const auto uses = triangles_at_edge.find(key);
      if (uses != triangles_at_edge.end() && uses->second == 1) {
        const double gap = boundary_gap_.at(key);
        if (gap > worst) {
          worst = gap;
          worst_sample = 1 + e;
          worst_edge = e;
        }
      }
    }
    found.worst[static_cast<std::size_t>(k)] = worst;
    found.worst_edge[static_cast<std::size_t>(k)] = worst_edge;
    found.worst_sample[static_cast<std::size_t>(k)] = worst_sample;
  });
  return found;
}

Eigen::VectorXd TriangleSampler::sample_point(int t, int worst_sample,
                                              const std::vector<Gram>& gram) const {
  const Triangle& tri = mesh_.triangle(t);
  const Eigen::VectorXd a = mesh_.point(tri[0]);
  const Eigen::VectorXd b = mesh_.point(tri[1]);
  const Eigen::VectorXd c = mesh_.point(tri[2]);
  double beta = 0.0, gamma = 0.0;
  if (worst_sample == 4 && has_circumcentre(gram[static_cast<std::size_t>(t)], beta, gamma)) {
    const Eigen::VectorXd ab = b - a;
    const Eigen::VectorXd ac = c - a;
    return a + beta * ab + gamma * ac;
  }
  if (worst_sample >= 1 && worst_sample <= 3) {
    const int e = worst_sample - 1;
    return 0.5 * (mesh_.point(tri[e]) + mesh_.point(tri[(e + 1) % 3]));
  }
  return (a + b + c) / 3.0;  // the centroid, and the model's
}

}  // namespace tessera::detail
