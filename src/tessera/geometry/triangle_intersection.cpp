// SPDX-License-Identifier: MIT
#include "tessera/geometry/triangle_intersection.h"

#include <algorithm>
#include <array>
#include <utility>

namespace tessera {
namespace {

// Twice the signed area of (p, q, r): > 0 when counter-clockwise.
double cross(const Eigen::Vector2d& p, const Eigen::Vector2d& q, const Eigen::Vector2d& r) {
  return (q.x() - p.x()) * (r.y() - p.y()) - (q.y() - p.y()) * (r.x() - p.x());
}

// A convex polygon of at most 3 + 3 vertices (each clip adds at most one vertex).
struct Polygon {
  std::array<Eigen::Vector2d, 9> vertices;
  int size = 0;
};

}  // namespace

PlanarOverlap triangle_intersection(const Eigen::Matrix<double, 2, 3>& a,
                                    const Eigen::Matrix<double, 2, 3>& b) {
  PlanarOverlap overlap;
  const double a_orientation = cross(a.col(0), a.col(1), a.col(2));
  const double b_orientation = cross(b.col(0), b.col(1), b.col(2));
  if (a_orientation == 0.0 || b_orientation == 0.0) {
    return overlap;
  }
  Polygon polygon;
  for (int k = 0; k < 3; ++k) {
    polygon.vertices[polygon.size++] = a.col(a_orientation > 0 ? k : 2 - k);
  }
  // b counter-clockwise: its interior lies left of each edge.
  std::array<Eigen::Vector2d, 3> clip;
  for (int k = 0; k < 3; ++k) {
    clip[k] = b.col(b_orientation > 0 ? k : 2 - k);
  }
  for (int k = 0; k < 3 && polygon.size > 0; ++k) {
    const Eigen::Vector2d& p = clip[k];
    const Eigen::Vector2d& q = clip[(k + 1) % 3];
    Polygon clipped;
    for (int i = 0; i < polygon.size; ++i) {
      const Eigen::Vector2d& u = polygon.vertices[i];
      const Eigen::Vector2d& w = polygon.vertices[(i + 1) % polygon.size];
      const double su = cross(p, q, u);
      const double sw = cross(p, q, w);
      if (su >= 0) {
        clipped.vertices[clipped.size++] = u;
      }
      if ((su >= 0) != (sw >= 0)) {
        // su and sw have opposite signs, so su − sw ≠ 0 and the weight lies in [0, 1].
        clipped.vertices[clipped.size++] = u + (su / (su - sw)) * (w - u);
      }
    }
    polygon = clipped;
  }
  if (polygon.size < 3) {
    return overlap;
  }
  // Shoelace about the first vertex (smaller rounding than about the origin).
  const Eigen::Vector2d& origin = polygon.vertices[0];
  double twice_area = 0.0;
  Eigen::Vector2d moment = Eigen::Vector2d::Zero();
  for (int i = 1; i + 1 < polygon.size; ++i) {
    const double fan = cross(origin, polygon.vertices[i], polygon.vertices[i + 1]);
    twice_area += fan;
    moment += fan * (origin + polygon.vertices[i] + polygon.vertices[i + 1]) / 3.0;
  }
  if (twice_area <= 0.0) {
    return overlap;
  }
  overlap.area = 0.5 * twice_area;
  overlap.centroid = moment / twice_area;
  for (int i = 0; i < polygon.size; ++i) {
    overlap.perimeter += (polygon.vertices[(i + 1) % polygon.size] - polygon.vertices[i]).norm();
    overlap.reach = std::max(overlap.reach, polygon.vertices[i].norm());
  }
  return overlap;
}

}  // namespace tessera
