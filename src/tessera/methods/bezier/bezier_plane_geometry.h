// SPDX-License-Identifier: MIT
// The plane geometry of Hohmann's continuation (ZIB SC 91-20, section 5, "Projections and
// barycentric coordinates"): a frame of the plane through three points of R^n, barycentric
// coordinates and the overlap test of triangles in it, and the edge tangents of eq. 3.4 ii.
#pragma once

#include <Eigen/Core>
#include <array>

namespace tessera::detail {

/// An orthonormal frame of the plane through three points: e1 along p1 − p0, e2 by one
/// Gram–Schmidt step. `valid` is false where the points are (nearly) collinear.
struct PlaneFrame {
  Eigen::VectorXd origin, e1, e2;
  bool valid = false;

  PlaneFrame(const Eigen::VectorXd& p0, const Eigen::VectorXd& p1, const Eigen::VectorXd& p2);
  /// y's coordinates in the plane.
  Eigen::Vector2d project(const Eigen::VectorXd& y) const;
  /// Distance of y from the plane.
  double offset(const Eigen::VectorXd& y) const;
};

/// Barycentric coordinates of p with respect to the 2-D triangle (A, B, C); NaN if it is flat.
Eigen::Vector3d barycentric(const Eigen::Vector2d& p, const Eigen::Vector2d& A,
                            const Eigen::Vector2d& B, const Eigen::Vector2d& C);

/// True if the interiors of two 2-D triangles, each shrunk slightly towards its centroid (so
/// that triangles sharing a vertex or an edge do not count), intersect (separating-axis test
/// over the six edge normals).
bool triangles_overlap(std::array<Eigen::Vector2d, 3> P, std::array<Eigen::Vector2d, 3> Q);

/// t_ij of eq. 3.4 ii: the normed projection of y_j − y_i onto the tangent plane (n×2 basis
/// T_i) at y_i.
Eigen::VectorXd edge_tangent(const Eigen::MatrixXd& T_i, const Eigen::VectorXd& y_i,
                             const Eigen::VectorXd& y_j);

}  // namespace tessera::detail
