// SPDX-License-Identifier: MIT
#include "tessera/methods/improvement/tangential_smoothing.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <sstream>
#include <vector>

#include "tessera/core/corrector.h"
#include "tessera/core/error.h"
#include "tessera/core/linearization.h"
#include "tessera/geometry/mesh_quality.h"
#include "tessera/geometry/mesh_topology.h"

namespace tessera {
namespace {


// Signed area of triangle t in the plane through `origin` with orthonormal basis T (n×2),
// divided by the squared longest edge there (a scale-free shape measure; 0.43 is equilateral).
double signed_area_ratio(const TriangleMesh& mesh, const Triangle& t, const Eigen::MatrixXd& T,
                         const Eigen::VectorXd& origin) {
  Eigen::Vector2d p[3];
  for (int k = 0; k < 3; ++k) {
    // Column by column: no temporary n-vector (this runs for every triangle of every star).
    p[k] = {T.col(0).dot(mesh.point(t[k]) - origin), T.col(1).dot(mesh.point(t[k]) - origin)};
  }
  const double area = 0.5 * ((p[1].x() - p[0].x()) * (p[2].y() - p[0].y()) -
                             (p[1].y() - p[0].y()) * (p[2].x() - p[0].x()));
  const double longest = std::max(
      {(p[0] - p[1]).squaredNorm(), (p[1] - p[2]).squaredNorm(), (p[2] - p[0]).squaredNorm()});
  return longest > 0 ? area / longest : 0.0;
}

}  // namespace

void SmoothingOptions::validate() const {
  TESSERA_CHECK(iterations >= 0,
                "SmoothingOptions::iterations = " << iterations << " must be >= 0");
  TESSERA_CHECK(relaxation > 0 && relaxation <= 1,
                "SmoothingOptions::relaxation = " << relaxation << " must be in (0, 1]");
  TESSERA_CHECK(min_area_ratio >= 0 && min_area_ratio < 0.4,
                "SmoothingOptions::min_area_ratio = " << min_area_ratio << " must be in [0, 0.4)");
}

std::string SmoothingSummary::brief_report() const {
  std::ostringstream out;
  out << moves << " moves in " << iterations << " passes; min angle " << min_angle_degrees_before
      << "° -> " << min_angle_degrees_after << "°";
  return out.str();
}

SmoothingSummary smooth_tangentially(TriangleMesh& mesh, const ImplicitProblem& problem,
                                     const SmoothingOptions& options) {
  TESSERA_CHECK(mesh.ambient_dimension() == problem.ambient_dimension(),
                "the mesh lives in R^" << mesh.ambient_dimension() << " but problem '"
                                       << problem.name() << "' in R^"
                                       << problem.ambient_dimension());
  options.validate();
  SmoothingSummary summary;
  if (options.measure_shapes) {
    summary.min_angle_degrees_before = measure_shape(mesh).min_angle_degrees;
  }
  const MeshTopology topology(mesh);
  // Boundary vertices and vertices of non-manifold edges stay where they are.
  std::vector<std::uint8_t> is_fixed(mesh.vertex_count(), 0);
  for (int e = 0; e < topology.edge_count(); ++e) {
    if (topology.edge_triangles(e).size() != 2) {
      is_fixed[topology.edge(e)[0]] = 1;
      is_fixed[topology.edge(e)[1]] = 1;
    }
  }
  const std::vector<Triangle>& triangles = mesh.triangles();
  Linearization at_old;
  Linearization at_new;
  const int n = mesh.ambient_dimension();
  // Kept across vertices: at n = 3 the allocations would cost more than the arithmetic.
  Eigen::VectorXd average(n);
  Eigen::VectorXd x(n);
  Eigen::VectorXd y(n);
  Eigen::VectorXd step(n);
  Eigen::MatrixXd T(n, 2);
  std::vector<double> sign_before;
  for (int pass = 0; pass < options.iterations; ++pass) {
    ++summary.iterations;
    for (int v = 0; v < mesh.vertex_count(); ++v) {
      const auto star = topology.vertex_triangles(v);
      if (is_fixed[v] || star.empty()) {
        continue;
      }
      x = mesh.point(v);
      // x̄: each neighbour appears in two triangles of a closed star, so the triangle-weighted
      // average of the other two corners is the plain average of the neighbours.
      average.setZero();
      double smallest_before = std::numbers::pi;
      for (const int t : star) {
        for (const int w : triangles[t]) {
          if (w != v) {
            average += mesh.point(w);
          }
        }
        smallest_before = std::min(smallest_before, min_angle(mesh, triangles[t]));
      }
      average /= 2.0 * static_cast<double>(star.size());
      if (!at_old.factor(problem, x)) {
        ++summary.rejected_projection;
        continue;
      }
      T = at_old.tangent_basis();
      step.noalias() = T * (T.transpose() * (average - x));
      step *= options.relaxation;
      y = x + step;
      CorrectorOptions corrector;
      corrector.max_displacement = std::max(step.norm(), 1e-300);
      // The chord of the factorisation at x: the move is a fraction of an edge, so it contracts
      // at once, without factoring at every iterate as Gauss–Newton would (the one factorisation
      // at y below is needed anyway, for the fold test in the tangent plane there).
      if (step.norm() == 0.0 || !project_chord(problem, at_old, y, corrector).is_success() ||
          !at_new.factor(problem, y, &T)) {
        ++summary.rejected_projection;
        continue;
      }
      // Orientation of each triangle of the star in the plane at x, before the move.
      sign_before.clear();
      for (const int t : star) {
        sign_before.push_back(signed_area_ratio(mesh, triangles[t], T, x) >= 0 ? 1.0 : -1.0);
      }
      mesh.mutable_point(v) = y;
      bool is_fold = false;
      double smallest_after = std::numbers::pi;
      for (std::size_t i = 0; i < star.size() && !is_fold; ++i) {
        const Triangle& triangle = triangles[star[i]];
        is_fold =
            !(sign_before[i] * signed_area_ratio(mesh, triangle, T, x) > options.min_area_ratio &&
              sign_before[i] * signed_area_ratio(mesh, triangle, at_new.tangent_basis(), y) >
                  options.min_area_ratio);
        smallest_after = std::min(smallest_after, min_angle(mesh, triangle));
      }
      if (is_fold) {
        mesh.mutable_point(v) = x;
        ++summary.rejected_fold;
        continue;
      }
      if (options.keep_min_angle && smallest_after < smallest_before) {
        mesh.mutable_point(v) = x;
        ++summary.rejected_angle;
        continue;
      }
      ++summary.moves;
    }
  }
  if (options.measure_shapes) {
    summary.min_angle_degrees_after = measure_shape(mesh).min_angle_degrees;
  }
  return summary;
}

}  // namespace tessera
