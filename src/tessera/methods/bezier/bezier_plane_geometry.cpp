// SPDX-License-Identifier: MIT
#include "tessera/methods/bezier/bezier_plane_geometry.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "tessera/methods/bezier/bezier_builder.h"

namespace tessera::detail {
namespace {

// Triangles are shrunk by this fraction towards their centroids before the overlap test, so
// that triangles sharing a vertex or an edge do not count as overlapping.
constexpr double kOverlapShrink = 1e-4;

}  // namespace

PlaneFrame::PlaneFrame(const Eigen::VectorXd& p0, const Eigen::VectorXd& p1,
                       const Eigen::VectorXd& p2)
    : origin(p0) {
  e1 = p1 - p0;
  const double alpha = e1.norm();
  if (!(alpha > 0)) {
    return;
  }
  e1 /= alpha;
  e2 = p2 - p0;
  e2 -= e1.dot(e2) * e1;
  const double gamma = e2.norm();
  if (!(gamma > 1e-14 * alpha)) {
    return;
  }
  e2 /= gamma;
  valid = true;
}

Eigen::Vector2d PlaneFrame::project(const Eigen::VectorXd& y) const {
  const Eigen::VectorXd d = y - origin;
  return {d.dot(e1), d.dot(e2)};
}

double PlaneFrame::offset(const Eigen::VectorXd& y) const {
  const Eigen::VectorXd d = y - origin;
  return (d - d.dot(e1) * e1 - d.dot(e2) * e2).norm();
}

Eigen::Vector3d barycentric(const Eigen::Vector2d& p, const Eigen::Vector2d& A,
                            const Eigen::Vector2d& B, const Eigen::Vector2d& C) {
  const double area = cross(B - A, C - A);
  if (std::abs(area) < 1e-300) {
    return Eigen::Vector3d::Constant(std::numeric_limits<double>::quiet_NaN());
  }
  const double lb = cross(p - A, C - A) / area;
  const double lc = cross(B - A, p - A) / area;
  return {1.0 - lb - lc, lb, lc};
}

bool triangles_overlap(std::array<Eigen::Vector2d, 3> P, std::array<Eigen::Vector2d, 3> Q) {
  for (auto* T : {&P, &Q}) {
    const Eigen::Vector2d c = ((*T)[0] + (*T)[1] + (*T)[2]) / 3.0;
    for (auto& v : *T) {
      v = c + (1.0 - kOverlapShrink) * (v - c);
    }
  }
  for (const auto* T : {&P, &Q}) {
    for (int i = 0; i < 3; ++i) {
      const Eigen::Vector2d edge = (*T)[(i + 1) % 3] - (*T)[i];
      const Eigen::Vector2d axis(-edge(1), edge(0));
      double pmin = std::numeric_limits<double>::infinity(), pmax = -pmin;
      double qmin = pmin, qmax = -pmin;
      for (int k = 0; k < 3; ++k) {
        pmin = std::min(pmin, axis.dot(P[k]));
        pmax = std::max(pmax, axis.dot(P[k]));
        qmin = std::min(qmin, axis.dot(Q[k]));
        qmax = std::max(qmax, axis.dot(Q[k]));
      }
      if (pmax <= qmin || qmax <= pmin) {
        return false;
      }
    }
  }
  return true;
}

Eigen::VectorXd edge_tangent(const Eigen::MatrixXd& T_i, const Eigen::VectorXd& y_i,
                             const Eigen::VectorXd& y_j) {
  Eigen::VectorXd t = T_i * (T_i.transpose() * (y_j - y_i));
  const double norm = t.norm();
  return norm > 0 ? Eigen::VectorXd(t / norm) : t;
}

}  // namespace tessera::detail
