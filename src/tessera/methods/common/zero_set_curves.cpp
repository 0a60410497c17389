// SPDX-License-Identifier: MIT
#include "tessera/methods/common/zero_set_curves.h"

#include <cmath>
#include <cstddef>
#include <deque>
#include <limits>
#include <utility>

#include "tessera/core/error.h"

namespace tessera {

namespace {

// Positive or not: a vertex with value exactly 0 counts as positive, so that every triangle with
// three known values has 0 or 2 edges across which the sign changes.
bool is_positive(double value) { return value >= 0.0; }

std::size_t index(int i) { return static_cast<std::size_t>(i); }

}  // namespace

ZeroSetCurves find_zero_set_curves(const TriangleMesh& mesh, const MeshTopology& topology,
                                   const VertexValueFunction& vertex_value,
                                   const ZeroSetOptions& options) {
  TESSERA_CHECK(topology.vertex_count() == mesh.vertex_count() &&
                    topology.triangle_count() == mesh.triangle_count(),
                "zero set curves: the topology has "
                    << topology.vertex_count() << " vertices and " << topology.triangle_count()
                    << " triangles, the mesh " << mesh.vertex_count() << " and "
                    << mesh.triangle_count());
  TESSERA_CHECK(static_cast<bool>(vertex_value), "zero set curves: no vertex value function");
  const int triangle_count = mesh.triangle_count();
  if (options.seed_triangles) {
    for (const int t : *options.seed_triangles) {
      TESSERA_CHECK(t >= 0 && t < triangle_count, "zero set curves: seed triangle "
                                                      << t << " is not in 0 … "
                                                      << triangle_count - 1);
    }
  }
  ZeroSetCurves result;
  const auto& triangles = mesh.triangles();

  std::vector<double> values(index(mesh.vertex_count()), std::numeric_limits<double>::quiet_NaN());
  std::vector<char> is_evaluated(index(mesh.vertex_count()), 0);
  auto ensure_value = [&](int v) {
    if (is_evaluated[index(v)]) {
      return;
    }
    is_evaluated[index(v)] = 1;
    ++result.evaluated_vertex_count;
    values[index(v)] = vertex_value(v);
  };
  // An edge is crossed when both values are known and their signs differ.
  auto is_crossed = [&](int a, int b) {
    const double va = values[index(a)];
    const double vb = values[index(b)];
    return !std::isnan(va) && !std::isnan(vb) && is_positive(va) != is_positive(vb);
  };

  // Marching triangles, grown from the seeds along the sign changes: a triangle is processed once
  // its three vertices have values; every triangle beside a crossed edge is processed.
  std::vector<char> is_processed(index(triangle_count), 0);
  std::deque<int> queue;
  auto push_triangle = [&](int t) {
    if (is_processed[index(t)]) {
      return;
    }
    for (const int v : triangles[index(t)]) {
      ensure_value(v);
    }
    queue.push_back(t);
  };
  if (options.seed_triangles) {
    for (const int t : *options.seed_triangles) {
      push_triangle(t);
    }
  } else {
    for (int t = 0; t < triangle_count; ++t) {
      push_triangle(t);
    }
  }

  std::vector<int> crossing_of_edge(index(topology.edge_count()), -1);
  std::vector<std::vector<int>> segments_of;  // per crossing: indices into `segments`
  std::vector<std::pair<int, int>> segments;  // pairs of crossings joined inside a triangle
  auto crossing_at = [&](int edge, int triangle) {
    int& c = crossing_of_edge[index(edge)];
    if (c < 0) {
      c = static_cast<int>(result.crossings.size());
      ZeroSetCrossing crossing;
      crossing.edge = edge;
      crossing.triangle = triangle;
      crossing.vertices = topology.edge(edge);
      const double v0 = values[index(crossing.vertices[0])];
      const double v1 = values[index(crossing.vertices[1])];
      crossing.fraction = v0 / (v0 - v1);
      result.crossings.push_back(crossing);
      segments_of.emplace_back();
    }
    return c;
  };
  while (!queue.empty()) {
    const int t = queue.front();
    queue.pop_front();
    if (is_processed[index(t)]) {
      continue;
    }
    is_processed[index(t)] = 1;
    ++result.processed_triangle_count;
    if (options.skip_triangle && options.skip_triangle(t)) {
      ++result.skipped_triangle_count;
      continue;
    }
    const Triangle& tri = triangles[index(t)];
    int crossed[3];
    int crossed_count = 0;
    for (int k = 0; k < 3; ++k) {
      const int a = tri[index(k)];
      const int b = tri[index((k + 1) % 3)];
      if (!is_crossed(a, b)) {
        continue;
      }
      const int edge = topology.triangle_edges(t)[index(k)];
      crossed[crossed_count++] = crossing_at(edge, t);
      for (const int other : topology.edge_triangles(edge)) {
        push_triangle(other);
      }
    }
    TESSERA_ASSERT(crossed_count != 3);  // the signs of three values change an even number of times
    if (crossed_count == 2) {
      const int segment = static_cast<int>(segments.size());
      segments.emplace_back(crossed[0], crossed[1]);
      segments_of[index(crossed[0])].push_back(segment);
      segments_of[index(crossed[1])].push_back(segment);
    }
  }
  const int crossing_count = static_cast<int>(result.crossings.size());
  result.crossing_count = crossing_count;

  // Polylines: walk from the open ends (crossings on one segment), then around the loops that
  // remain, then the crossings on no segment.
  std::vector<char> is_walked(segments.size(), 0);
  auto walk = [&](int first) {
    ZeroSetChain chain;
    chain.crossings.push_back(first);
    int current = first;
    for (;;) {
      int next_segment = -1;
      for (const int s : segments_of[index(current)]) {
        if (!is_walked[index(s)]) {
          next_segment = s;
          break;
        }
      }
      if (next_segment < 0) {
        break;
      }
      is_walked[index(next_segment)] = 1;
      const auto& [p, q] = segments[index(next_segment)];
      current = p == current ? q : p;
      if (current == first) {
        chain.is_closed = true;
        return chain;
      }
      chain.crossings.push_back(current);
    }
    return chain;
  };
  for (int c = 0; c < crossing_count; ++c) {
    if (segments_of[index(c)].size() == 1 && !is_walked[index(segments_of[index(c)][0])]) {
      result.chains.push_back(walk(c));
    }
  }
  for (int c = 0; c < crossing_count; ++c) {
    for (const int s : segments_of[index(c)]) {
      if (!is_walked[index(s)]) {
        result.chains.push_back(walk(c));
        break;
      }
    }
  }
  for (int c = 0; c < crossing_count; ++c) {
    if (segments_of[index(c)].empty()) {
      result.chains.push_back({{c}, false});
    }
  }
  return result;
}

ZeroSetCurves find_zero_set_curves(const TriangleMesh& mesh, const MeshTopology& topology,
                                   const std::vector<double>& vertex_values,
                                   const ZeroSetOptions& options) {
  TESSERA_CHECK(static_cast<int>(vertex_values.size()) == mesh.vertex_count(),
                "zero set curves: " << vertex_values.size() << " vertex values for "
                                    << mesh.vertex_count() << " vertices");
  return find_zero_set_curves(
      mesh, topology, [&vertex_values](int v) { return vertex_values[index(v)]; }, options);
}

Eigen::VectorXd crossing_point(const ZeroSetCrossing& crossing,
                               const Eigen::Ref<const Eigen::MatrixXd>& points) {
  TESSERA_CHECK(crossing.vertices[0] >= 0 && crossing.vertices[1] >= 0 &&
                    crossing.vertices[0] < points.cols() && crossing.vertices[1] < points.cols(),
                "crossing_point: the crossing's vertices ("
                    << crossing.vertices[0] << ", " << crossing.vertices[1]
                    << ") are not columns of the " << points.rows() << "×" << points.cols()
                    << " points");
  const Eigen::VectorXd a = points.col(crossing.vertices[0]);
  return a + crossing.fraction * (points.col(crossing.vertices[1]) - a);
}

}  // namespace tessera
