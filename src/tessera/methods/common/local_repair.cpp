// SPDX-License-Identifier: MIT
#include "tessera/methods/common/local_repair.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "tessera/core/describe.h"
#include "tessera/core/linearization.h"
#include "tessera/geometry/mesh_quality.h"
#include "tessera/geometry/mesh_topology.h"

namespace tessera {
namespace {

double cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return a.x() * b.y() - a.y() * b.x();
}

// Twice the signed area of the 2-D triangle (a, b, c).
double orient(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c) {
  return cross(b - a, c - a);
}

// Triangulates one hole: `loop` lists its vertices with the hole on the left (the orientation
// of the triangles that filled it). Appends the new triangles, or returns a reason.
//
// A split mesh (each rank its rows of every vertex) takes the tangent coordinates of all the
// vertices involved, and the lengths of all sides and diagonals of the hole, in one reduction
// each; every decision is then taken on those sums, the same on every rank.
std::string fill_hole(const ImplicitProblem& problem, const TriangleMesh& mesh,
                      const std::vector<int>& loop, const std::vector<Triangle>& outside_triangles,
                      std::vector<Triangle>& triangles) {
  const AmbientSpace& space = mesh.space();
  const int k = static_cast<int>(loop.size());
  const int n = mesh.ambient_dimension();
  Eigen::VectorXd center = Eigen::VectorXd::Zero(n);
  for (int v : loop) {
    center += mesh.point(v);
  }
  center /= k;
  // Only on failure (its coordinates are gathered from the ranks of a split mesh).
  const auto where = [&] { return "the hole around " + describe_point(center, space); };
  Linearization linearization;
  Eigen::VectorXd on_m = center;
  if (!project_onto_manifold(problem, on_m, linearization) ||
      !linearization.factor(problem, on_m)) {
    return where() + " has no tangent plane: its centre could not be projected onto M";
  }
  const Eigen::MatrixXd& T = linearization.tangent_basis();
  // The tangent coordinates of the loop's vertices and of the triangles around it, in that
  // order (the triangles' corners may repeat loop vertices: a few columns more, no search).
  const int around = static_cast<int>(outside_triangles.size());
  Eigen::Matrix2Xd coordinates(2, k + 3 * around);
  const auto project = [&](int column, int v) {
    const Eigen::Vector2d q = T.transpose() * (mesh.point(v) - on_m);
    coordinates.col(column) = q;
  };
  for (int i = 0; i < k; ++i) {
    project(i, loop[i]);
  }
  for (int j = 0; j < around; ++j) {
    for (int r = 0; r < 3; ++r) {
      project(k + 3 * j + r, outside_triangles[j][r]);
    }
  }
  space.sum(coordinates.data(), static_cast<int>(coordinates.size()));
  // M's orientation as the mesh sees it, from the triangles around the hole.
  double sense = 0.0;
  for (int j = 0; j < around; ++j) {
    sense += orient(coordinates.col(k + 3 * j), coordinates.col(k + 3 * j + 1),
                    coordinates.col(k + 3 * j + 2));
  }
  if (sense == 0.0) {
    return where() + " has no oriented triangle around it";
  }
  std::vector<Eigen::Vector2d> p(k);
  for (int i = 0; i < k; ++i) {
    p[i] = coordinates.col(i);
    if (sense < 0) {
      p[i].y() = -p[i].y();
    }
  }
  double area = 0.0;
  for (int i = 0; i < k; ++i) {
    area += cross(p[i], p[(i + 1) % k]);
  }
  if (area <= 0) {
    return where() + " folds over itself in M's tangent plane";
  }
  // |loop[i] − loop[j]|² for i < j: every side an ear can have (sum_index(i, j)).
  std::vector<double> squared(static_cast<std::size_t>(k) * (k - 1) / 2);
  const auto sum_index = [&](int i, int j) {
    if (i > j) {
      std::swap(i, j);
    }
    return static_cast<std::size_t>(i) * (2 * k - i - 1) / 2 + (j - i - 1);
  };
  for (int i = 0; i < k; ++i) {
    for (int j = i + 1; j < k; ++j) {
      squared[sum_index(i, j)] = (mesh.point(loop[j]) - mesh.point(loop[i])).squaredNorm();
    }
  }
  if (!squared.empty()) {
    space.sum(squared.data(), static_cast<int>(squared.size()));
  }
  // min_angle of the triangle of loop vertices a, b, c (the same numbers, to the bit).
  const auto ear_angle = [&](int a, int b, int c) {
    return min_angle_of_sides(std::sqrt(squared[sum_index(a, b)]),
                              std::sqrt(squared[sum_index(b, c)]),
                              std::sqrt(squared[sum_index(c, a)]));
  };
  // Ear clipping, the ear of largest smallest angle (measured in R^n) first.
  std::vector<int> polygon(k);
  for (int i = 0; i < k; ++i) {
    polygon[i] = i;
  }
  const double tiny = 1e-12 * area;
  while (polygon.size() > 3) {
    const int m = static_cast<int>(polygon.size());
    int best = -1;
    double best_angle = -1.0;
    for (int i = 0; i < m; ++i) {
      const int a = polygon[(i + m - 1) % m], b = polygon[i], c = polygon[(i + 1) % m];
      if (orient(p[a], p[b], p[c]) <= tiny) {
        continue;  // a reflex or flat corner is no ear
      }
      bool empty = true;
      for (int j : polygon) {
        if (j != a && j != b && j != c && orient(p[a], p[b], p[j]) >= 0 &&
            orient(p[b], p[c], p[j]) >= 0 && orient(p[c], p[a], p[j]) >= 0) {
          empty = false;
          break;
        }
      }
      if (!empty) {
        continue;
      }
      const double angle = ear_angle(a, b, c);
      if (angle > best_angle) {
        best_angle = angle;
        best = i;
      }
    }
    if (best < 0) {
      return where() + " is not a simple polygon in M's tangent plane";
    }
    triangles.push_back(
        {loop[polygon[(best + m - 1) % m]], loop[polygon[best]], loop[polygon[(best + 1) % m]]});
    polygon.erase(polygon.begin() + best);
  }
  if (orient(p[polygon[0]], p[polygon[1]], p[polygon[2]]) <= tiny) {
    return where() + " leaves a flat last triangle";
  }
  triangles.push_back({loop[polygon[0]], loop[polygon[1]], loop[polygon[2]]});
  return {};
}

}  // namespace

LocalRepair repair_locally(const ImplicitProblem& problem, TriangleMesh& mesh,
                           const std::vector<int>& defective, int rings) {
  LocalRepair repair;
  check_mesh_of_problem(mesh, problem, "repair_locally");
  const int vertex_count = mesh.vertex_count();
  const int triangle_count = mesh.triangle_count();
  std::vector<std::vector<int>> fan(vertex_count);
  for (int t = 0; t < triangle_count; ++t) {
    for (int v : mesh.triangle(t)) {
      fan[v].push_back(t);
    }
  }
  // The region: the defective triangles grown by the fans of their vertices, so that a
  // misplaced vertex of a defective triangle ends up inside the region and is dropped.
  std::vector<char> in_region(triangle_count, 0);
  for (int t : defective) {
    in_region[t] = 1;
  }
  for (int ring = 0; ring < rings; ++ring) {
    const std::vector<char> current = in_region;
    for (int t = 0; t < triangle_count; ++t) {
      if (current[t]) {
        for (int v : mesh.triangle(t)) {
          for (int s : fan[v]) {
            in_region[s] = 1;
          }
        }
      }
    }
  }
  std::vector<Triangle> region;
  std::vector<Triangle> kept;
  for (int t = 0; t < triangle_count; ++t) {
    (in_region[t] ? region : kept).push_back(mesh.triangle(t));
  }
  if (region.empty()) {
    repair.is_repaired = true;
    return repair;
  }
  // Each edge-connected part of the region must be a disk: one boundary loop, χ = 1.
  const MeshTopology topology(vertex_count, region);
  std::vector<std::vector<Triangle>> parts(topology.component_count());
  for (int t = 0; t < static_cast<int>(region.size()); ++t) {
    parts[topology.component_of(t)].push_back(region[t]);
  }
  std::vector<Triangle> filled;
  for (const std::vector<Triangle>& part : parts) {
    const MeshTopology disk(vertex_count, part);
    Eigen::VectorXd center = Eigen::VectorXd::Zero(mesh.ambient_dimension());
    for (const Triangle& t : part) {
      center += (mesh.point(t[0]) + mesh.point(t[1]) + mesh.point(t[2])) / (3.0 * part.size());
    }
    if (disk.boundary_loop_count() != 1 || disk.euler_characteristic() != 1) {
      repair.message = "the defective triangles near " + describe_point(center, mesh.space()) +
                       " and their neighbours do not form a disk";
      return repair;
    }
    const auto span = disk.boundary_loop(0);
    std::vector<int> loop(span.begin(), span.end());
    std::vector<int> sorted = loop;
    std::sort(sorted.begin(), sorted.end());
    if (std::adjacent_find(sorted.begin(), sorted.end()) != sorted.end() || loop.size() < 3) {
      repair.message =
          "the hole near " + describe_point(center, mesh.space()) + " touches itself";
      return repair;
    }
    // The triangles outside the region along its boundary tell M's orientation.
    std::vector<Triangle> around;
    std::vector<char> on_loop(vertex_count, 0);
    for (int v : loop) {
      on_loop[v] = 1;
    }
    for (const Triangle& t : kept) {
      if (on_loop[t[0]] + on_loop[t[1]] + on_loop[t[2]] >= 2) {
        around.push_back(t);
      }
    }
    const std::string reason = fill_hole(problem, mesh, loop, around, filled);
    if (!reason.empty()) {
      repair.message = reason;
      return repair;
    }
    ++repair.filled_holes;
  }
  repair.removed_triangles = static_cast<int>(region.size());
  repair.added_triangles = static_cast<int>(filled.size());
  kept.insert(kept.end(), filled.begin(), filled.end());
  mesh.set_triangles(std::move(kept));
  mesh.keep_triangles(std::vector<bool>(mesh.triangle_count(), true));  // drop inner vertices
  repair.is_repaired = true;
  return repair;
}

}  // namespace tessera
