// SPDX-License-Identifier: MIT
#include "tessera/methods/atlas/atlas_triangulation.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <vector>

#include "tessera/core/describe.h"
#include "tessera/geometry/mesh_quality.h"
#include "tessera/geometry/pinched_vertices.h"

namespace tessera {
namespace {

// Loops of boundary edges longer than this are the atlas's outer boundary (in S, or around the
// margin outside it), not holes. Shorter loops between closed charts are holes, filled by
// triangles whose corners' disks overlap pairwise (see HoleFiller::triangulate).
constexpr int kMaxHoleVertices = 128;
// A hole's new edges join charts at most this many times the sum of their radii apart (every
// edge of the atlas's dual joins overlapping disks, at most 1 times apart in a flat atlas).
// Closure is judged in each chart's tangent plane, where neighbours on a curved M look nearer
// than they are in R^n, and a strip of disagreement ends in a fan: on a thin torus the four
// charts around a hole were 1.01 (R_a + R_b) apart across both diagonals, and the tip of a
// strip 1.5 radii wide needed an edge 1.53 (R_a + R_b) long.
constexpr double kHoleEdgeReach = 2.0;

struct Proposal {
  std::pair<std::uint64_t, std::uint32_t> key;  // the triangle's charts, increasing, packed
  std::array<int, 3> sorted;                    // the same, unpacked
  int proposer = 0;
  bool even = true;  // (i, j, k) as proposed is an even permutation of `sorted`
};

std::uint64_t edge_key(int a, int b) {
  return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(a)) << 32) |
         static_cast<std::uint32_t>(b);
}

bool is_even_rotation(const std::array<int, 3>& t, const std::array<int, 3>& sorted) {
  for (int r = 0; r < 3; ++r) {
    if (t[r] == sorted[0] && t[(r + 1) % 3] == sorted[1] && t[(r + 2) % 3] == sorted[2]) {
      return true;
    }
  }
  return false;
}

// A closed walk that visits a vertex twice is two loops joined there; returns the simple ones.
// Of a walk that does not close (it ran into a dead end), only the loops it went around count:
// what is left after them is the open tail, no loop.
std::vector<std::vector<int>> split_into_simple_loops(const std::vector<int>& walk, bool closed) {
  std::vector<std::vector<int>> loops;
  std::vector<int> stack;
  for (int v : walk) {
    const auto seen = std::find(stack.begin(), stack.end(), v);
    if (seen != stack.end()) {
      loops.emplace_back(seen, stack.end());
      stack.erase(seen, stack.end());
    }
    stack.push_back(v);
  }
  if (closed && stack.size() >= 3) {
    loops.push_back(stack);
  }
  std::erase_if(loops, [](const std::vector<int>& loop) { return loop.size() < 3; });
  return loops;
}

class HoleFiller {
 public:
  /// `triangles`: every triangle at a suspect chart (and maybe others); boundary edges are
  /// looked for only at suspect charts, where all triangles are present.
  HoleFiller(const AtlasCells& cells, std::vector<Triangle>& triangles,
             const std::vector<bool>& suspect)
      : cells_(cells),
        triangles_(triangles),
        suspect_(suspect),
        space_(cells.space ? cells.space
                           : std::make_shared<const AmbientSpace>(cells.ambient_dimension)) {}

  /// Fills the holes bounded by closed charts; returns the number filled, and sets `message`
  /// for the first hole that could not be filled.
  int fill(std::string& message);

 private:
  void index_edges();
  bool has_edge(int a, int b) const {
    return std::binary_search(undirected_.begin(), undirected_.end(),
                              edge_key(std::min(a, b), std::max(a, b)));
  }
  bool triangulate(const std::vector<int>& loop, std::vector<Triangle>& added,
                   bool require_counter_clockwise) const;

  const AmbientSpace& space() const { return *space_; }

  const AtlasCells& cells_;
  std::vector<Triangle>& triangles_;
  const std::vector<bool>& suspect_;
  std::shared_ptr<const AmbientSpace> space_;  // the centres' rows and their reductions
  std::vector<std::uint64_t> directed_;
  std::vector<std::uint64_t> undirected_;
};

void HoleFiller::index_edges() {
  directed_.clear();
  undirected_.clear();
  for (const Triangle& t : triangles_) {
    for (int e = 0; e < 3; ++e) {
      const int a = t[e];
      const int b = t[(e + 1) % 3];
      directed_.push_back(edge_key(a, b));
      undirected_.push_back(edge_key(std::min(a, b), std::max(a, b)));
    }
  }
  std::sort(directed_.begin(), directed_.end());
  std::sort(undirected_.begin(), undirected_.end());
  undirected_.erase(std::unique(undirected_.begin(), undirected_.end()), undirected_.end());
}

int HoleFiller::fill(std::string& message) {
  index_edges();
  // Boundary half-edges a→b: their reverse b→a belongs to no triangle. The hole lies to the
  // right of them, so each loop runs clockwise around its hole.
  std::vector<std::pair<int, int>> boundary;
  for (std::uint64_t key : directed_) {
    const int a = static_cast<int>(key >> 32);
    const int b = static_cast<int>(key & 0xffffffffu);
    if ((suspect_[a] || suspect_[b]) &&
        !std::binary_search(directed_.begin(), directed_.end(), edge_key(b, a))) {
      boundary.emplace_back(a, b);
    }
  }
  std::sort(boundary.begin(), boundary.end());
  std::vector<bool> used(boundary.size(), false);
  auto next_from = [&](int a) -> int {
    auto it = std::lower_bound(boundary.begin(), boundary.end(), std::make_pair(a, -1));
    for (; it != boundary.end() && it->first == a; ++it) {
      const auto index = static_cast<std::size_t>(it - boundary.begin());
      if (!used[index]) {
        return static_cast<int>(index);
      }
    }
    return -1;
  };
  int filled = 0;
  std::vector<Triangle> added;
  for (std::size_t first = 0; first < boundary.size(); ++first) {
    if (used[first]) {
      continue;
    }
    std::vector<int> loop;
    int edge = static_cast<int>(first);
    bool closed_loop = false;
    while (edge >= 0) {
      used[edge] = true;
      loop.push_back(boundary[edge].first);
      const int head = boundary[edge].second;
      if (head == boundary[first].first) {
        closed_loop = true;
        break;
      }
      edge = next_from(head);
    }
    // Where two holes touch at a vertex the walk runs through both: split it into simple loops.
    // The walk is followed to its end and only then split. Where a hole touches the atlas's
    // outer boundary (a hole of disagreeing charts next to one at the margin outside S that is
    // never completed), the walk runs around the hole and along the whole outer boundary; the
    // hole is still a hole between closed charts and must be filled. Dropping every walk longer
    // than the longest hole, as before, left such a hole inside S (whitney_pleat at tolerance
    // 0.01062: four nearly cocircular charts at the face y = 1.5, whose polygons each chose a
    // different diagonal, touching through a second such quad a chart just beyond the margin).
    for (std::vector<int>& simple : split_into_simple_loops(loop, closed_loop)) {
      if (static_cast<int>(simple.size()) > kMaxHoleVertices) {
        continue;  // the atlas boundary
      }
      const bool all_closed =
          std::all_of(simple.begin(), simple.end(), [&](int c) { return cells_.is_closed(c); });
      if (!all_closed) {
        continue;  // the boundary of the atlas (run stopped, or the margin outside the domain)
      }
      std::reverse(simple.begin(), simple.end());  // counter-clockwise around the hole
      // Only counter-clockwise triangles: a loop that cannot be filled so is not a hole but
      // the outline of an island of triangles (filling it would double the island) or a fold.
      if (!triangulate(simple, added, true)) {
        if (message.empty()) {
          message = "the charts' polygons leave a hole of " + std::to_string(simple.size()) +
                    " vertices near " + describe_point(cells_.center(simple.front()), space()) +
                    " that cannot be triangulated";
        }
        continue;
      }
      ++filled;
    }
  }
  triangles_.insert(triangles_.end(), added.begin(), added.end());
  return filled;
}

bool HoleFiller::triangulate(const std::vector<int>& loop, std::vector<Triangle>& added,
                             bool require_counter_clockwise) const {
  const int k = static_cast<int>(loop.size());
  // The loop's points relative to the first (n × k), their distances and their coordinates in
  // every corner's tangent plane, computed once: O(n k²) here, O(1) per candidate triangle in
  // the O(k³) search below.
  const Eigen::VectorXd origin = cells_.center(loop[0]);
  Eigen::MatrixXd X(origin.size(), k);
  for (int i = 0; i < k; ++i) {
    X.col(i) = cells_.center(loop[i]) - origin;
  }
  const Eigen::MatrixXd gram = space().products(X, X);
  Eigen::MatrixXd distance(k, k);
  for (int i = 0; i < k; ++i) {
    for (int j = 0; j < k; ++j) {
      distance(i, j) = std::sqrt(std::max(0.0, gram(i, i) + gram(j, j) - 2.0 * gram(i, j)));
    }
  }
  // Orientation is judged in the tangent planes of the triangle's own vertices (all three must
  // agree: where M turns fast, one far tangent plane can misjudge it); angles in R^n.
  std::vector<Eigen::MatrixXd> plane(k);  // 2 × k: the loop in corner i's tangent coordinates
  for (int i = 0; i < k; ++i) {
    plane[i] = space().products(cells_.tangent(loop[i]), X);
  }
  auto quality = [&](int a, int b, int c) {
    for (int corner : {a, b, c}) {
      const Eigen::Vector2d u = plane[corner].col(b) - plane[corner].col(a);
      const Eigen::Vector2d v = plane[corner].col(c) - plane[corner].col(a);
      if (require_counter_clockwise && u(0) * v(1) - u(1) * v(0) <= 0) {
        return -1.0;  // not counter-clockwise: would fold over its neighbours
      }
    }
    const double smallest = min_angle_of_sides(distance(a, b), distance(b, c), distance(a, c));
    return smallest > 0 ? smallest : -1.0;
  };
  // A new edge joins two charts whose disks (nearly) overlap, as every edge of the atlas's dual
  // does (kHoleEdgeReach): a hole between closed charts, a disagreement of their polygons, is
  // filled, while a gap no chart covers could only be bridged by longer edges and is reported.
  // The hole's size is not the test: on a thin torus (r = 0.07, charts of radius 0.023) the
  // polygons of two rows of charts, seen from planes 20° apart, disagree along strips of
  // 12–52 charts.
  auto diagonal_allowed = [&](int a, int b) {
    if (b - a == 1 || (a == 0 && b == k - 1)) {
      return true;
    }
    return !has_edge(loop[a], loop[b]) &&
           distance(a, b) < kHoleEdgeReach * (cells_.radius(loop[a]) + cells_.radius(loop[b]));
  };
  const double kNone = -1.0;
  std::vector<double> best(k * k, kNone);
  std::vector<int> split(k * k, -1);
  for (int i = 0; i + 1 < k; ++i) {
    best[i * k + i + 1] = std::numeric_limits<double>::infinity();
  }
  for (int length = 2; length < k; ++length) {
    for (int i = 0; i + length < k; ++i) {
      const int j = i + length;
      if (!diagonal_allowed(i, j)) {
        continue;
      }
      for (int m = i + 1; m < j; ++m) {
        const double value = std::min({best[i * k + m], best[m * k + j], quality(i, m, j)});
        if (value > best[i * k + j]) {
          best[i * k + j] = value;
          split[i * k + j] = m;
        }
      }
    }
  }
  if (best[k - 1] <= 0) {
    return false;
  }
  std::vector<std::pair<int, int>> stack = {{0, k - 1}};
  while (!stack.empty()) {
    const auto [i, j] = stack.back();
    stack.pop_back();
    if (j - i < 2) {
      continue;
    }
    const int m = split[i * k + j];
    added.push_back({loop[i], loop[m], loop[j]});
    stack.emplace_back(i, m);
    stack.emplace_back(m, j);
  }
  return true;
}

}  // namespace

AtlasTriangulation triangulate_atlas(const AtlasCells& cells) {
  std::vector<Proposal> proposals;
  proposals.reserve(static_cast<std::size_t>(cells.chart_count) * 6);
  std::vector<int> proposed(cells.chart_count, 0);
  std::vector<int> accepted(cells.chart_count, 0);
  for (int c = 0; c < cells.chart_count; ++c) {
    const auto& vertices = cells.polygon(c).vertices();
    const double r2 = cells.radius(c) * cells.radius(c) * (1.0 + 1e-9);
    const int m = static_cast<int>(vertices.size());
    for (int i = 0; i < m && m >= 3; ++i) {
      const int before = vertices[(i + m - 1) % m].edge_label;  // edge ending at vertex i
      const int after = vertices[i].edge_label;                 // edge starting at vertex i
      if (before < 0 || after < 0 || before == after ||
          vertices[i].s * vertices[i].s + vertices[i].t * vertices[i].t > r2) {
        continue;
      }
      const std::array<int, 3> t = {c, before, after};
      std::array<int, 3> sorted = t;
      std::sort(sorted.begin(), sorted.end());
      const std::pair<std::uint64_t, std::uint32_t> key = {
          (static_cast<std::uint64_t>(static_cast<std::uint32_t>(sorted[0])) << 32) |
              static_cast<std::uint32_t>(sorted[1]),
          static_cast<std::uint32_t>(sorted[2])};
      proposals.push_back({key, sorted, c, is_even_rotation(t, sorted)});
      ++proposed[c];
    }
  }
  std::sort(proposals.begin(), proposals.end(), [](const Proposal& a, const Proposal& b) {
    return a.key != b.key ? a.key < b.key : a.proposer < b.proposer;
  });
  std::vector<Triangle> triangles;
  for (std::size_t first = 0; first < proposals.size();) {
    std::size_t last = first;
    int proposers = 0;
    int even_votes = 0;
    int previous = -1;
    while (last < proposals.size() && proposals[last].key == proposals[first].key) {
      if (proposals[last].proposer != previous) {
        ++proposers;
        previous = proposals[last].proposer;
        even_votes += proposals[last].even ? 1 : 0;
      }
      ++last;
    }
    if (proposers == 3) {
      const auto& s = proposals[first].sorted;
      for (int c : s) {
        ++accepted[c];
      }
      triangles.push_back(even_votes >= 2 ? Triangle{s[0], s[1], s[2]}
                                          : Triangle{s[0], s[2], s[1]});
    }
    first = last;
  }
  AtlasTriangulation result;
  result.consistent_triangles = static_cast<int>(triangles.size());

  // A closed chart all of whose proposals were accepted has its whole fan: every triangle at
  // it is one it proposed. Only triangles at the other ("suspect") charts can have a third
  // triangle on an edge or a boundary edge, so the repairs below look at those alone, which
  // keeps the assembly linear in the number of charts.
  std::vector<bool> suspect(cells.chart_count, false);
  for (int c = 0; c < cells.chart_count; ++c) {
    suspect[c] = accepted[c] < proposed[c] || !cells.is_closed(c);
  }
  std::vector<Triangle> settled;
  {
    std::vector<Triangle> near_suspects;
    for (const Triangle& t : triangles) {
      (suspect[t[0]] || suspect[t[1]] || suspect[t[2]] ? near_suspects : settled).push_back(t);
    }
    triangles = std::move(near_suspects);
  }

  // An edge of more than two triangles cannot come from consistent fans; drop them all and let
  // the hole filler triangulate the place again. So is a triangle none of whose edges another
  // triangle shares: an island inside a hole (on a thin torus, one triangle of three charts
  // whose polygons agreed, in a strip where their neighbours' did not), whose outline cannot
  // be filled and which the hole's triangles would overlap.
  {
    std::vector<std::pair<std::uint64_t, int>> edges;  // (edge, triangle), -1: a settled one
    std::vector<bool> near(cells.chart_count, false);
    for (int t = 0; t < static_cast<int>(triangles.size()); ++t) {
      for (int e = 0; e < 3; ++e) {
        const int a = triangles[t][e];
        const int b = triangles[t][(e + 1) % 3];
        edges.emplace_back(edge_key(std::min(a, b), std::max(a, b)), t);
        near[a] = true;
      }
    }
    for (const Triangle& t : settled) {
      for (int e = 0; e < 3; ++e) {
        const int a = t[e];
        const int b = t[(e + 1) % 3];
        if (near[a] && near[b]) {
          edges.emplace_back(edge_key(std::min(a, b), std::max(a, b)), -1);
        }
      }
    }
    std::sort(edges.begin(), edges.end());
    std::vector<bool> drop(triangles.size(), false);
    std::vector<int> shared_edges(triangles.size(), 0);
    for (std::size_t i = 0; i < edges.size();) {
      std::size_t j = i;
      while (j < edges.size() && edges[j].first == edges[i].first) {
        ++j;
      }
      for (std::size_t q = i; q < j; ++q) {
        if (edges[q].second >= 0) {
          drop[edges[q].second] = drop[edges[q].second] || j - i > 2;
          shared_edges[edges[q].second] += j - i > 1 ? 1 : 0;
        }
      }
      i = j;
    }
    if (triangles.size() + settled.size() > 1) {
      for (std::size_t t = 0; t < triangles.size(); ++t) {
        drop[t] = drop[t] || shared_edges[t] == 0;
      }
    }
    std::vector<Triangle> kept;
    for (std::size_t t = 0; t < triangles.size(); ++t) {
      if (!drop[t]) {
        kept.push_back(triangles[t]);
      }
    }
    triangles = std::move(kept);
  }
  HoleFiller filler(cells, triangles, suspect);
  result.filled_holes = filler.fill(result.message);
  triangles.insert(triangles.end(), settled.begin(), settled.end());
  // Pinches arise at the ragged outer edge of an unfinished atlas (outside the domain, or
  // where a run stopped); the caller checks that none is left where M must be covered.
  {
    const std::vector<bool> keep = keep_largest_fans(cells.chart_count, triangles);
    std::vector<Triangle> kept;
    for (std::size_t t = 0; t < triangles.size(); ++t) {
      if (keep[t]) {
        kept.push_back(triangles[t]);
      }
    }
    result.dropped_triangles = static_cast<int>(triangles.size() - kept.size());
    triangles = std::move(kept);
  }

  // Vertices: the charts that carry triangles, in chart order.
  std::vector<int> vertex_of(cells.chart_count, -1);
  for (const Triangle& t : triangles) {
    for (int c : t) {
      vertex_of[c] = 0;
    }
  }
  std::vector<bool> carries(cells.chart_count, false);
  int vertex_count = 0;
  for (int c = 0; c < cells.chart_count; ++c) {
    if (vertex_of[c] == 0) {
      carries[c] = true;
      vertex_of[c] = vertex_count++;
      result.radius.push_back(cells.radius(c));
    }
  }
  for (Triangle& t : triangles) {
    for (int& c : t) {
      c = vertex_of[c];
    }
  }
  std::sort(triangles.begin(), triangles.end());  // deterministic order
  PointStorage points(cells.ambient_dimension);
  if (cells.take_centers) {
    points = cells.take_centers(carries);
  } else {
    points.reserve(vertex_count);
    for (int c = 0; c < cells.chart_count; ++c) {
      if (carries[c]) {
        points.push_back(cells.center(c));
      }
    }
  }
  result.mesh = TriangleMesh(std::move(points), std::move(triangles));
  if (cells.space && cells.space->is_distributed()) {
    result.mesh.set_space(cells.space);
  }
  return result;
}

}  // namespace tessera
