// SPDX-License-Identifier: MIT
// Whether a point of M is already covered by a mesh of several components, and by which: the
// test that decides whether a seed projected onto M starts a covering of its own.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "tessera/geometry/triangle_mesh.h"

namespace tessera {

/// The triangles of a growing mesh of several components, each component a range of
/// triangles, measured in the problem's metric.
///
/// A point x of M counts as covered by a component when one of its triangles passes within
/// kCoveredFraction × that triangle's longest edge (plus the distance bound of the run) of x.
/// A point of M inside a triangle's patch lies within the chord error κh²/8 of the flat
/// triangle, far below h/4 wherever h resolves the curvature κ (κh < 2); a point of another
/// component lies at least the gap between the two away. So two components nearer to each
/// other than a quarter of the local edge length are taken for one (docs/components.md).
class ComponentCoverage {
 public:
  static constexpr double kCoveredFraction = 0.25;

  /// \param mesh the mesh the components are appended to; it must outlive this object.
  /// \param weights the metric's weights w (‖x‖² = Σ (w_i x_i)²); empty: Euclidean.
  /// \param tolerance the run's distance bound ε ≥ 0 (0: none), added to the reach.
  ComponentCoverage(const TriangleMesh& mesh, Eigen::VectorXd weights, double tolerance);

  /// Declares the mesh's triangles from the end of the last component to the mesh's end as
  /// the next component (its index: the number added before).
  void add_component();
  int component_count() const { return static_cast<int>(component_ends_.size()); }

  /// The component covering x (an n-vector on M), or −1. The one of the nearest triangle
  /// within reach when several are.
  int covering_component(const Eigen::Ref<const Eigen::VectorXd>& x) const;

 private:
  // x in the metric's coordinates y = W x.
  Eigen::VectorXd scaled(const Eigen::Ref<const Eigen::VectorXd>& x) const;

  const TriangleMesh& mesh_;
  Eigen::VectorXd weights_;
  double tolerance_;
  std::vector<int> component_ends_;    ///< one past the last triangle of each component
  std::vector<double> longest_edges_;  ///< per triangle, in the metric
  double longest_edge_ = 0.0;          ///< over all triangles
};

/// The point of the triangle (a, b, c) nearest to p, in any dimension (Ericson, Real-Time
/// Collision Detection, 5.1.5: only dot products, so it holds in R^n).
Eigen::VectorXd closest_point_on_triangle(const Eigen::Ref<const Eigen::VectorXd>& p,
                                          const Eigen::Ref<const Eigen::VectorXd>& a,
                                          const Eigen::Ref<const Eigen::VectorXd>& b,
                                          const Eigen::Ref<const Eigen::VectorXd>& c);

}  // namespace tessera
