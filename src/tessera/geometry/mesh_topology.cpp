// SPDX-License-Identifier: MIT
#include "tessera/geometry/mesh_topology.h"

#include <algorithm>
#include <utility>

#include "tessera/core/error.h"

namespace tessera {
namespace {

// Local index k of edge e in triangle t (the edge joining t[k] and t[(k+1) % 3]).
int local_edge_index(const std::array<int, 3>& triangle_edges, int e) {
  for (int k = 0; k < 3; ++k) {
    if (triangle_edges[k] == e) {
      return k;
    }
  }
  TESSERA_ASSERT(false);
  return -1;
}

// Prefix sums in place: counts[i + 1] holds the count of item i on entry, offsets on exit.
void accumulate_offsets(std::vector<int>& counts) {
  for (std::size_t i = 1; i < counts.size(); ++i) {
    counts[i] += counts[i - 1];
  }
}

}  // namespace

MeshTopology::MeshTopology(const TriangleMesh& mesh)
    : MeshTopology(mesh.vertex_count(), mesh.triangles()) {}

MeshTopology::MeshTopology(int vertex_count, std::span<const Triangle> triangles)
    : vertex_count_(vertex_count), triangles_(triangles.begin(), triangles.end()) {
  TESSERA_CHECK(vertex_count >= 0,
                "MeshTopology: vertex_count = " << vertex_count << " must be >= 0");
  for (std::size_t t = 0; t < triangles_.size(); ++t) {
    const Triangle& tri = triangles_[t];
    for (int k = 0; k < 3; ++k) {
      TESSERA_CHECK(tri[k] >= 0 && tri[k] < vertex_count,
                    "MeshTopology: triangle " << t << " = (" << tri[0] << ", " << tri[1] << ", "
                                              << tri[2] << ") has vertex index " << tri[k]
                                              << " outside [0, " << vertex_count
                                              << "); validate() reports all such triangles");
    }
    TESSERA_CHECK(tri[0] != tri[1] && tri[1] != tri[2] && tri[2] != tri[0],
                  "MeshTopology: triangle " << t << " = (" << tri[0] << ", " << tri[1] << ", "
                                            << tri[2]
                                            << ") repeats a vertex; its three vertices must be "
                                               "distinct");
  }
  build_vertex_triangles();
  build_edges();
  build_components();
  build_boundary_loops();
}

void MeshTopology::build_vertex_triangles() {
  vertex_triangle_offsets_.assign(static_cast<std::size_t>(vertex_count_) + 1, 0);
  for (const Triangle& tri : triangles_) {
    for (int v : tri) {
      ++vertex_triangle_offsets_[v + 1];
    }
  }
  referenced_vertex_count_ = 0;
  for (int v = 0; v < vertex_count_; ++v) {
    referenced_vertex_count_ += vertex_triangle_offsets_[v + 1] > 0 ? 1 : 0;
  }
  accumulate_offsets(vertex_triangle_offsets_);
  vertex_triangles_.resize(triangles_.size() * 3);
  std::vector<int> cursor(vertex_triangle_offsets_.begin(), vertex_triangle_offsets_.end() - 1);
  for (int t = 0; t < triangle_count(); ++t) {
    for (int v : triangles_[t]) {
      vertex_triangles_[cursor[v]++] = t;
    }
  }
}

// Half-edge h = 3t + k is local edge k of triangle t. Half-edges are bucketed by their smaller
// vertex (a counting sort), then each small bucket is sorted by (larger vertex, h); runs of
// equal vertex pairs are the edges. This is O(N) for bounded vertex degree and needs no map.
void MeshTopology::build_edges() {
  const std::size_t half_edge_count = triangles_.size() * 3;
  auto low_high = [this](std::size_t h) {
    const Triangle& tri = triangles_[h / 3];
    const int a = tri[h % 3];
    const int b = tri[(h % 3 + 1) % 3];
    return a < b ? std::pair{a, b} : std::pair{b, a};
  };

  std::vector<int> bucket_offsets(static_cast<std::size_t>(vertex_count_) + 1, 0);
  for (std::size_t h = 0; h < half_edge_count; ++h) {
    ++bucket_offsets[low_high(h).first + 1];
  }
  accumulate_offsets(bucket_offsets);
  // Key: larger vertex in the high 32 bits, half-edge in the low ones, so that sorting the
  // keys sorts by larger vertex and then by triangle.
  std::vector<std::uint64_t> keys(half_edge_count);
  {
    std::vector<int> cursor(bucket_offsets.begin(), bucket_offsets.end() - 1);
    for (std::size_t h = 0; h < half_edge_count; ++h) {
      const auto [low, high] = low_high(h);
      keys[cursor[low]++] = (static_cast<std::uint64_t>(high) << 32) | h;
    }
  }

  edges_.clear();
  edges_.reserve(half_edge_count / 2 + 1);
  edge_triangle_offsets_.assign(1, 0);
  edge_triangle_offsets_.reserve(half_edge_count / 2 + 2);
  edge_triangles_.clear();
  edge_triangles_.reserve(half_edge_count);
  edges_by_low_vertex_offsets_.assign(static_cast<std::size_t>(vertex_count_) + 1, 0);
  triangle_edges_.assign(triangles_.size(), {-1, -1, -1});
  triangle_neighbors_.assign(triangles_.size(), {-1, -1, -1});
  is_edge_orientation_consistent_.clear();
  is_edge_orientation_consistent_.reserve(half_edge_count / 2 + 1);

  for (int v = 0; v < vertex_count_; ++v) {
    edges_by_low_vertex_offsets_[v] = edge_count();
    const auto bucket_begin = keys.begin() + bucket_offsets[v];
    const auto bucket_end = keys.begin() + bucket_offsets[v + 1];
    std::sort(bucket_begin, bucket_end);
    for (auto run = bucket_begin; run != bucket_end;) {
      const auto high = static_cast<int>(*run >> 32);
      auto run_end = run;
      while (run_end != bucket_end && static_cast<int>(*run_end >> 32) == high) {
        ++run_end;
      }
      const int e = edge_count();
      edges_.push_back({v, high});
      for (auto it = run; it != run_end; ++it) {
        const auto h = static_cast<std::size_t>(*it & 0xffffffffu);
        edge_triangles_.push_back(static_cast<int>(h / 3));
        triangle_edges_[h / 3][h % 3] = e;
      }
      std::uint8_t is_consistent = 1;
      if (run_end - run == 2) {
        const auto h0 = static_cast<std::size_t>(run[0] & 0xffffffffu);
        const auto h1 = static_cast<std::size_t>(run[1] & 0xffffffffu);
        triangle_neighbors_[h0 / 3][h0 % 3] = static_cast<int>(h1 / 3);
        triangle_neighbors_[h1 / 3][h1 % 3] = static_cast<int>(h0 / 3);
        // A half-edge is forward if it starts at the smaller vertex v.
        const bool is_forward0 = triangles_[h0 / 3][h0 % 3] == v;
        const bool is_forward1 = triangles_[h1 / 3][h1 % 3] == v;
        is_consistent = is_forward0 != is_forward1 ? 1 : 0;
      }
      is_edge_orientation_consistent_.push_back(is_consistent);
      edge_triangle_offsets_.push_back(static_cast<int>(edge_triangles_.size()));
      run = run_end;
    }
  }
  edges_by_low_vertex_offsets_[vertex_count_] = edge_count();

  boundary_edges_.clear();
  for (int e = 0; e < edge_count(); ++e) {
    if (is_boundary_edge(e)) {
      boundary_edges_.push_back(e);
    }
  }
}

// Union-find over triangles, joining the triangles of each edge: it walks the CSR arrays in
// order, which is several times faster than a search that jumps from triangle to triangle.
void MeshTopology::build_components() {
  std::vector<int> parent(triangles_.size());
  for (std::size_t t = 0; t < parent.size(); ++t) {
    parent[t] = static_cast<int>(t);
  }
  auto find = [&parent](int t) {
    while (parent[t] != t) {
      parent[t] = parent[parent[t]];  // path halving
      t = parent[t];
    }
    return t;
  };
  for (int e = 0; e < edge_count(); ++e) {
    // All triangles on an edge, not only manifold neighbours: a non-manifold edge still
    // connects its triangles.
    const auto on_edge = edge_triangles(e);
    for (std::size_t i = 1; i < on_edge.size(); ++i) {
      const int a = find(on_edge[0]);
      const int b = find(on_edge[i]);
      if (a != b) {
        parent[std::max(a, b)] = std::min(a, b);  // the root is the lowest triangle
      }
    }
  }
  // Roots are the lowest triangles of their components, so numbering roots in order numbers
  // the components by their lowest triangle.
  triangle_component_.resize(triangles_.size());
  component_count_ = 0;
  for (int t = 0; t < triangle_count(); ++t) {
    const int root = find(t);
    triangle_component_[t] = root == t ? component_count_++ : triangle_component_[root];
  }
}

// Boundary half-edges are chained vertex to vertex. At each vertex an unused boundary edge that
// leaves it in its triangle's direction is preferred, so a consistently oriented boundary is
// followed in that direction; an edge entering the vertex is taken (against its direction) only
// when no leaving one is left, which happens where orientation is inconsistent.
void MeshTopology::build_boundary_loops() {
  const int count = static_cast<int>(boundary_edges_.size());
  std::vector<int> from(count);
  std::vector<int> to(count);
  for (int i = 0; i < count; ++i) {
    const int e = boundary_edges_[i];
    const int t = edge_triangles(e)[0];
    const int k = local_edge_index(triangle_edges_[t], e);
    from[i] = triangles_[t][k];
    to[i] = triangles_[t][(k + 1) % 3];
  }
  // CSR lists of the boundary edges leaving and entering each vertex, each with a cursor past
  // the edges already used, so that the whole walk is O(number of boundary edges).
  std::vector<int> leaving_offsets(static_cast<std::size_t>(vertex_count_) + 1, 0);
  std::vector<int> entering_offsets(static_cast<std::size_t>(vertex_count_) + 1, 0);
  for (int i = 0; i < count; ++i) {
    ++leaving_offsets[from[i] + 1];
    ++entering_offsets[to[i] + 1];
  }
  accumulate_offsets(leaving_offsets);
  accumulate_offsets(entering_offsets);
  std::vector<int> leaving(count);
  std::vector<int> entering(count);
  std::vector<int> leaving_cursor(leaving_offsets.begin(), leaving_offsets.end() - 1);
  std::vector<int> entering_cursor(entering_offsets.begin(), entering_offsets.end() - 1);
  for (int i = 0; i < count; ++i) {
    leaving[leaving_cursor[from[i]]++] = i;
    entering[entering_cursor[to[i]]++] = i;
  }
  std::copy(leaving_offsets.begin(), leaving_offsets.end() - 1, leaving_cursor.begin());
  std::copy(entering_offsets.begin(), entering_offsets.end() - 1, entering_cursor.begin());

  std::vector<std::uint8_t> is_used(count, 0);
  auto next_unused = [&is_used](const std::vector<int>& list, const std::vector<int>& offsets,
                                std::vector<int>& cursor, int v) {
    while (cursor[v] < offsets[v + 1] && is_used[list[cursor[v]]]) {
      ++cursor[v];
    }
    return cursor[v] < offsets[v + 1] ? list[cursor[v]] : -1;
  };

  boundary_loop_offsets_.assign(1, 0);
  boundary_loop_vertices_.clear();
  boundary_loop_vertices_.reserve(count);
  for (int first = 0; first < count; ++first) {
    if (is_used[first]) {
      continue;
    }
    is_used[first] = 1;
    const int start = from[first];
    boundary_loop_vertices_.push_back(start);
    int current = to[first];
    while (current != start) {
      boundary_loop_vertices_.push_back(current);
      int i = next_unused(leaving, leaving_offsets, leaving_cursor, current);
      if (i < 0) {
        i = next_unused(entering, entering_offsets, entering_cursor, current);
      }
      if (i < 0) {
        break;  // an open chain: only possible next to a non-manifold edge
      }
      is_used[i] = 1;
      current = from[i] == current ? to[i] : from[i];
    }
    boundary_loop_offsets_.push_back(static_cast<int>(boundary_loop_vertices_.size()));
  }
}

int MeshTopology::find_edge(int a, int b) const {
  if (a > b) {
    std::swap(a, b);
  }
  if (a < 0 || b >= vertex_count_) {
    return -1;
  }
  const auto begin = edges_.begin() + edges_by_low_vertex_offsets_[a];
  const auto end = edges_.begin() + edges_by_low_vertex_offsets_[a + 1];
  const auto it = std::lower_bound(begin, end, Edge{a, b});
  return it != end && *it == Edge{a, b} ? static_cast<int>(it - edges_.begin()) : -1;
}

OrientationAssignment MeshTopology::orientation_assignment() const {
  OrientationAssignment result;
  result.is_flipped.assign(triangles_.size(), 0);
  result.is_component_orientable.assign(component_count_, 1);
  std::vector<std::uint8_t> is_reached(triangles_.size(), 0);
  std::vector<int> stack;
  for (int seed = 0; seed < triangle_count(); ++seed) {
    if (is_reached[seed]) {
      continue;
    }
    is_reached[seed] = 1;
    stack.push_back(seed);
    while (!stack.empty()) {
      const int t = stack.back();
      stack.pop_back();
      for (int k = 0; k < 3; ++k) {
        const int u = triangle_neighbors_[t][k];
        if (u < 0) {
          continue;
        }
        // u must be flipped relative to t exactly when both traverse the edge the same way.
        const bool is_same_direction = !is_edge_orientation_consistent_[triangle_edges_[t][k]];
        const std::uint8_t wanted = result.is_flipped[t] ^ (is_same_direction ? 1 : 0);
        if (!is_reached[u]) {
          is_reached[u] = 1;
          result.is_flipped[u] = wanted;
          stack.push_back(u);
        } else if (result.is_flipped[u] != wanted) {
          result.is_component_orientable[triangle_component_[t]] = 0;
        }
      }
    }
  }
  return result;
}

std::vector<Triangle> orient_consistently(const TriangleMesh& mesh, bool* is_orientable) {
  const MeshTopology topology(mesh);
  const OrientationAssignment assignment = topology.orientation_assignment();
  std::vector<Triangle> triangles = mesh.triangles();
  for (std::size_t t = 0; t < triangles.size(); ++t) {
    if (assignment.is_flipped[t]) {
      std::swap(triangles[t][1], triangles[t][2]);
    }
  }
  if (is_orientable != nullptr) {
    *is_orientable = std::all_of(assignment.is_component_orientable.begin(),
                                 assignment.is_component_orientable.end(),
                                 [](std::uint8_t flag) { return flag != 0; });
  }
  return triangles;
}

}  // namespace tessera
