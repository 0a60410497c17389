// SPDX-License-Identifier: MIT
// Small meshes with known topology, built in code, shared by the geometry tests.
#pragma once

#include <cmath>
#include <map>
#include <numbers>
#include <utility>

#include <Eigen/Core>

#include "tessera/geometry/triangle_mesh.h"

namespace tessera::examples {

/// Vertices ±e_x, ±e_y, ±e_z (0: +x, 1: -x, 2: +y, 3: -y, 4: +z, 5: -z); 8 triangles with
/// outward normals. V = 6, E = 12, F = 8, chi = 2.
inline TriangleMesh octahedron() {
  Eigen::MatrixXd points = Eigen::MatrixXd::Zero(3, 6);
  for (int axis = 0; axis < 3; ++axis) {
    points(axis, 2 * axis) = 1.0;
    points(axis, 2 * axis + 1) = -1.0;
  }
  std::vector<Triangle> triangles;
  for (int sx = 0; sx < 2; ++sx) {
    for (int sy = 0; sy < 2; ++sy) {
      for (int sz = 0; sz < 2; ++sz) {
        const int x = sx;
        const int y = 2 + sy;
        const int z = 4 + sz;
        // (x, y, z) is outward in the octant with an even number of negative signs.
        if ((sx + sy + sz) % 2 == 0) {
          triangles.push_back({x, y, z});
        } else {
          triangles.push_back({x, z, y});
        }
      }
    }
  }
  return TriangleMesh(points, triangles);
}

/// Icosahedron with each triangle split into 4, `subdivisions` times, projected onto the unit
/// sphere. V = 10 * 4^s + 2, E = 30 * 4^s, F = 20 * 4^s, chi = 2.
inline TriangleMesh icosphere(int subdivisions) {
  const double phi = (1.0 + std::sqrt(5.0)) / 2.0;
  std::vector<Eigen::Vector3d> points = {{-1, phi, 0}, {1, phi, 0}, {-1, -phi, 0}, {1, -phi, 0},
                                         {0, -1, phi}, {0, 1, phi}, {0, -1, -phi}, {0, 1, -phi},
                                         {phi, 0, -1}, {phi, 0, 1}, {-phi, 0, -1}, {-phi, 0, 1}};
  std::vector<Triangle> triangles = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                                     {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                                     {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                                     {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
  for (int s = 0; s < subdivisions; ++s) {
    std::map<std::pair<int, int>, int> midpoint;  // test code: clarity over speed
    auto middle = [&](int a, int b) {
      const auto key = std::minmax(a, b);
      const auto [it, is_new] = midpoint.try_emplace(key, static_cast<int>(points.size()));
      if (is_new) {
        points.push_back(0.5 * (points[a] + points[b]));
      }
      return it->second;
    };
    std::vector<Triangle> finer;
    for (const Triangle& t : triangles) {
      const int ab = middle(t[0], t[1]);
      const int bc = middle(t[1], t[2]);
      const int ca = middle(t[2], t[0]);
      finer.insert(finer.end(), {{t[0], ab, ca}, {t[1], bc, ab}, {t[2], ca, bc}, {ab, bc, ca}});
    }
    triangles = std::move(finer);
  }
  Eigen::MatrixXd matrix(3, static_cast<int>(points.size()));
  for (std::size_t i = 0; i < points.size(); ++i) {
    matrix.col(static_cast<int>(i)) = points[i].normalized();
  }
  return TriangleMesh(matrix, triangles);
}

/// Vertex (i, j) of an m×n grid with periodic rows and columns has index i * n + j.
inline int grid_index(int i, int j, int n) { return i * n + j; }

/// Torus of revolution (radii 2 and 0.5) from an m×n periodic grid, 2mn triangles, outward
/// normals. V = mn, E = 3mn, F = 2mn, chi = 0, genus 1. \pre m, n >= 3.
inline TriangleMesh torus(int m, int n) {
  Eigen::MatrixXd points(3, m * n);
  for (int i = 0; i < m; ++i) {
    for (int j = 0; j < n; ++j) {
      const double u = 2 * std::numbers::pi * i / m;
      const double v = 2 * std::numbers::pi * j / n;
      points.col(grid_index(i, j, n)) << (2 + 0.5 * std::cos(v)) * std::cos(u),
          (2 + 0.5 * std::cos(v)) * std::sin(u), 0.5 * std::sin(v);
    }
  }
  std::vector<Triangle> triangles;
  triangles.reserve(2 * static_cast<std::size_t>(m) * n);
  for (int i = 0; i < m; ++i) {
    for (int j = 0; j < n; ++j) {
      const int a = grid_index(i, j, n);
      const int b = grid_index((i + 1) % m, j, n);
      const int c = grid_index((i + 1) % m, (j + 1) % n, n);
      const int d = grid_index(i, (j + 1) % n, n);
      triangles.push_back({a, b, c});
      triangles.push_back({a, c, d});
    }
  }
  return TriangleMesh(points, triangles);
}

/// The unit square in R^2 as a k×k grid of quads, each split into 2 counter-clockwise
/// triangles. V = (k+1)^2, F = 2k^2, E = 3k^2 + 2k, chi = 1, one boundary loop of 4k vertices.
inline TriangleMesh square_grid(int k) {
  Eigen::MatrixXd points(2, (k + 1) * (k + 1));
  for (int i = 0; i <= k; ++i) {
    for (int j = 0; j <= k; ++j) {
      points.col(grid_index(i, j, k + 1)) << static_cast<double>(j) / k, static_cast<double>(i) / k;
    }
  }
  std::vector<Triangle> triangles;
  for (int i = 0; i < k; ++i) {
    for (int j = 0; j < k; ++j) {
      const int a = grid_index(i, j, k + 1);
      const int b = grid_index(i, j + 1, k + 1);
      const int c = grid_index(i + 1, j + 1, k + 1);
      const int d = grid_index(i + 1, j, k + 1);
      triangles.push_back({a, b, c});
      triangles.push_back({a, c, d});
    }
  }
  return TriangleMesh(points, triangles);
}

/// Möbius strip of m quads (2m triangles) in R^3: vertex 2i + s is at angle 2 pi i / m on
/// side s. The last quad is glued to the first with the sides swapped. V = 2m, E = 4m,
/// F = 2m, chi = 0, one boundary loop of 2m vertices, non-orientable. \pre m >= 3.
inline TriangleMesh mobius_strip(int m) {
  Eigen::MatrixXd points(3, 2 * m);
  for (int i = 0; i < m; ++i) {
    const double angle = 2 * std::numbers::pi * i / m;
    for (int side = 0; side < 2; ++side) {
      const double w = side == 0 ? -0.3 : 0.3;
      points.col(2 * i + side) << (1 + w * std::cos(angle / 2)) * std::cos(angle),
          (1 + w * std::cos(angle / 2)) * std::sin(angle), w * std::sin(angle / 2);
    }
  }
  std::vector<Triangle> triangles;
  for (int i = 0; i < m; ++i) {
    const bool is_seam = i == m - 1;
    const int a = 2 * i;
    const int d = 2 * i + 1;
    const int next = is_seam ? 0 : 2 * (i + 1);
    const int b = is_seam ? next + 1 : next;  // the seam swaps the sides
    const int c = is_seam ? next : next + 1;
    triangles.push_back({a, b, c});
    triangles.push_back({a, c, d});
  }
  return TriangleMesh(points, triangles);
}

/// The triangles of `mesh` followed by those of `other`, whose vertices come after.
inline TriangleMesh disjoint_union(const TriangleMesh& mesh, const TriangleMesh& other) {
  Eigen::MatrixXd points(mesh.ambient_dimension(), mesh.vertex_count() + other.vertex_count());
  points << mesh.points(), other.points();
  std::vector<Triangle> triangles = mesh.triangles();
  for (Triangle t : other.triangles()) {
    triangles.push_back(
        {t[0] + mesh.vertex_count(), t[1] + mesh.vertex_count(), t[2] + mesh.vertex_count()});
  }
  return TriangleMesh(points, triangles);
}

}  // namespace tessera::examples
