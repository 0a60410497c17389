// SPDX-License-Identifier: MIT
#include "tessera/picture/detail/camera.h"

#include "tessera/picture/picture.h"

#include <Eigen/Geometry>
#include <numbers>
#include <algorithm>
#include <cmath>

namespace tessera::picture_detail {

namespace {


struct Extents {
  Eigen::Vector3d lower, upper, extent;
  double largest = 0, smallest = 0;
};

Extents extents_of(const Eigen::Matrix3Xd& positions) {
  Extents e;
  e.lower = positions.rowwise().minCoeff();
  e.upper = positions.rowwise().maxCoeff();
  e.extent = e.upper - e.lower;
  e.largest = std::max(e.extent.maxCoeff(), 1e-300);
  e.smallest = e.largest;
  for (int k = 0; k < 3; ++k) {
    if (e.extent(k) > 1e-12 * e.largest) {
      e.smallest = std::min(e.smallest, e.extent(k));
    }
  }
  return e;
}

}  // namespace

}  // namespace tessera::picture_detail

namespace tessera {

bool has_axes_scaled_apart(const Eigen::Matrix3Xd& positions, PictureAspect aspect) {
  if (aspect != PictureAspect::Automatic || positions.cols() == 0) {
    return aspect == PictureAspect::Box;
  }
  const picture_detail::Extents e = picture_detail::extents_of(positions);
  return e.largest > tessera::kMaxEqualAspectRatio * e.smallest;
}

}  // namespace tessera

namespace tessera::picture_detail {

Camera::Camera(const Eigen::Matrix3Xd& positions, PictureAspect aspect, double azimuth_degrees,
               double elevation_degrees, bool perspective)
    : perspective_(perspective) {
  const Extents e = extents_of(positions);
  lower_ = e.lower;
  upper_ = e.upper;
  centre_ = 0.5 * (lower_ + upper_);
  const bool is_box = has_axes_scaled_apart(positions, aspect);
  for (int k = 0; k < 3; ++k) {
    scale_(k) = is_box && e.extent(k) > 1e-12 * e.largest ? 1.0 / e.extent(k) : 1.0 / e.largest;
  }
  const double a = azimuth_degrees * std::numbers::pi / 180.0;
  const double el = elevation_degrees * std::numbers::pi / 180.0;
  toward_eye_ =
      Eigen::Vector3d(std::cos(el) * std::cos(a), std::cos(el) * std::sin(a), std::sin(el));
  right_ = Eigen::Vector3d(-std::sin(a), std::cos(a), 0.0);
  up_ = toward_eye_.cross(right_);
}

void Camera::fit(const Eigen::Matrix3Xd& points, const Rect& frame, double zoom, double fraction) {
  Eigen::Vector2d low(INFINITY, INFINITY), high(-INFINITY, -INFINITY);
  for (Eigen::Index i = 0; i < points.cols(); ++i) {
    const Eigen::Vector3d s = screen(points.col(i));
    low = low.cwiseMin(s.head<2>());
    high = high.cwiseMax(s.head<2>());
  }
  if (points.cols() == 0) {
    low.setZero();
    high.setOnes();
  }
  const Eigen::Vector2d range = (high - low).cwiseMax(1e-12);
  pixels_per_unit_ =
      zoom * fraction * std::min(frame.width() / range(0), frame.height() / range(1));
  middle_ = 0.5 * (low + high);
  frame_centre_ = Eigen::Vector2d(0.5 * (frame.x0 + frame.x1), 0.5 * (frame.y0 + frame.y1));
}

Eigen::Vector3d Camera::screen(const Eigen::Vector3d& p) const {
  const Eigen::Vector3d q = scale_.cwiseProduct(p - centre_);
  Eigen::Vector3d s(q.dot(right_), q.dot(up_), q.dot(toward_eye_));
  if (perspective_) {
    // The eye at 2.5 units (the normalised scene is within √3/2 of its centre).
    constexpr double eye = 2.5;
    const double factor = eye / (eye - s(2));
    s(0) *= factor;
    s(1) *= factor;
  }
  return s;
}

Eigen::Vector2d Camera::pixel(const Eigen::Vector3d& p) const {
  const Eigen::Vector3d s = screen(p);
  return {frame_centre_(0) + pixels_per_unit_ * (s(0) - middle_(0)),
          frame_centre_(1) - pixels_per_unit_ * (s(1) - middle_(1))};
}

double Camera::facing(const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                      const Eigen::Vector3d& c) const {
  const Eigen::Vector3d qa = scale_.cwiseProduct(a), qb = scale_.cwiseProduct(b),
                        qc = scale_.cwiseProduct(c);
  const Eigen::Vector3d normal = (qb - qa).cross(qc - qa);
  const double norm = normal.norm();
  return norm > 0 ? std::abs(normal.dot(toward_eye_)) / norm : 0.0;
}

Eigen::Vector2d Camera::axis_direction(int k) const {
  Eigen::Vector3d e = Eigen::Vector3d::Zero();
  e(k) = 1.0;
  return {e.dot(right_), e.dot(up_)};
}

}  // namespace tessera::picture_detail
