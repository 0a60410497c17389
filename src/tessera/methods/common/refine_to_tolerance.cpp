// SPDX-License-Identifier: MIT
#include "tessera/methods/common/refine_to_tolerance.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <unordered_map>
#include <unordered_set>

#include "tessera/core/error.h"
#include "tessera/core/factorisation_cache.h"
#include "tessera/core/linearization.h"
#include "tessera/geometry/mesh_quality.h"
#include "tessera/methods/common/clip_to_domain.h"

namespace tessera {
namespace {

// Sampled distances are measured to this fraction of the refinement threshold: enough to
// decide "split or not", and a bound from above, so the decision errs towards splitting.
constexpr double kDistanceAccuracy = 0.02;
// A sample whose two-step bound (chord_distance_bound) is below this fraction of the threshold
// passes without a third step: most samples of a mesh sized for the tolerance lie well inside.
constexpr double kClearPass = 0.75;

std::uint64_t edge_key(int a, int b) {
  if (a > b) {
    std::swap(a, b);
  }
  return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(a)) << 32) |
         static_cast<std::uint32_t>(b);
}

// The faces of the domain both endpoints lie on: the edge runs along their intersection.
// `distance_a`, `distance_b`: every face's signed distance of the endpoints (Domain::
// signed_distances, measured for all edges of a round at once).
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

// A boundary edge that cuts a corner of the domain: one end on face a only, the other on face b
// only. M ∩ S reaches beyond it to the corner point M ∩ a ∩ b (isolated: M is a surface), so
// the gap is measured there and the edge is split at that point ({a, b}); empty otherwise.
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

// A triangle (a, b, c)'s Gram numbers: |b − a|², |c − a|², (b − a)·(c − a), and |c − b|² (for
// its third edge's length to the bit).
using Gram = std::array<double, 4>;

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
// instead of one factorisation per triangle.
std::vector<std::pair<int, int>> anchored(const TriangleMesh& mesh,
                                          const std::vector<int>& candidates, int rings) {
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
  Linearization workspace;
  // Gauss–Newton, and where it contracts too slowly for the method's corrector (θ above its
  // max_contraction, typically 1/2), once more with θ up to 0.9, as the report measures: a
  // midpoint far from a strongly curved M (cstr, an edge 0.2 long) is often first overshot,
  // and a midpoint that can be neither measured nor projected leaves its triangle unrefined.
  // (Only points come out of these projections, not their workspace: Gauss–Newton may keep its
  // factorisation while it contracts, on sparse problems.)
  CorrectorOptions corrector = options.corrector;
  corrector.reuse_factorisation = true;
  CorrectorOptions patient = corrector;
  patient.max_contraction = std::max(patient.max_contraction, 0.9);
  patient.max_iterations = std::max(patient.max_iterations, 50);
  const auto project_patiently = [&](Eigen::VectorXd& x) {
    const Eigen::VectorXd start = x;
    if (project_gauss_newton(problem, x, corrector, workspace).is_success()) {
      return true;
    }
    x = start;
    return project_gauss_newton(problem, x, patient, workspace).is_success();
  };
  const double threshold = options.tolerance * options.sample_safety;
  // The samples of a triangle are projected with the chord iteration frozen at one of its
  // vertices, its anchor, which serves all triangles around it (a factorisation for every
  // third vertex or so, instead of several per Gauss–Newton projection: for sparse problems
  // factorisations are the cost). The chord lands on M, so its displacement bounds the
  // distance from above: the estimate errs towards splitting. It is only needed to a small
  // fraction of the threshold, which two or three chord steps give (chord_distance_bound).
  const double accuracy = kDistanceAccuracy * threshold;
  const double clear_below = kClearPass * threshold;
  const bool is_sparse = problem.has_sparse_jacobian();
  Linearization frozen;
  int frozen_at = -1;
  bool frozen_ok = false;
  // Sparse problems anchor across two rings (fewer factorisations); where the anchor's chord
  // does not contract at a point, a corner of the triangle is tried: one already factored if
  // any (the last few are kept), else its first.
  const int rings = is_sparse ? 2 : 1;
  FactorisationCache corners(6, std::size_t{256} << 20);
  const auto corner_of = [&](const Triangle& tri) -> const Linearization* {
    for (int v : tri) {
      if (const Linearization* factored = corners.find(v)) {
        return factored->is_factored() ? factored : nullptr;
      }
    }
    return corners.factor(tri[0], problem, mesh.point(tri[0]));
  };
  // Where the anchor's chord does not contract at a point: a corner of the triangle, and last
  // a (patient) Gauss–Newton projection.
  auto distance_without_anchor = [&](const Eigen::VectorXd& point, const Triangle& tri) {
    if (frozen_at != tri[0] && frozen_at != tri[1] && frozen_at != tri[2]) {
      const Linearization* corner = corner_of(tri);
      const double bound = corner != nullptr
                               ? chord_distance_bound(problem, *corner, point, accuracy,
                                                      options.corrector, clear_below)
                               : std::numeric_limits<double>::infinity();
      if (std::isfinite(bound)) {
        return bound;
      }
    }
    Eigen::VectorXd x = point;
    if (!project_patiently(x)) {
      return std::numeric_limits<double>::infinity();
    }
    return space.distance(x, point);
  };
  // Each rank's stop request is its own: the ranks stop together if any asks.
  const auto is_stop_requested = [&] {
    if (!options.stop_requested) {
      return false;
    }
    const bool stop = options.stop_requested();
    return space.is_distributed() ? space.maximum(stop ? 1.0 : 0.0) > 0.0 : stop;
  };
  // An edge's midpoint is sampled once for both triangles that share it (vertices never move,
  // so the distance stays valid across rounds).
  std::unordered_map<std::uint64_t, double> midpoint_distance;
  // The largest sampled distance of triangle t to M, and where it is. `gram` holds the Gram
  // numbers of the triangles sampled (measure_gram, one reduction per pass).
  Eigen::VectorXd where;
  Eigen::MatrixXd samples;
  std::vector<Gram> gram;
  // Boundary edges on ∂S: the mesh ends at the chord, M ∩ S at the curve M ∩ face, which bulges
  // beyond the chord within M by its geodesic curvature·L²/8, a part of M ∩ S that no triangle
  // covers and no sample of a triangle sees (on cstr's face Da = 0.3, 0.012 at a tolerance of
  // 0.008). So each boundary edge on a face also samples the gap: the distance from its
  // midpoint to M ∩ face, where its split would put the new vertex. `triangles_at_edge` counts
  // each edge's triangles (rebuilt each round); the gaps are kept, since vertices never move.
  std::unordered_map<std::uint64_t, int> triangles_at_edge;
  std::unordered_map<std::uint64_t, double> boundary_gap;
  int worst_edge = -1;  // after sample(): the edge whose gap is the worst sample, else −1
  const auto count_edges = [&] {
    triangles_at_edge.clear();
    if (domain.is_unbounded()) {
      return;
    }
    for (const Triangle& tri : mesh.triangles()) {
      for (int e = 0; e < 3; ++e) {
        ++triangles_at_edge[edge_key(tri[e], tri[(e + 1) % 3])];
      }
    }
  };
  const auto gap_of = [&](int u, int v) {
    const std::uint64_t key = edge_key(u, v);
    if (const auto known = boundary_gap.find(key); known != boundary_gap.end()) {
      return known->second;
    }
    double gap = 0.0;
    const std::vector<int> ends = {u, v};
    const Eigen::MatrixXd distance = domain.signed_distances(mesh.points(), ends);
    std::vector<int> faces = shared_faces(distance.col(0), distance.col(1), options.face_tolerance);
    if (faces.empty()) {
      faces = corner_faces(distance.col(0), distance.col(1), options.face_tolerance);
    }
    if (!faces.empty() && faces.size() <= 2) {
      const Eigen::VectorXd midpoint = 0.5 * (mesh.point(u) + mesh.point(v));
      Eigen::VectorXd x = midpoint;
      const double length = space.distance(mesh.point(u), mesh.point(v));
      // A midpoint that cannot be put on M ∩ face is left to the triangle samples (its edge
      // is then unsplittable anyway).
      // The chord from the triangle's anchor first: at large n no factorisation at all.
      if (project_onto_faces(problem, domain, faces, x, length, corrector, nullptr,
                             frozen_ok ? &frozen : nullptr)) {
        gap = space.distance(x, midpoint);
      }
    }
    boundary_gap.emplace(key, gap);
    return gap;
  };
  auto sample = [&](int anchor, int t) {
    const Triangle tri = mesh.triangle(t);
    const Eigen::VectorXd a = mesh.point(tri[0]);
    const Eigen::VectorXd b = mesh.point(tri[1]);
    const Eigen::VectorXd c = mesh.point(tri[2]);
    if (anchor != frozen_at) {
      frozen_ok = frozen.factor(problem, mesh.point(anchor));
      frozen_at = anchor;
    }
    // The samples: the centroid, the midpoints not measured before and, on a surface of
    // constant curvature the farthest point, the circumcentre (when it lies inside the
    // triangle), which makes the estimate nearly exact.
    samples.resize(a.size(), 5);
    Eigen::Index count = 0;
    samples.col(count++) = (a + b + c) / 3.0;
    std::array<std::uint64_t, 3> new_midpoints{};
    int new_midpoint_count = 0;
    for (int e = 0; e < 3; ++e) {
      const int u = tri[e];
      const int v = tri[(e + 1) % 3];
      if (!midpoint_distance.contains(edge_key(u, v))) {
        new_midpoints[new_midpoint_count++] = edge_key(u, v);
        samples.col(count++) = 0.5 * (mesh.point(u) + mesh.point(v));
      }
    }
    bool has_circumcentre = false;
    const Gram& g = gram[static_cast<std::size_t>(t)];
    const double uu = g[0], ww = g[1], uw = g[2];
    const double det = 2.0 * (uu * ww - uw * uw);
    if (det > 0) {
      const double beta = ww * (uu - uw) / det;
      const double gamma = uu * (ww - uw) / det;
      if (beta >= 0 && gamma >= 0 && beta + gamma <= 1) {
        const Eigen::VectorXd ab = b - a;
        const Eigen::VectorXd ac = c - a;
        samples.col(count++) = a + beta * ab + gamma * ac;
        has_circumcentre = true;
      }
    }
    // All samples are measured from the anchor in lockstep (one multi-column solve per chord
    // step); those where its chord does not contract, another way.
    const auto points = samples.leftCols(count);
    std::vector<double> distance =
        frozen_ok ? chord_distance_bounds(problem, frozen, points, accuracy, options.corrector,
                                          clear_below)
                  : std::vector<double>(static_cast<std::size_t>(count),
                                        std::numeric_limits<double>::infinity());
    for (Eigen::Index j = 0; j < count; ++j) {
      auto& d = distance[static_cast<std::size_t>(j)];
      if (!std::isfinite(d)) {
        d = distance_without_anchor(points.col(j), tri);
      }
    }
    for (int e = 0; e < new_midpoint_count; ++e) {
      midpoint_distance.emplace(new_midpoints[e], distance[static_cast<std::size_t>(1 + e)]);
    }
    // The worst sample, the first of equals in the order centroid, midpoints, circumcentre;
    // its point is formed once, for the worst triangle's report.
    double worst = -1.0;
    int worst_sample = -1;  // 0: the centroid, 1 + e: the midpoint of edge e, 4: circumcentre,
                            // 5: between them (the model below)
    const auto consider = [&](int which, double d) {
      if (!(d <= worst)) {
        worst = d;
        worst_sample = which;
      }
    };
    consider(0, distance[0]);
    std::array<double, 3> at_midpoint{};
    for (int e = 0; e < 3; ++e) {
      at_midpoint[e] = midpoint_distance.at(edge_key(tri[e], tri[(e + 1) % 3]));
      consider(1 + e, at_midpoint[e]);
    }
    // Between the samples: a flat triangle's distance to M vanishes at its corners and is, to
    // leading order, quadratic in the barycentric coordinates λ (exactly so on a sphere), so
    // the midpoints' distances a_e fix 4·Σ λ_i λ_j a_ij and the centroid's a cubic bubble
    // b·λ₀λ₁λ₂ on top. Its largest value on a grid of the triangle (arithmetic only) bounds
    // the distance where the samples miss it: beside the longest edge of an obtuse triangle
    // where M's curvature varies (bezier's triangles were up to 1.3 % beyond the tolerance
    // between these samples).
    if (std::isfinite(distance[0]) && std::isfinite(at_midpoint[0]) &&
        std::isfinite(at_midpoint[1]) && std::isfinite(at_midpoint[2])) {
      const auto quadratic = [&](double l0, double l1, double l2) {
        return 4.0 *
               (l0 * l1 * at_midpoint[0] + l1 * l2 * at_midpoint[1] + l2 * l0 * at_midpoint[2]);
      };
      const double bubble = 27.0 * (distance[0] - quadratic(1.0 / 3, 1.0 / 3, 1.0 / 3));
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
    if (has_circumcentre) {
      consider(4, distance.back());
    }
    worst_edge = -1;
    for (int e = 0; e < 3 && !triangles_at_edge.empty(); ++e) {
      const int u = tri[e];
      const int v = tri[(e + 1) % 3];
      const auto uses = triangles_at_edge.find(edge_key(u, v));
      if (uses != triangles_at_edge.end() && uses->second == 1) {
        const double gap = gap_of(u, v);
        if (gap > worst) {
          worst = gap;
          worst_sample = 1 + e;
          worst_edge = e;
        }
      }
    }
    if (worst_sample == 0 || worst_sample == 4 || worst_sample == 5) {
      where = points.col(worst_sample == 4 ? count - 1 : 0);  // the model's: its centroid
    } else {
      const int e = worst_sample - 1;
      where = 0.5 * (mesh.point(tri[e]) + mesh.point(tri[(e + 1) % 3]));
    }
    return worst;
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
    for (const auto& [anchor, t] : anchored(mesh, candidates, rings)) {
      // Checked here only, where nothing of the round has changed the mesh yet: at large n
      // the samples are minutes of chord steps, and a stopped run wants its mesh now.
      if (is_stop_requested()) {
        summary.interrupted = true;
        break;
      }
      const Triangle tri = mesh.triangle(t);
      const double worst = sample(anchor, t);
      if (worst <= threshold) {
        summary.max_distance = std::max(summary.max_distance, worst);
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
      if (worst_edge >= 0) {
        longest = worst_edge;  // the gap beyond a boundary edge: that edge is split
      }
      const int u = tri[longest];
      const int v = tri[(longest + 1) % 3];
      if (!unsplittable.contains(edge_key(u, v)) &&
          midpoint_of.emplace(edge_key(u, v), -1).second) {
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
      const auto uses = triangles_at_edge.find(edge_key(u, v));
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
        if (frozen_at != u && is_sparse) {
          frozen_ok = frozen.factor(problem, a);
          frozen_at = u;
        }
        projected = is_sparse && frozen_ok &&
                    project_chord(problem, frozen, x, options.corrector).is_success() &&
                    space.distance(x, start) <= length;
        if (!projected) {
          x = start;
          projected = project_patiently(x) && space.distance(x, start) <= length;
        }
      } else {
        projected =
            faces.size() <= 2 && project_onto_faces(problem, domain, faces, x, length, corrector);
      }
      if (projected) {
        midpoint_of[edge_key(u, v)] = mesh.add_vertex(x);
        ++made;
      } else {
        unsplittable.insert(edge_key(u, v));
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
        const auto it = midpoint_of.find(edge_key(tri[e], tri[(e + 1) % 3]));
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
    for (const auto& [anchor, t] : anchored(mesh, candidates, rings)) {
      const double worst = sample(anchor, t);
      summary.max_distance = std::max(summary.max_distance, worst);
      if (!(worst <= threshold)) {
        if (!(worst <= worst_remaining)) {
          worst_remaining = worst;
          summary.worst_point = where;
        }
        ++summary.remaining;
      }
    }
  }
  return summary;
}

}  // namespace tessera
