// SPDX-License-Identifier: MIT
// A geometric check for tests: every triangle of a mesh of M is oriented like M around it.
// Until `validate` checks this itself, the front and clipping tests use this one.
#pragma once

#include <Eigen/Core>
#include <Eigen/LU>
#include <algorithm>
#include <map>
#include <numeric>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "tessera/core/describe.h"
#include "tessera/core/implicit_problem.h"
#include "tessera/geometry/triangle_mesh.h"

namespace tessera::testing {

/// One triangle whose orientation disagrees with the rest of its edge-connected component.
struct FlippedTriangle {
  int triangle = -1;
  Eigen::VectorXd centroid;  ///< n-vector
  /// det[DF(c); e1ᵀ; e2ᵀ] / (‖e1‖·‖e2‖·Π‖∇F_i‖): the sine of the angle between the triangle's
  /// normal and M's, for n = 3; its sign is the orientation.
  double orientation = 0.0;
};

struct OrientationCheck {
  int component_count = 0;
  std::vector<FlippedTriangle> flipped;

  bool is_consistent() const { return flipped.empty(); }
  std::string report(std::size_t shown = 10) const {
    std::ostringstream out;
    out << flipped.size() << " flipped triangle(s) in " << component_count << " component(s)";
    for (std::size_t i = 0; i < std::min(shown, flipped.size()); ++i) {
      out << "\n  triangle " << flipped[i].triangle << " at " << describe_point(flipped[i].centroid)
          << ", orientation " << flipped[i].orientation;
    }
    return out.str();
  }
};

/// The orientation of triangle t relative to M: the sign of det[DF(c); e1ᵀ; e2ᵀ] at the
/// centroid c, with e1, e2 the edges from its first vertex (for n = 3: ∇F·(e1 × e2)),
/// normalised to lie in [−1, 1].
inline double triangle_orientation(const TriangleMesh& mesh, const ImplicitProblem& problem,
                                   int t) {
  const int n = mesh.ambient_dimension();
  const Triangle& tri = mesh.triangle(t);
  const Eigen::VectorXd a = mesh.point(tri[0]);
  const Eigen::VectorXd e1 = mesh.point(tri[1]) - a;
  const Eigen::VectorXd e2 = mesh.point(tri[2]) - a;
  const Eigen::VectorXd centroid = a + (e1 + e2) / 3.0;
  Eigen::MatrixXd J(n - 2, n);
  problem.jacobian(centroid, J);
  Eigen::MatrixXd A(n, n);
  A.topRows(n - 2) = J;
  A.row(n - 2) = e1.transpose();
  A.row(n - 1) = e2.transpose();
  double scale = e1.norm() * e2.norm();
  for (int i = 0; i < n - 2; ++i) {
    scale *= J.row(i).norm();
  }
  return scale > 0 ? A.determinant() / scale : 0.0;
}

/// Triangles whose orientation disagrees with the majority of their edge-connected component
/// (or is zero): a consistently oriented mesh of M has one sign per component.
inline OrientationCheck check_orientation(const TriangleMesh& mesh,
                                          const ImplicitProblem& problem) {
  const int count = mesh.triangle_count();
  std::vector<int> parent(count);
  std::iota(parent.begin(), parent.end(), 0);
  const auto find = [&](int t) {
    while (parent[t] != t) {
      parent[t] = parent[parent[t]];
      t = parent[t];
    }
    return t;
  };
  std::map<std::pair<int, int>, int> first_triangle_of_edge;
  for (int t = 0; t < count; ++t) {
    const Triangle& tri = mesh.triangle(t);
    for (int r = 0; r < 3; ++r) {
      const auto edge = std::minmax(tri[r], tri[(r + 1) % 3]);
      const auto [it, inserted] = first_triangle_of_edge.emplace(edge, t);
      if (!inserted) {
        parent[find(t)] = find(it->second);
      }
    }
  }
  std::vector<double> orientation(count);
  std::map<int, std::pair<int, int>> votes;  // root → (positive, negative)
  for (int t = 0; t < count; ++t) {
    orientation[t] = triangle_orientation(mesh, problem, t);
    auto& vote = votes[find(t)];
    vote.first += orientation[t] > 0 ? 1 : 0;
    vote.second += orientation[t] < 0 ? 1 : 0;
  }
  OrientationCheck check;
  check.component_count = static_cast<int>(votes.size());
  for (int t = 0; t < count; ++t) {
    const auto& vote = votes[find(t)];
    const double majority = vote.first >= vote.second ? 1.0 : -1.0;
    if (!(orientation[t] * majority > 0)) {
      const Triangle& tri = mesh.triangle(t);
      const Eigen::VectorXd centroid =
          (mesh.point(tri[0]) + mesh.point(tri[1]) + mesh.point(tri[2])) / 3.0;
      check.flipped.push_back({t, centroid, orientation[t]});
    }
  }
  return check;
}

}  // namespace tessera::testing
