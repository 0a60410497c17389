// SPDX-License-Identifier: MIT
#include "tessera/geometry/bezier_surface.h"

#include <algorithm>
#include <cstdint>
#include <map>
#include <unordered_map>

#include "tessera/core/error.h"

namespace tessera {
namespace {

void check_patches(const TriangleMesh& mesh, const std::vector<CubicBezierPatch>& patches) {
  TESSERA_CHECK(static_cast<int>(patches.size()) == mesh.triangle_count(),
                "cubic surface: " << patches.size() << " patches for " << mesh.triangle_count()
                                  << " triangles; need one per triangle");
  for (std::size_t t = 0; t < patches.size(); ++t) {
    TESSERA_CHECK(patches[t].ambient_dimension() == mesh.ambient_dimension(),
                  "cubic surface: patch " << t << " is in R^" << patches[t].ambient_dimension()
                                          << " but the mesh is in R^" << mesh.ambient_dimension());
  }
}

// Barycentric coordinates of lattice point (i, j) of the K-subdivision: (K − i − j, i, j)/K is
// the weight of corners 0, 1, 2.
Eigen::Vector3d lattice(int i, int j, int K) {
  return Eigen::Vector3d(K - i - j, i, j) / static_cast<double>(K);
}

}  // namespace

TriangleMesh refine_bezier_surface(const TriangleMesh& mesh,
                                   const std::vector<CubicBezierPatch>& patches, int subdivisions) {
  check_patches(mesh, patches);
  TESSERA_CHECK(subdivisions >= 1, "refine: subdivisions = " << subdivisions << " must be >= 1");
  const int K = subdivisions;
  const int n = mesh.ambient_dimension();
  TriangleMesh refined(n);
  refined.reserve(mesh.vertex_count() + mesh.triangle_count() * (K + 1) * (K + 2) / 2,
                  mesh.triangle_count() * K * K);
  for (int v = 0; v < mesh.vertex_count(); ++v) {
    refined.add_vertex(mesh.point(v));
  }
  // Points inside edges, keyed by the undirected edge (smaller vertex first) and the position
  // counted from the smaller vertex: both triangles at an edge use the same points.
  std::map<std::pair<int, int>, std::vector<int>> edge_points;
  for (int t = 0; t < mesh.triangle_count(); ++t) {
    const Triangle& tri = mesh.triangle(t);
    const CubicBezierPatch& patch = patches[t];
    // index[i][j]: refined vertex of lattice point (i, j) (weight of corner 1 is i/K, of 2 j/K).
    std::vector<std::vector<int>> index(K + 1, std::vector<int>(K + 1, -1));
    const auto on_edge = [&](int from, int to, int step) -> int {
      // The step-th of the K − 1 inner points from corner `from` to corner `to` of tri.
      const int u = tri[from];
      const int w = tri[to];
      auto& points = edge_points[{std::min(u, w), std::max(u, w)}];
      const int position = u < w ? step : K - step;  // counted from the smaller vertex
      if (points.empty()) {
        points.assign(K + 1, -1);
      }
      if (points[position] < 0) {
        Eigen::Vector3d lambda = Eigen::Vector3d::Zero();
        lambda(from) = static_cast<double>(K - step) / K;
        lambda(to) = static_cast<double>(step) / K;
        points[position] = refined.add_vertex(patch.evaluate(lambda));
      }
      return points[position];
    };
    for (int i = 0; i <= K; ++i) {
      for (int j = 0; i + j <= K; ++j) {
        const int k = K - i - j;
        if (i == 0 && j == 0) {
          index[i][j] = tri[0];
        } else if (i == K) {
          index[i][j] = tri[1];
        } else if (j == K) {
          index[i][j] = tri[2];
        } else if (j == 0) {
          index[i][j] = on_edge(0, 1, i);  // edge 0→1, i steps from corner 0
        } else if (i == 0) {
          index[i][j] = on_edge(0, 2, j);
        } else if (k == 0) {
          index[i][j] = on_edge(1, 2, j);  // edge 1→2, j steps from corner 1
        } else {
          index[i][j] = refined.add_vertex(patch.evaluate(lattice(i, j, K)));
        }
      }
    }
    for (int i = 0; i < K; ++i) {
      for (int j = 0; i + j < K; ++j) {
        // Same orientation as (corner 0, corner 1, corner 2).
        refined.add_triangle(index[i][j], index[i + 1][j], index[i][j + 1]);
        if (i + j + 1 < K) {
          refined.add_triangle(index[i + 1][j], index[i + 1][j + 1], index[i][j + 1]);
        }
      }
    }
  }
  return refined;
}

double max_edge_mismatch(const TriangleMesh& mesh, const std::vector<CubicBezierPatch>& patches,
                         int samples) {
  check_patches(mesh, patches);
  TESSERA_CHECK(samples >= 1, "max_edge_mismatch: samples = " << samples << " must be >= 1");
  // First triangle seen at each undirected edge, with the local corners of the edge.
  struct Side {
    int triangle;
    int from, to;  // local corners, from = the smaller vertex
  };
  std::map<std::pair<int, int>, Side> first;
  double mismatch = 0.0;
  for (int t = 0; t < mesh.triangle_count(); ++t) {
    const Triangle& tri = mesh.triangle(t);
    for (int c = 0; c < 3; ++c) {
      int from = c, to = (c + 1) % 3;
      if (tri[from] > tri[to]) {
        std::swap(from, to);
      }
      const std::pair<int, int> key{tri[from], tri[to]};
      const auto it = first.find(key);
      if (it == first.end()) {
        first.emplace(key, Side{t, from, to});
        continue;
      }
      const Side& other = it->second;
      for (int s = 1; s <= samples; ++s) {
        const double mu = static_cast<double>(s) / (samples + 1);
        Eigen::Vector3d mine = Eigen::Vector3d::Zero(), theirs = Eigen::Vector3d::Zero();
        mine(from) = 1.0 - mu;
        mine(to) = mu;
        theirs(other.from) = 1.0 - mu;
        theirs(other.to) = mu;
        mismatch =
            std::max(mismatch,
                     (patches[t].evaluate(mine) - patches[other.triangle].evaluate(theirs)).norm());
      }
    }
  }
  return mismatch;
}

}  // namespace tessera
