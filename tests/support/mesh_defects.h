// SPDX-License-Identifier: MIT
// Geometric defects of a mesh of M, counted independently of any method (test support, header
// only): triangles whose orientation disagrees with M's, and pairs of triangles that cover the
// same part of M. A throwaway check until `validate` does this itself (issue 10).
#pragma once

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <numeric>
#include <unordered_map>
#include <vector>

#include "tessera/core/implicit_problem.h"
#include "tessera/geometry/triangle_mesh.h"

namespace tessera::testing {

/// sign det[DF(c); e1ᵀ; e2ᵀ] at the centroid c of triangle t (n×n, e1, e2 its edges from the
/// first vertex): +1 or −1 by M's orientation, 0 for a degenerate triangle or a singular DF.
inline int triangle_orientation_sign(const TriangleMesh& mesh, const ImplicitProblem& problem, int t) {
  const int n = mesh.ambient_dimension();
  const Triangle& tri = mesh.triangle(t);
  const Eigen::VectorXd a = mesh.point(tri[0]);
  const Eigen::VectorXd e1 = Eigen::VectorXd(mesh.point(tri[1])) - a;
  const Eigen::VectorXd e2 = Eigen::VectorXd(mesh.point(tri[2])) - a;
  const Eigen::VectorXd c = (a + mesh.point(tri[1]) + mesh.point(tri[2])) / 3.0;
  Eigen::MatrixXd J(n - 2, n);
  problem.jacobian(c, J);
  Eigen::MatrixXd bordered(n, n);
  bordered.topRows(n - 2) = J;
  bordered.row(n - 2) = e1.transpose();
  bordered.row(n - 1) = e2.transpose();
  const double det = bordered.partialPivLu().determinant();
  return det > 0 ? 1 : (det < 0 ? -1 : 0);
}

/// Triangles connected through shared edges: the component of each triangle.
inline std::vector<int> triangle_components(const TriangleMesh& mesh) {
  const int count = mesh.triangle_count();
  std::vector<int> parent(count);
  std::iota(parent.begin(), parent.end(), 0);
  const auto find = [&](int t) {
    while (parent[t] != t) {
      t = parent[t] = parent[parent[t]];
    }
    return t;
  };
  std::unordered_map<long long, int> first_at_edge;
  for (int t = 0; t < count; ++t) {
    for (int e = 0; e < 3; ++e) {
      const int a = std::min(mesh.triangle(t)[e], mesh.triangle(t)[(e + 1) % 3]);
      const int b = std::max(mesh.triangle(t)[e], mesh.triangle(t)[(e + 1) % 3]);
      const auto [it, inserted] = first_at_edge.emplace((static_cast<long long>(a) << 32) | b, t);
      if (!inserted) {
        parent[find(t)] = find(it->second);
      }
    }
  }
  std::vector<int> component(count);
  for (int t = 0; t < count; ++t) {
    component[t] = find(t);
  }
  return component;
}

/// Triangles whose orientation is the minority one in their component (or degenerate): a
/// consistently oriented mesh of an orientable M has none.
/// With `counted`, only the triangles for which counted(t) is true are counted (all vote).
template <typename Predicate>
inline int count_flipped_triangles(const TriangleMesh& mesh, const ImplicitProblem& problem,
                                   Predicate counted) {
  const std::vector<int> component = triangle_components(mesh);
  std::unordered_map<int, int> votes;
  std::vector<int> sign(mesh.triangle_count());
  for (int t = 0; t < mesh.triangle_count(); ++t) {
    sign[t] = triangle_orientation_sign(mesh, problem, t);
    votes[component[t]] += sign[t];
  }
  int flipped = 0;
  for (int t = 0; t < mesh.triangle_count(); ++t) {
    const int majority = votes[component[t]] >= 0 ? 1 : -1;
    flipped += sign[t] != majority && counted(t) ? 1 : 0;
  }
  return flipped;
}

inline int count_flipped_triangles(const TriangleMesh& mesh, const ImplicitProblem& problem) {
  return count_flipped_triangles(mesh, problem, [](int) { return true; });
}

/// Pairs of triangles without a common vertex that cover the same part of M: the centroid of
/// one lies over the other (inside it when projected onto its plane) and within a quarter of
/// the other's longest edge from that plane. Quadratic in the number of triangles near each
/// other (a grid of cells of the longest edge), fine for test meshes.
inline int count_overlapping_pairs(const TriangleMesh& mesh) {
  const int count = mesh.triangle_count();
  const int n = mesh.ambient_dimension();
  double longest = 0.0;
  std::vector<Eigen::VectorXd> centroid(count);
  for (int t = 0; t < count; ++t) {
    const Triangle& tri = mesh.triangle(t);
    centroid[t] = (mesh.point(tri[0]) + mesh.point(tri[1]) + mesh.point(tri[2])) / 3.0;
    for (int e = 0; e < 3; ++e) {
      longest = std::max(longest, (mesh.point(tri[e]) - mesh.point(tri[(e + 1) % 3])).norm());
    }
  }
  if (count == 0 || longest == 0.0) {
    return 0;
  }
  const auto cell_of = [&](const Eigen::VectorXd& x) {
    long long key = 0;
    for (int i = 0; i < std::min(n, 3); ++i) {
      key = key * 1000003 + static_cast<long long>(std::floor(x(i) / longest));
    }
    return key;
  };
  std::unordered_map<long long, std::vector<int>> grid;
  for (int t = 0; t < count; ++t) {
    grid[cell_of(centroid[t])].push_back(t);
  }
  const auto covers = [&](int a, int b) {  // does triangle a lie over b's centroid?
    const Triangle& tri = mesh.triangle(a);
    const Eigen::VectorXd p0 = mesh.point(tri[0]);
    Eigen::MatrixXd E(n, 2);
    E.col(0) = mesh.point(tri[1]) - p0;
    E.col(1) = mesh.point(tri[2]) - p0;
    const Eigen::VectorXd d = centroid[b] - p0;
    const Eigen::Vector2d w = E.colPivHouseholderQr().solve(d);
    const double normal = (d - E * w).norm();
    const double edge = std::max({E.col(0).norm(), E.col(1).norm(), (E.col(1) - E.col(0)).norm()});
    return w(0) > 0 && w(1) > 0 && w(0) + w(1) < 1 && normal < 0.25 * edge;
  };
  int pairs = 0;
  for (int a = 0; a < count; ++a) {
    const int dimensions = std::min(n, 3);
    Eigen::VectorXd corner = centroid[a];
    for (int offset = 0; offset < static_cast<int>(std::pow(3, dimensions)); ++offset) {
      Eigen::VectorXd probe = corner;
      for (int i = 0, o = offset; i < dimensions; ++i, o /= 3) {
        probe(i) += (o % 3 - 1) * longest;
      }
      const auto found = grid.find(cell_of(probe));
      if (found == grid.end()) {
        continue;
      }
      for (int b : found->second) {
        if (b <= a) {
          continue;
        }
        const Triangle& ta = mesh.triangle(a);
        const Triangle& tb = mesh.triangle(b);
        bool shares = false;
        for (int u : ta) {
          shares = shares || std::find(tb.begin(), tb.end(), u) != tb.end();
        }
        if (!shares && (covers(a, b) || covers(b, a))) {
          ++pairs;
        }
      }
    }
  }
  return pairs;
}

}  // namespace tessera::testing
