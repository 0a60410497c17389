// SPDX-License-Identifier: MIT
#include "tessera/picture/view_direction.h"

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>

#include <numbers>
#include <algorithm>
#include <cmath>
#include <vector>

#include "tessera/picture/detail/camera.h"

namespace tessera {

namespace {

constexpr int kPixels = 160;         // the depth buffer's side
constexpr double kMaxStretch = 4.0;  // a pixel stands for at most this much surface

double cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return a(0) * b(1) - a(1) * b(0);
}

// The area of surface seen from `view`: what a depth buffer shows, each pixel counting the
// surface it stands for (1/|cos| of its triangle's angle to the eye, at most kMaxStretch).
double seen_area(const PictureScene& scene, PictureAspect aspect, const ViewDirection& view,
                 std::vector<double>& depth, std::vector<int>& owner) {
  const picture_detail::Camera camera(scene.positions, aspect, view.azimuth_degrees,
                                      view.elevation_degrees, false);
  // A fixed scale for every direction (the scaled scene lies within √3/2 of its centre), so
  // that areas and lengths compare across directions.
  const double scale = kPixels / std::sqrt(3.0);
  const auto vertex_count = scene.positions.cols();
  Eigen::Matrix3Xd screen(3, vertex_count);
  for (Eigen::Index v = 0; v < vertex_count; ++v) {
    const Eigen::Vector3d s = camera.screen(scene.positions.col(v));
    screen.col(v) =
        Eigen::Vector3d(kPixels / 2.0 + scale * s(0), kPixels / 2.0 - scale * s(1), s(2));
  }
  std::fill(depth.begin(), depth.end(), -INFINITY);
  std::fill(owner.begin(), owner.end(), -1);
  for (std::size_t t = 0; t < scene.triangles.size(); ++t) {
    const auto& [a, b, c] = scene.triangles[t];
    const Eigen::Vector2d pa = screen.col(a).head<2>(), pb = screen.col(b).head<2>(),
                          pc = screen.col(c).head<2>();
    const double area = cross(pb - pa, pc - pa);
    if (std::abs(area) < 1e-12) {
      continue;
    }
    const int x0 = std::max(0, static_cast<int>(std::floor(std::min({pa(0), pb(0), pc(0)}))));
    const int x1 =
        std::min(kPixels - 1, static_cast<int>(std::ceil(std::max({pa(0), pb(0), pc(0)}))));
    const int y0 = std::max(0, static_cast<int>(std::floor(std::min({pa(1), pb(1), pc(1)}))));
    const int y1 =
        std::min(kPixels - 1, static_cast<int>(std::ceil(std::max({pa(1), pb(1), pc(1)}))));
    for (int y = y0; y <= y1; ++y) {
      for (int x = x0; x <= x1; ++x) {
        const Eigen::Vector2d p(x + 0.5, y + 0.5);
        const double u = cross(pb - p, pc - p) / area;
        const double v = cross(pc - p, pa - p) / area;
        const double w = 1.0 - u - v;
        if (u < 0 || v < 0 || w < 0) {
          continue;
        }
        const double z = u * screen(2, a) + v * screen(2, b) + w * screen(2, c);
        const auto pixel = static_cast<std::size_t>(y * kPixels + x);
        if (z > depth[pixel]) {
          depth[pixel] = z;
          owner[pixel] = static_cast<int>(t);
        }
      }
    }
  }
  std::vector<double> stretch(scene.triangles.size(), 0.0);
  for (std::size_t t = 0; t < scene.triangles.size(); ++t) {
    const auto& [a, b, c] = scene.triangles[t];
    const double facing =
        camera.facing(scene.positions.col(a), scene.positions.col(b), scene.positions.col(c));
    stretch[t] = std::min(kMaxStretch, 1.0 / std::max(facing, 1e-12));
  }
  double area = 0.0;
  for (const int t : owner) {
    if (t >= 0) {
      area += stretch[static_cast<std::size_t>(t)];
    }
  }
  return area;
}

// A preference between directions that show about as much: both horizontal axes readable
// (neither seen end-on).
double preference(const ViewDirection& view) {
  const double a = view.azimuth_degrees * std::numbers::pi / 180.0;
  return 0.85 + 0.15 * std::min(1.0, 2.0 * std::min(std::abs(std::sin(a)), std::abs(std::cos(a))));
}

}  // namespace

ViewDirection best_view_direction(const PictureScene& scene, PictureAspect aspect) {
  if (scene.triangles.empty() || scene.positions.cols() == 0) {
    return {};
  }
  // The folds: where the tangent plane stands vertical (contains the third axis), the sheets
  // above a point of the plane of the first two axes meet and turn back. The horizontal normals
  // there, weighted by area, give the direction across the folds (their principal axis).
  const picture_detail::Camera scaled(scene.positions, aspect, 0.0, 90.0, false);  // from above
  Eigen::Matrix2d across = Eigen::Matrix2d::Zero();
  double total_area = 0.0;
  for (const Triangle& triangle : scene.triangles) {
    const Eigen::Vector3d a = scaled.scaled(scene.positions.col(triangle[0]));
    const Eigen::Vector3d b = scaled.scaled(scene.positions.col(triangle[1]));
    const Eigen::Vector3d c = scaled.scaled(scene.positions.col(triangle[2]));
    const Eigen::Vector3d normal = (b - a).cross(c - a);
    const double area = 0.5 * normal.norm();
    if (!(area > 0)) {
      continue;
    }
    total_area += area;
    const Eigen::Vector3d n = normal.normalized();
    constexpr double kVertical = 0.25;  // |n_z| below this: a tangent plane within 14° of vertical
    const double weight = area * std::max(0.0, 1.0 - std::abs(n(2)) / kVertical);
    across += weight * n.head<2>() * n.head<2>().transpose();
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> principal(across);
  const Eigen::Vector2d spread = principal.eigenvalues();  // increasing
  // No folds, or folds facing every way alike (a sphere's equator): nothing to choose by.
  if (!(spread(1) > 1e-3 * total_area) || spread(1) < 1.5 * spread(0)) {
    return {};
  }
  const Eigen::Vector2d normal = principal.eigenvectors().col(1);
  const double along = std::atan2(normal(0), -normal(1)) * 180.0 / std::numbers::pi;  // the folds' direction
  // Look along the folds, 30° aside so that they do not shrink to points, from above the plane
  // of the first two axes: the sheets' S shows at the near end. Of the four such directions and
  // three elevations, the one that shows the most surface.
  std::vector<double> depth(static_cast<std::size_t>(kPixels * kPixels));
  std::vector<int> owner(depth.size());
  ViewDirection best;
  double best_score = -INFINITY;
  for (const double base : {along, along + 180.0}) {
    for (const double aside : {-30.0, 30.0}) {
      for (const double elevation : {20.0, 30.0, 40.0}) {
        const ViewDirection view{std::remainder(base + aside, 360.0), elevation};
        const double score = seen_area(scene, aspect, view, depth, owner) * preference(view);
        if (score > best_score) {
          best_score = score;
          best = view;
        }
      }
    }
  }
  return best;
}

}  // namespace tessera
