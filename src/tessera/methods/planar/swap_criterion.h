// SPDX-License-Identifier: MIT
// Criteria that decide which diagonal of a convex quadrilateral a triangulation should use
// (Malcolm's survey of Delaunay, minimum-weight and Dyn–Levin–Rippa's data-dependent costs).
#pragma once

#include <array>
#include <memory>
#include <optional>
#include <string>
#include <string_view>

#include "tessera/methods/planar/planar_triangulation.h"

namespace tessera {

/// How cost vectors are compared (Malcolm section 2): by their l1 norm, their l2 norm, or
/// lexicographically after sorting into non-increasing order. For the vector-valued edge costs
/// (PF, PD) it also names the norm of the edge's own vector: l1, l2, or max for lexicographic.
enum class CostOrdering { L1, L2, Lexicographic };

/// Which costs a swap compares (Malcolm section 5(a)): the diagonal alone ("local"), or the
/// diagonal and the four outer edges of the quadrilateral ("global", Dyn, Levin and Rippa).
/// With the global test every swap lowers the total cost of the triangulation in the chosen
/// ordering, which is what guarantees termination; the local test has no such guarantee.
enum class SwapTest { Local, Global };

/// The criteria of Malcolm section 4 that need only the data. EQUID (approximate
/// equidistribution) needs the function's second derivatives too: EquidistributionCriterion.
enum class CriterionKind {
  Delaunay,                 ///< max-min angle of the triangles in the plane
  MinimumWeight,            ///< MWT: length of the edge in the plane
  MaxMinAngle3d,            ///< max-min angle of the triangles lifted to (x, y, z)
  MinimumWeight3d,          ///< MWT-3D: length of the lifted edge
  AngleBetweenNormals,      ///< ABN: angle between the normals of the two lifted triangles
  JumpInNormalDerivatives,  ///< JND: jump of the derivative across the edge, normal to it
  PlaneFit,                 ///< PF: vertical misfit of each plane at the opposite vertex
  PlaneDistance,            ///< PD: distance of each plane to the opposite lifted vertex
};

/// Short names as in the report and on the command line: delaunay, mwt, maxmin3d, mwt3d, abn,
/// jnd, pf, pd.
std::string to_string(CriterionKind kind);
std::optional<CriterionKind> parse_criterion(std::string_view name);

/// A swap criterion. Either a cost per interior edge (lower is better), or, for the max-min
/// angle criteria, the angles of each triangle (a larger smallest angle is better).
class SwapCriterion {
 public:
  enum class Kind { EdgeCost, TriangleAngles };

  virtual ~SwapCriterion() = default;
  virtual std::string name() const = 0;
  virtual Kind kind() const = 0;
  /// Cost ≥ 0 of the interior edge q.a–q.b between triangles (a, b, c) and (b, a, d).
  /// `norm` combines the two parts of PF and PD (see CostOrdering); others ignore it.
  /// Only called when kind() == Kind::EdgeCost.
  virtual double edge_cost(const PlanarTriangulation& triangulation, const EdgeQuadrilateral& q,
                           CostOrdering norm) const;
  /// The three angles (radians) of the counter-clockwise triangle (a, b, c).
  /// Only called when kind() == Kind::TriangleAngles.
  virtual std::array<double, 3> triangle_angles(const PlanarTriangulation& triangulation, int a,
                                                int b, int c) const;
};

/// The criterion of `kind`.
std::unique_ptr<SwapCriterion> make_criterion(CriterionKind kind);

/// Gradient (a, b) of the linear interpolant f = a x + b y + c of the values on triangle
/// (p, q, r). \pre the triangle is not degenerate.
Eigen::Vector2d linear_gradient(const PlanarTriangulation& triangulation, int p, int q, int r);

}  // namespace tessera
