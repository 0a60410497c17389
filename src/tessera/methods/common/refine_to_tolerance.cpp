// SPDX-License-Identifier: MIT
#include "tessera/methods/common/refine_to_tolerance.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <unordered_map>
#include <unordered_set>

#include "tessera/core/error.h"
#include "tessera/core/face_projection.h"
#include "tessera/core/linearization.h"
#include "tessera/geometry/mesh_quality.h"
#include "tessera/geometry/spatial_order.h"
#include "tessera/methods/common/clip_to_domain.h"
#include "tessera/methods/common/triangle_samples.h"

namespace tessera {
namespace {

using detail::corner_faces;
using detail::Gram;
using detail::shared_faces;
using detail::unordered_edge_key;

// Sampled distances are measured to this fraction of the refinement threshold: enough to
// decide "split or not", and a bound from above, so the decision errs towards splitting.
constexpr double kDistanceAccuracy = 0.02;
// A sample whose two-step bound (chord_distance_bound) is below this fraction of the threshold
// passes without a third step: most samples of a mesh sized for the tolerance lie well inside.
constexpr double kClearPass = 0.75;

// Squared distances between pairs of mesh vertices, measured in one pass: each rank's partial
// sums, then one reduction for all (in one process, (q − p).squaredNorm() as before, whose root
// is (q − p).norm() to the bit).
class PairLengths {
 public:
  int add(int p, int q) {
    pairs_.emplace_back(p, q);
    return static_cast<int>(pairs_.size()) - 1;
  }
  void measure(const TriangleMesh& mesh) {
    squared_.resize(pairs_.size());
    for (std::size_t i = 0; i < pairs_.size(); ++i) {
      squared_[i] = (mesh.point(pairs_[i].second) - mesh.point(pairs_[i].first)).squaredNorm();
    }
    if (!squared_.empty()) {
      mesh.space().sum(squared_.data(), static_cast<int>(squared_.size()));
    }
  }
  double length(int i) const { return std::sqrt(squared_[static_cast<std::size_t>(i)]); }
  /// The smallest angle of the triangle whose sides are the pairs i, j, k (min_angle).
  double min_angle(int i, int j, int k) const {
    return min_angle_of_sides(length(i), length(j), length(k));
  }

 private:
  std::vector<std::pair<int, int>> pairs_;
  std::vector<double> squared_;
};

// The Gram numbers of the triangles `which`, summed over the ranks at once, in `gram` (indexed by
// triangle). In one process the expressions the samples used before, to the bit.
void measure_gram(const TriangleMesh& mesh, const std::vector<int>& which,
                  std::vector<Gram>& gram) {
  gram.assign(static_cast<std::size_t>(mesh.triangle_count()), Gram{});
  std::vector<double> values(4 * which.size());
  for (std::size_t i = 0; i < which.size(); ++i) {
    const Triangle& tri = mesh.triangle(which[i]);
    const Eigen::VectorXd ab = mesh.point(tri[1]) - mesh.point(tri[0]);
    const Eigen::VectorXd ac = mesh.point(tri[2]) - mesh.point(tri[0]);
    values[4 * i] = ab.squaredNorm();
    values[4 * i + 1] = ac.squaredNorm();
    values[4 * i + 2] = ab.dot(ac);
    values[4 * i + 3] = (mesh.point(tri[1]) - mesh.point(tri[2])).squaredNorm();
  }
  if (!values.empty()) {
    mesh.space().sum(values.data(), static_cast<int>(values.size()));
  }
  for (std::size_t i = 0; i < which.size(); ++i) {
    gram[static_cast<std::size_t>(which[i])] = {values[4 * i], values[4 * i + 1], values[4 * i + 2],
                                                values[4 * i + 3]};
  }
}

// The triangles `candidates` in an order that lets few factorisations serve them all: each is
// paired with an anchor and the pairs are sorted by anchor. The anchors are chosen greedily
// (of an unanchored triangle's vertices, the one with the most unanchored triangles around it),
// and an anchor serves the triangles that touch it or one of its neighbours (`rings` = 2), or
// only those that touch it (`rings` = 1): about one vertex in ten, or in three, is an anchor
// instead of one factorisation per triangle. `along_M(first anchor)`: whether the anchors come
// along a Hilbert curve through M (spatially_ordered) instead of by index: for a sparse
// problem's samples, which run in this order with one state, where factorisations are worth
// sharing (an anchor borrows the nearest kept one, SampleState::freeze_at): in index order most
// anchors lay more than four edges from the last (bratu2d:N=32: 446 of 629), and nearly every
// anchor factored.
std::vector<std::pair<int, int>> anchored(const TriangleMesh& mesh,
                                          const std::vector<int>& candidates, int rings,
                                          const std::function<bool(int)>& along_M) {
  const int V = mesh.vertex_count();
  std::vector<int> start(V + 1, 0);  // candidates around each vertex, compressed rows
  for (int t : candidates) {
    for (int v : mesh.triangle(t)) {
      ++start[v + 1];
    }
  }
  for (int v = 0; v < V; ++v) {
    start[v + 1] += start[v];
  }
  std::vector<int> around(start[V]);
  std::vector<int> fill(start.begin(), start.end() - 1);
  for (int k = 0; k < static_cast<int>(candidates.size()); ++k) {
    for (int v : mesh.triangle(candidates[k])) {
      around[fill[v]++] = k;
    }
  }
  std::vector<int> open_around(V);
  for (int v = 0; v < V; ++v) {
    open_around[v] = start[v + 1] - start[v];
  }
  std::vector<int> anchor(candidates.size(), -1);
  for (std::size_t k = 0; k < candidates.size(); ++k) {
    if (anchor[k] >= 0) {
      continue;
    }
    const Triangle& tri = mesh.triangle(candidates[k]);
    int best = tri[0];
    for (int v : tri) {
      if (open_around[v] > open_around[best]) {
        best = v;
      }
    }
    const auto serve_around = [&](int w) {
      for (int i = start[w]; i < start[w + 1]; ++i) {
        const int j = around[i];
        if (anchor[j] < 0) {
          anchor[j] = best;
          for (int v : mesh.triangle(candidates[j])) {
            --open_around[v];
          }
        }
      }
    };
    if (rings == 1) {
      serve_around(best);
      continue;
    }
    // The neighbours are collected first: serving changes the counts, not the adjacency.
    std::vector<int> neighbours{best};
    for (int i = start[best]; i < start[best + 1]; ++i) {
      for (int v : mesh.triangle(candidates[around[i]])) {
        neighbours.push_back(v);
      }
    }
    for (int w : neighbours) {
      serve_around(w);
    }
  }
  std::vector<std::pair<int, int>> pairs;
  pairs.reserve(candidates.size());
  for (std::size_t k = 0; k < candidates.size(); ++k) {
    pairs.emplace_back(anchor[k], candidates[k]);
  }
  std::sort(pairs.begin(), pairs.end());
  if (!pairs.empty() && along_M(pairs.front().first)) {
    std::vector<int> anchors;
    for (const auto& [a, t] : pairs) {
      if (anchors.empty() || anchors.back() != a) {
        anchors.push_back(a);
      }
    }
    std::vector<int> rank(static_cast<std::size_t>(V), 0);
    const std::vector<int> ordered = spatially_ordered(mesh, std::move(anchors));
    for (std::size_t k = 0; k < ordered.size(); ++k) {
      rank[static_cast<std::size_t>(ordered[k])] = static_cast<int>(k);
    }
    std::sort(pairs.begin(), pairs.end(), [&rank](const auto& p, const auto& q) {
      const int rp = rank[static_cast<std::size_t>(p.first)];
      const int rq = rank[static_cast<std::size_t>(q.first)];
      return rp != rq ? rp < rq : p.second < q.second;
    });
  }
  return pairs;
}

}  // namespace

ToleranceRefinement refine_to_tolerance(const ImplicitProblem& problem, const Domain& domain,
                                        TriangleMesh& mesh, std::vector<int> candidates,
                                        const ToleranceRefinementOptions& options) {
  ToleranceRefinement summary;
  check_mesh_of_problem(mesh, problem, "refine_to_tolerance");
  TESSERA_CHECK(domain.is_unbounded() || domain.ambient_dimension() == mesh.ambient_dimension(),
                "refine_to_tolerance: the domain's normals have "
                    << domain.ambient_dimension() << " rows, the mesh's points "
                    << mesh.ambient_dimension() << " (a split mesh needs Domain::distributed)");
  // A split mesh (each rank its rows of every vertex) measures through its space: every
  // decision below is taken on sums over the ranks, the same on every rank. In one process
  // these are Eigen's own expressions.
  const AmbientSpace& space = mesh.space();
  if (candidates.empty()) {
    for (int t = 0; t < mesh.triangle_count(); ++t) {
      candidates.push_back(t);
    }
  }
  // The samples of a triangle are projected with the chord iteration frozen at one of its
  // vertices, its anchor, which serves all triangles around it (a factorisation for every
  // third vertex or so, instead of several per Gauss–Newton projection: for sparse problems
  // factorisations are the cost). The chord lands on M, so its displacement bounds the
  // distance from above: the estimate errs towards splitting. It is only needed to a small
  // fraction of the threshold, which two or three chord steps give (chord_distance_bound).
  detail::SampleSettings settings;
  settings.threshold = options.tolerance * options.sample_safety;
  settings.accuracy = kDistanceAccuracy * settings.threshold;
  settings.clear_below = kClearPass * settings.threshold;
  settings.face_tolerance = options.face_tolerance;
  settings.chord = options.corrector;
  // Gauss–Newton, and where it contracts too slowly for the method's corrector (θ above its
  // max_contraction, typically 1/2), once more with θ up to 0.9, as the report measures: a
  // midpoint far from a strongly curved M (cstr, an edge 0.2 long) is often first overshot,
  // and a midpoint that can be neither measured nor projected leaves its triangle unrefined.
  settings.gauss_newton = options.corrector;
  settings.gauss_newton.reuse_factorisation = true;
  settings.patient = settings.gauss_newton;
  settings.patient.max_contraction = std::max(settings.patient.max_contraction, 0.9);
  settings.patient.max_iterations = std::max(settings.patient.max_iterations, 50);
  const double threshold = settings.threshold;
  const bool is_sparse = problem.has_sparse_jacobian();
  // Sparse problems anchor across two rings (fewer factorisations); the bisection's projections
  // share their samples' factorisations (detail::SampleState).
  const int rings = is_sparse ? 2 : 1;
  detail::SampleState shared;
  // Each rank's stop request is its own: the ranks stop together if any asks.
  const auto is_stop_requested = [&] {
    if (!options.stop_requested) {
      return false;
    }
    const bool stop = options.stop_requested();
    return space.is_distributed() ? space.maximum(stop ? 1.0 : 0.0) > 0.0 : stop;
  };
  detail::TriangleSampler sampler(problem, domain, mesh, settings, shared, is_stop_requested);
  // Whether the anchors go along M: known from the first factorisation (made at the first
  // anchor, which the samples would factor first anyway).
  const auto along_M = [&](int first_anchor) {
    if (is_sparse && shared.sharing < 0) {
      shared.freeze_own_at(problem, mesh, first_anchor);
    }
    return is_sparse && shared.sharing == 1;
  };
  std::vector<Gram> gram;
  // Boundary edges (for the gaps beyond ∂S, detail::TriangleSampler): each edge's triangles,
  // rebuilt each round; none for an unbounded domain.
  std::unordered_map<std::uint64_t, int> triangles_at_edge;
  const auto count_edges = [&] {
    triangles_at_edge.clear();
    if (domain.is_unbounded()) {
      return;
    }
    for (const Triangle& tri : mesh.triangles()) {
      for (int e = 0; e < 3; ++e) {
        ++triangles_at_edge[unordered_edge_key(tri[e], tri[(e + 1) % 3])];
      }
    }
  };
  // Edges whose midpoint could not be projected: not tried again in later rounds (their
  // triangles stay candidates and end as remaining unless a neighbour's split reaches them).
  std::unordered_set<std::uint64_t> unsplittable;
  bool exhausted = true;  // false once a round finds nothing to split
  for (summary.rounds = 0; summary.rounds < options.max_rounds && !candidates.empty();
       ++summary.rounds) {
    // 1. Which edges to split: the longest edge of every candidate that is too far from M.
    std::unordered_map<std::uint64_t, int> midpoint_of;  // edge → new vertex
    // The edges to split, each with its length.
    std::vector<std::pair<std::pair<int, int>, double>> to_split;
    std::vector<std::uint8_t> is_far(mesh.triangle_count(), 0);
    count_edges();
    measure_gram(mesh, candidates, gram);
    const std::vector<std::pair<int, int>> pairs = anchored(mesh, candidates, rings, along_M);
    // A stop request is polled only here, where nothing of the round has changed the mesh
    // yet: at large n the samples are minutes of chord steps, and a stopped run wants its mesh
    // now.
    const detail::PassSamples pass = sampler.sample(pairs, gram, triangles_at_edge, true);
    if (pass.interrupted) {
      summary.interrupted = true;
      return summary;
    }
    for (std::size_t k = 0; k < pairs.size(); ++k) {
      const int t = pairs[k].second;
      const Triangle tri = mesh.triangle(t);
      const double worst = pass.worst[k];
      if (worst <= threshold) {
        summary.max_distance = std::max(summary.max_distance, worst);
        summary.max_distance_within = std::max(summary.max_distance_within, worst);
        continue;
      }
      is_far[t] = 1;
      int longest = 0;
      double length = -1.0;
      const Gram& g = gram[static_cast<std::size_t>(t)];
      const std::array<double, 3> squared = {g[0], g[3], g[1]};  // edges ab, bc, ca
      for (int e = 0; e < 3; ++e) {
        const double l = std::sqrt(squared[static_cast<std::size_t>(e)]);
        if (l > length) {
          length = l;
          longest = e;
        }
      }
      if (pass.worst_edge[k] >= 0) {
        longest = pass.worst_edge[k];  // the gap beyond a boundary edge: that edge is split
      }
      const int u = tri[longest];
      const int v = tri[(longest + 1) % 3];
      if (!unsplittable.contains(unordered_edge_key(u, v)) &&
          midpoint_of.emplace(unordered_edge_key(u, v), -1).second) {
        to_split.push_back({{u, v}, length});
      }
    }
    if (summary.interrupted) {
      return summary;
    }
    if (to_split.empty()) {
      // Nothing left to split: done if no candidate is too far, otherwise the far ones (whose
      // edges cannot be split) are measured once more below and counted as remaining.
      candidates.clear();
      for (int t = 0; t < mesh.triangle_count(); ++t) {
        if (is_far[t]) {
          candidates.push_back(t);
        }
      }
      exhausted = !candidates.empty();
      break;
    }
    // 2. The new vertices: midpoints projected onto M (∩ the faces the edge lies on).
    std::sort(to_split.begin(), to_split.end());
    // The endpoints' distances to the faces, all at once.
    std::vector<int> endpoints;
    endpoints.reserve(2 * to_split.size());
    for (const auto& [edge, length] : to_split) {
      endpoints.push_back(edge.first);
      endpoints.push_back(edge.second);
    }
    const Eigen::MatrixXd face_distance = domain.signed_distances(mesh.points(), endpoints);
    int made = 0;
    for (std::size_t i = 0; i < to_split.size(); ++i) {
      const auto [u, v] = to_split[i].first;
      const double length = to_split[i].second;
      const Eigen::VectorXd a = mesh.point(u);
      const Eigen::VectorXd b = mesh.point(v);
      Eigen::VectorXd x = 0.5 * (a + b);
      const auto column = static_cast<Eigen::Index>(2 * i);
      std::vector<int> faces = shared_faces(face_distance.col(column),
                                            face_distance.col(column + 1), options.face_tolerance);
      const auto uses = triangles_at_edge.find(unordered_edge_key(u, v));
      if (faces.empty() && uses != triangles_at_edge.end() && uses->second == 1) {
        // A boundary edge across a corner of S: split at the corner point M ∩ a ∩ b.
        faces = corner_faces(face_distance.col(column), face_distance.col(column + 1),
                             options.face_tolerance);
      }
      bool projected = false;
      if (faces.empty()) {
        // Sparse problems: the chord frozen at an endpoint first (the pairs are sorted, so one
        // factorisation serves the edges of a vertex), full Gauss–Newton where it does not
        // contract. Dense problems take Gauss–Newton's nearest point: the chord projects along
        // the endpoint's normal space, which where two sheets nearly touch (the trough) can
        // land the new vertex on the other sheet.
        const Eigen::VectorXd start = x;
        const auto chord_from_frozen = [&] {
          return shared.frozen_ok &&
                 project_chord(problem, shared.frozen, x, options.corrector).is_success() &&
                 space.distance(x, start) <= length;
        };
        if (is_sparse) {
          shared.freeze_at(problem, mesh, u, length);
          projected = chord_from_frozen();
          if (!projected && shared.frozen_ok && shared.frozen.solves_from_elsewhere()) {
            // Borrowed from farther away: u's own factorisation before Gauss–Newton.
            x = start;
            shared.freeze_own_at(problem, mesh, u);
            projected = chord_from_frozen();
          }
        }
        if (!projected) {
          x = start;
          projected = detail::project_patiently(problem, x, settings, shared.workspace) &&
                      space.distance(x, start) <= length;
        }
      } else {
        projected = faces.size() <= 2 &&
                    project_onto_faces(problem, domain, faces, x, length, settings.gauss_newton);
      }
      if (projected) {
        midpoint_of[unordered_edge_key(u, v)] = mesh.add_vertex(x);
        ++made;
      } else {
        unsplittable.insert(unordered_edge_key(u, v));
      }
    }
    summary.split_edges += made;
    if (made == 0) {
      break;
    }
    // 3. Every triangle with split edges is subdivided; the new triangles are the next
    //    round's candidates. A triangle with two split edges leaves a quadrilateral, cut by
    //    its diagonal of larger smallest angle: the sides of all of them are measured first,
    //    in one pass (one reduction for a split mesh).
    std::vector<Triangle> triangles = mesh.triangles();
    struct Subdivision {
      std::array<int, 3> mid{-1, -1, -1};  // the new vertex on edge e, −1 if not split
      int count = 0;                       // split edges
      std::array<int, 4> quad{};           // count == 2: the quadrilateral q0 q1 q2 q3
      std::array<int, 6> sides{};          // its sides q0q1, q1q2, q2q3, q3q0, q0q2, q1q3
    };
    std::vector<Subdivision> subdivision(triangles.size());
    PairLengths lengths;
    for (std::size_t t = 0; t < triangles.size(); ++t) {
      const Triangle& tri = triangles[t];
      Subdivision& sub = subdivision[t];
      for (int e = 0; e < 3; ++e) {
        const auto it = midpoint_of.find(unordered_edge_key(tri[e], tri[(e + 1) % 3]));
        sub.mid[e] = it == midpoint_of.end() ? -1 : it->second;
        sub.count += sub.mid[e] >= 0 ? 1 : 0;
      }
      if (sub.count != 2) {
        continue;
      }
      // Rotated so that edge 0 (tri[0]→tri[1]) is split: the quadrilateral left beside the
      // triangle cut off at the other split edge.
      int r = 0;
      while (sub.mid[r] < 0) {
        ++r;
      }
      const int a = tri[r];
      const int b = tri[(r + 1) % 3];
      const int c = tri[(r + 2) % 3];
      const int m = sub.mid[r];
      const int m_bc = sub.mid[(r + 1) % 3];
      const int m_ca = sub.mid[(r + 2) % 3];
      sub.quad = m_bc >= 0 ? std::array<int, 4>{a, m, m_bc, c} : std::array<int, 4>{m, b, c, m_ca};
      const std::array<int, 4>& q = sub.quad;
      sub.sides = {lengths.add(q[0], q[1]), lengths.add(q[1], q[2]), lengths.add(q[2], q[3]),
                   lengths.add(q[3], q[0]), lengths.add(q[0], q[2]), lengths.add(q[1], q[3])};
    }
    lengths.measure(mesh);
    std::vector<Triangle> result;
    result.reserve(triangles.size() + 3 * to_split.size());
    candidates.clear();
    for (std::size_t t = 0; t < triangles.size(); ++t) {
      const Triangle& tri = triangles[t];
      const Subdivision& sub = subdivision[t];
      const std::array<int, 3>& mid = sub.mid;
      if (sub.count == 0) {
        result.push_back(tri);
        if (is_far[t]) {
          // Too far, but its edge could not be split this round (the midpoint's projection
          // failed, or the edge was split for a neighbour whose subdivision did not reach
          // it): it stays a candidate, so that it is split later or counted as remaining.
          candidates.push_back(static_cast<int>(result.size()) - 1);
        }
        continue;
      }
      const std::size_t first = result.size();
      if (sub.count == 3) {
        result.push_back({tri[0], mid[0], mid[2]});
        result.push_back({mid[0], tri[1], mid[1]});
        result.push_back({mid[2], mid[1], tri[2]});
        result.push_back({mid[0], mid[1], mid[2]});
      } else if (sub.count == 1) {
        // Rotate so that edge 0 (tri[0]→tri[1]) is split; bisect it.
        int r = 0;
        while (mid[r] < 0) {
          ++r;
        }
        result.push_back({tri[r], mid[r], tri[(r + 2) % 3]});
        result.push_back({mid[r], tri[(r + 1) % 3], tri[(r + 2) % 3]});
      } else {
        // The triangle at the corner between the split edges, then the quadrilateral.
        int r = 0;
        while (mid[r] < 0) {
          ++r;
        }
        const int a = tri[r];
        const int b = tri[(r + 1) % 3];
        const int m = mid[r];
        const int m_bc = mid[(r + 1) % 3];
        const int m_ca = mid[(r + 2) % 3];
        result.push_back(m_bc >= 0 ? Triangle{m, b, m_bc} : Triangle{a, m, m_ca});
        const std::array<int, 4>& q = sub.quad;
        const std::array<int, 6>& s = sub.sides;
        // Cut by q0q2, or by q1q3.
        const double via_q0 =
            std::min(lengths.min_angle(s[0], s[1], s[4]), lengths.min_angle(s[4], s[2], s[3]));
        const double via_q1 =
            std::min(lengths.min_angle(s[0], s[5], s[3]), lengths.min_angle(s[1], s[2], s[5]));
        if (via_q0 >= via_q1) {
          result.push_back({q[0], q[1], q[2]});
          result.push_back({q[0], q[2], q[3]});
        } else {
          result.push_back({q[0], q[1], q[3]});
          result.push_back({q[1], q[2], q[3]});
        }
      }
      for (std::size_t k = first; k < result.size(); ++k) {
        candidates.push_back(static_cast<int>(k));
      }
    }
    mesh.set_triangles(std::move(result));
  }
  // Rounds exhausted, or a round could not split anything: the candidates left are measured
  // once more, so that `remaining` and `max_distance` describe the mesh returned.
  if (exhausted) {
    double worst_remaining = -1.0;
    count_edges();
    measure_gram(mesh, candidates, gram);
    const std::vector<std::pair<int, int>> pairs = anchored(mesh, candidates, rings, along_M);
    const detail::PassSamples pass = sampler.sample(pairs, gram, triangles_at_edge, false);
    for (std::size_t k = 0; k < pairs.size(); ++k) {
      const double worst = pass.worst[k];
      summary.max_distance = std::max(summary.max_distance, worst);
      if (!(worst <= threshold)) {
        if (!(worst <= worst_remaining)) {
          worst_remaining = worst;
          summary.worst_point = sampler.sample_point(pairs[k].second, pass.worst_sample[k], gram);
        }
        ++summary.remaining;
        summary.far_triangles.push_back(pairs[k].second);
      } else {
        summary.max_distance_within = std::max(summary.max_distance_within, worst);
      }
    }
    std::sort(summary.far_triangles.begin(), summary.far_triangles.end());
  }
  return summary;
}

}  // namespace tessera
