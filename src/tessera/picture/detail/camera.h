// SPDX-License-Identifier: MIT
// Internal to the picture module: the camera of the surface pictures, the map from scene
// coordinates to pixels and depth (the aspect's scaling of the axes, the rotation to the view
// direction, perspective, and the fit to a frame of the picture).
#pragma once

#include <Eigen/Core>

#include "tessera/picture/picture.h"

namespace tessera::picture_detail {

/// A rectangle of the picture in pixels (x right, y down).
struct Rect {
  double x0 = 0, y0 = 0, x1 = 0, y1 = 0;
  double width() const { return x1 - x0; }
  double height() const { return y1 - y0; }
  bool intersects(const Rect& other, double gap = 0.0) const {
    return x0 < other.x1 + gap && other.x0 < x1 + gap && y0 < other.y1 + gap && other.y0 < y1 + gap;
  }
  bool contains(const Rect& other) const {
    return other.x0 >= x0 && other.x1 <= x1 && other.y0 >= y0 && other.y1 <= y1;
  }
};

class Camera {
 public:
  /// Looks from (cos e cos a, cos e sin a, sin e) at the centre of the bounding box of
  /// `positions` (3×V, V ≥ 1), a = azimuth, e = elevation in degrees, after scaling the axes
  /// as `aspect` says (the box becomes at most a unit cube). Call fit() before pixel().
  Camera(const Eigen::Matrix3Xd& positions, PictureAspect aspect, double azimuth_degrees,
         double elevation_degrees, bool perspective);

  /// Places the camera so that the projected extent of `points` (3×m) fills `fraction`·zoom of
  /// `frame`, centred in it.
  void fit(const Eigen::Matrix3Xd& points, const Rect& frame, double zoom, double fraction = 0.92);

  /// A scene point in the scaled space (the aspect's scaling about the box's centre).
  Eigen::Vector3d scaled(const Eigen::Vector3d& p) const {
    return scale_.cwiseProduct(p - centre_);
  }
  /// (right, up, depth toward the eye) of a scene point, before the fit to the frame.
  Eigen::Vector3d screen(const Eigen::Vector3d& p) const;
  /// Pixel coordinates (x right, y down).
  Eigen::Vector2d pixel(const Eigen::Vector3d& p) const;
  double depth(const Eigen::Vector3d& p) const { return screen(p)(2); }
  /// |cos| of the angle between the eye direction and the normal of the triangle (a, b, c) in
  /// the scaled space (what the eye sees); 0 for a degenerate triangle.
  double facing(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c) const;
  /// The screen direction (right, up) of axis k, unit length in the scaled space.
  Eigen::Vector2d axis_direction(int k) const;
  /// The direction toward the eye in the scene's (unscaled) axes' orientation.
  const Eigen::Vector3d& toward_eye() const { return toward_eye_; }
  /// The bounding box of the positions.
  const Eigen::Vector3d& lower() const { return lower_; }
  const Eigen::Vector3d& upper() const { return upper_; }
  double pixels_per_unit() const { return pixels_per_unit_; }

 private:
  bool perspective_;
  Eigen::Vector3d lower_, upper_;
  Eigen::Vector3d centre_;
  Eigen::Vector3d scale_;
  Eigen::Vector3d toward_eye_, right_, up_;
  Eigen::Vector2d middle_ = Eigen::Vector2d::Zero();
  Eigen::Vector2d frame_centre_ = Eigen::Vector2d::Zero();
  double pixels_per_unit_ = 1.0;
};

}  // namespace tessera::picture_detail
