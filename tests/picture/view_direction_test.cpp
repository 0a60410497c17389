// SPDX-License-Identifier: MIT
// best_view_direction (view_direction.h): a sheet folded into an S is seen along its folds, where
// all three sheets show; a sphere, the same from everywhere, keeps the default.
#include "tessera/picture/view_direction.h"

#include <gtest/gtest.h>

#include <cmath>

namespace tessera {
namespace {

constexpr double kPi = 3.14159265358979323846;

// The S-shaped sheet x = s³ − s, z = s over s ∈ [−1.3, 1.3], extruded along y ∈ [0, 1]: over
// |x| < 0.38 three sheets lie above each other in z; its folds (s = ±1/√3) run along y.
PictureScene folded_sheet() {
  constexpr int ns = 60, nt = 20;
  PictureScene scene;
  scene.positions.resize(3, (ns + 1) * (nt + 1));
  for (int j = 0; j <= nt; ++j) {
    for (int i = 0; i <= ns; ++i) {
      const double s = -1.3 + 2.6 * i / ns;
      scene.positions.col(j * (ns + 1) + i) = Eigen::Vector3d(s * s * s - s, 1.0 * j / nt, s);
    }
  }
  for (int j = 0; j < nt; ++j) {
    for (int i = 0; i < ns; ++i) {
      const int v = j * (ns + 1) + i;
      scene.triangles.push_back({v, v + 1, v + ns + 2});
      scene.triangles.push_back({v, v + ns + 2, v + ns + 1});
    }
  }
  return scene;
}

TEST(ViewDirection, AFoldedSheetIsSeenAlongItsFolds) {
  const ViewDirection view = best_view_direction(folded_sheet(), PictureAspect::Automatic);
  // Along y: the azimuth within 35° of ±90° (cos a small), from above the x–y plane.
  const double a = view.azimuth_degrees * kPi / 180.0;
  EXPECT_LT(std::abs(std::cos(a)), std::sin(35.0 * kPi / 180.0))
      << view.azimuth_degrees << ", " << view.elevation_degrees;
  EXPECT_GE(view.elevation_degrees, 10.0);
  EXPECT_LE(view.elevation_degrees, 50.0);
}

TEST(ViewDirection, ASphereKeepsTheDefault) {
  constexpr int n = 24;
  PictureScene scene;
  scene.positions.resize(3, n * (n + 1));
  for (int j = 0; j <= n; ++j) {
    for (int i = 0; i < n; ++i) {
      const double theta = kPi * j / n, phi = 2 * kPi * i / n;
      scene.positions.col(j * n + i) = Eigen::Vector3d(
          std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta));
    }
  }
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      const int v = j * n + i, right = j * n + (i + 1) % n;
      scene.triangles.push_back({v, right, right + n});
      scene.triangles.push_back({v, right + n, v + n});
    }
  }
  const ViewDirection view = best_view_direction(scene, PictureAspect::Automatic);
  EXPECT_EQ(view.azimuth_degrees, -60.0);
  EXPECT_EQ(view.elevation_degrees, 30.0);
}

}  // namespace
}  // namespace tessera
