// SPDX-License-Identifier: MIT
// The validation's sampled check of thin triangles on M (docs/validation.md, "Thin triangles").
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <set>
#include <sstream>
#include <utility>
#include <vector>

#include <Eigen/LU>

#include "tessera/core/describe.h"
#include "tessera/core/linearization.h"
#include "tessera/geometry/detail/mesh_validation_checks.h"
#include "tessera/geometry/mesh_quality.h"

namespace tessera::detail {

// 2b. Thin triangles, sampled. A needle's or a cap's plane is a poor chart of M: a cap whose
// corners lie nearly along a curve of M stands steeply on M, the tangent planes at its corners
// disagree, and where M bends across it no flat chart of the pair sees its fold (cstr near
// x1 = 1: caps of 177°, folded in the global chart (x2, B), pass both tests above). So every
// triangle with an angle below 10° or above 150° is also sampled: seven of its points (the
// centroid, and one near and one between the centroid and each corner), each projected onto M
// at m. A nearby triangle s covers m if M's normal space at m meets s strictly inside (all
// barycentric coordinates above 1e-3) at q, and q projects back onto m (the same sheet, as in
// overlap_on_manifold). The point lies inside the thin triangle, so a second triangle over
// it covers that part of M twice. Well-shaped meshes have no such triangles and pay nothing.
// Dense problems only (below).
void check_thin_triangles(const MeshView& view, const GeometricInput& geometry,
                          const std::vector<std::pair<int, int>>& pairs, CheckStop& stop,
                          DefectRecorder& recorder, MeshValidation& result) {
  const MeshTopology& topology = view.topology;
  const std::vector<Triangle>& triangles = topology.triangles();
  const TriangleShapes& shapes = view.shapes;
  const auto points = view.mesh.points();
  const AmbientSpace& space = view.mesh.space();
  // Sparse (large n) problems are left out: seven projections per thin triangle are seven
  // factorisations there, and their meshes come from the atlas and the front (bezier's
  // continuation makes the thin triangles, and it does not run split).
  if (space.is_distributed() || geometry.problem.has_sparse_jacobian()) {
    return;
  }
  const int count = topology.triangle_count();
  constexpr double kThin = 10.0 * std::numbers::pi / 180.0;
  constexpr double kWide = 150.0 * std::numbers::pi / 180.0;
  std::vector<std::uint8_t> is_thin(count, 0);
  bool any = false;
  for (int t = 0; t < count; ++t) {
    if (!shapes.is_finite[t] || shapes.is_degenerate[t]) {
      continue;
    }
    const Triangle& tri = triangles[t];
    for (int k = 0; k < 3 && !is_thin[t]; ++k) {
      const double angle = corner_angle(points.col(tri[k]), points.col(tri[(k + 1) % 3]),
                                        points.col(tri[(k + 2) % 3]));
      is_thin[t] = angle < kThin || angle > kWide;
    }
    any = any || is_thin[t];
  }
  if (!any) {
    return;
  }
  std::vector<std::vector<int>> partners(count);
  for (const auto& [s, t] : pairs) {
    if (is_thin[s]) {
      partners[s].push_back(t);
    }
    if (is_thin[t]) {
      partners[t].push_back(s);
    }
  }
  std::set<std::pair<int, int>> known(result.overlapping_triangle_pairs.begin(),
                                      result.overlapping_triangle_pairs.end());
  const std::array<Eigen::Vector3d, 7> samples = {
      Eigen::Vector3d(1, 1, 1) / 3,     Eigen::Vector3d(0.8, 0.1, 0.1),
      Eigen::Vector3d(0.1, 0.8, 0.1),   Eigen::Vector3d(0.1, 0.1, 0.8),
      Eigen::Vector3d(0.5, 0.25, 0.25), Eigen::Vector3d(0.25, 0.5, 0.25),
      Eigen::Vector3d(0.25, 0.25, 0.5)};
  Linearization workspace;
  Linearization back;
  int sampled = 0;
  int to_sample = 0;
  for (int t = 0; t < count; ++t) {
    to_sample += is_thin[t] && !partners[t].empty() ? 1 : 0;
  }
  for (int t = 0; t < count; ++t) {
    if (!is_thin[t] || partners[t].empty()) {
      continue;
    }
    if (stop.is_stopped()) {
      result.checks_cut_short.push_back(
          "thin triangles on M: " + std::to_string(to_sample - sampled) + " of " +
          std::to_string(to_sample) + " not sampled");
      break;
    }
    ++sampled;
    const Triangle& tri = triangles[t];
    std::vector<int> found;
    for (const Eigen::Vector3d& w : samples) {
      Eigen::VectorXd m =
          w[0] * points.col(tri[0]) + w[1] * points.col(tri[1]) + w[2] * points.col(tri[2]);
      if (!project_onto_manifold(geometry.problem, m, workspace) || !workspace.is_factored()) {
        continue;
      }
      const Eigen::MatrixXd& T = workspace.tangent_basis();
      for (int s : partners[t]) {
        if (std::find(found.begin(), found.end(), s) != found.end() || !shapes.is_finite[s] ||
            shapes.is_degenerate[s]) {
          continue;
        }
        const Triangle& other = triangles[s];
        const Eigen::VectorXd a = points.col(other[0]);
        Eigen::MatrixXd E(a.size(), 2);
        E.col(0) = points.col(other[1]) - a;
        E.col(1) = points.col(other[2]) - a;
        const Eigen::Matrix2d TE = T.transpose() * E;
        if (!(std::abs(TE.determinant()) > 1e-3 * 2.0 * shapes.area[s])) {
          continue;  // s stands across M at m
        }
        const Eigen::Vector2d b = TE.inverse() * (T.transpose() * (m - a));
        if (std::min({1.0 - b.x() - b.y(), b.x(), b.y()}) <= 1e-3) {
          continue;
        }
        const Eigen::VectorXd q = a + E * b;
        Eigen::VectorXd m_back = q;
        if (!project_onto_manifold(geometry.problem, m_back, back) ||
            (m_back - m).norm() >
                0.25 * (q - m).norm() + 1e-10 * (1.0 + m.lpNorm<Eigen::Infinity>())) {
          continue;  // another sheet
        }
        found.push_back(s);
        const std::pair<int, int> pair = std::minmax(view.original[t], view.original[s]);
        if (!known.insert(pair).second) {
          continue;
        }
        result.overlapping_triangle_pairs.push_back(pair);
        recorder.record(MeshDefectKind::OverlappingTriangles, [&] {
          std::ostringstream out;
          out.precision(3);
          out << triangle_name(view.original[t], tri) << ", a thin triangle, and "
              << triangle_name(view.original[s], other) << " both cover M at "
              << describe_point(m, space) << " (sampled)";
          return out.str();
        });
      }
    }
  }
  std::sort(result.overlapping_triangle_pairs.begin(), result.overlapping_triangle_pairs.end());
}

}  // namespace tessera::detail
