// SPDX-License-Identifier: MIT
// Delaunay triangulation of scattered points in the plane (CGAL, exact predicates).
// This is the only file of tessera that includes CGAL: its headers are heavy.
#include "tessera/methods/planar/delaunay.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <utility>
#include <vector>

#include <CGAL/Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#include "tessera/core/error.h"

namespace tessera {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using VertexBase = CGAL::Triangulation_vertex_base_with_info_2<int, Kernel>;
using DataStructure =
    CGAL::Triangulation_data_structure_2<VertexBase, CGAL::Triangulation_face_base_2<Kernel>>;
using Delaunay = CGAL::Delaunay_triangulation_2<Kernel, DataStructure>;

Kernel::Point_2 cgal_point(const PlanarTriangulation& triangulation, int vertex) {
  return {triangulation.point(vertex).x(), triangulation.point(vertex).y()};
}

// True if d lies exactly on the circumcircle of the triangle (a, b, c) (exact predicate).
bool is_cocircular(const PlanarTriangulation& triangulation, const EdgeQuadrilateral& q) {
  return CGAL::side_of_oriented_circle(
             cgal_point(triangulation, q.a), cgal_point(triangulation, q.b),
             cgal_point(triangulation, q.c),
             cgal_point(triangulation, q.d)) == CGAL::ON_ORIENTED_BOUNDARY;
}

// The input-order rule (see the header): among the Delaunay triangulations, the one in which
// every cocircular quadrilateral's diagonal avoids its node with the largest index. This is
// the Delaunay triangulation of the points lifted to the paraboloid with node i raised by
// ε^(N−i) (ε → 0), which is unique; Lawson's flips with that perturbed in-circle test reach it
// from any Delaunay triangulation and end, because each flip lowers the perturbed lifted
// surface. Only exactly cocircular quadrilaterals are affected: for all others the exact
// in-circle test already decides, and the perturbation cannot change its sign.
DelaunaySummary apply_input_order_rule(PlanarTriangulation& triangulation) {
  DelaunaySummary summary;
  // Each swap lowers the perturbed surface, so no triangulation repeats; the cap only guards
  // against a broken invariant (it ends the loop in release builds too).
  const int max_swaps = 10 * triangulation.triangle_count() + 10;
  bool swapped = true;
  while (swapped && summary.rule_swaps <= max_swaps) {
    swapped = false;
    for (int t = 0; t < triangulation.triangle_count(); ++t) {
      for (int k = 0; k < 3; ++k) {
        if (!triangulation.is_interior_edge(t, k)) {
          continue;
        }
        const EdgeQuadrilateral q = triangulation.quadrilateral(t, k);
        if (!is_cocircular(triangulation, q)) {
          continue;
        }
        const int last = std::max({q.a, q.b, q.c, q.d});
        // Four distinct points on a circle form a strictly convex quadrilateral; the validity
        // check (relative tolerance) can refuse only a nearly flat corner, where we keep
        // CGAL's diagonal rather than create a sliver.
        if ((last == q.a || last == q.b) && triangulation.is_swap_valid(t, k)) {
          triangulation.swap(t, k);
          ++summary.rule_swaps;
          swapped = true;
          TESSERA_ASSERT(summary.rule_swaps <= max_swaps);
        }
      }
    }
  }
  for (int t = 0; t < triangulation.triangle_count(); ++t) {
    for (int k = 0; k < 3; ++k) {
      const int u = triangulation.neighbour(t, k);
      if (u > t && is_cocircular(triangulation, triangulation.quadrilateral(t, k))) {
        ++summary.cocircular_edges;
      }
    }
  }
  return summary;
}

}  // namespace

PlanarTriangulation delaunay_triangulation(const Eigen::Ref<const Eigen::Matrix2Xd>& points,
                                           const Eigen::Ref<const Eigen::VectorXd>& values,
                                           DelaunaySummary* summary) {
  const auto n = static_cast<int>(points.cols());
  TESSERA_CHECK(n >= 3, "delaunay_triangulation: " << n << " points; need at least 3");
  TESSERA_CHECK(values.size() == 0 || values.size() == n,
                "delaunay_triangulation: " << values.size() << " values for " << n
                                           << " points; need one per point (or none)");
  for (int i = 0; i < n; ++i) {
    TESSERA_CHECK(points.col(i).allFinite(), "delaunay_triangulation: point "
                                                 << i << " = (" << points(0, i) << ", "
                                                 << points(1, i) << ") is not finite");
  }
  // Equal points: CGAL would merge them silently, leaving a value without a vertex.
  std::vector<int> order(n);
  std::iota(order.begin(), order.end(), 0);
  const auto key = [&points](int i) { return std::pair{points(0, i), points(1, i)}; };
  std::sort(order.begin(), order.end(), [&key](int i, int j) { return key(i) < key(j); });
  for (int j = 1; j < n; ++j) {
    TESSERA_CHECK(key(order[j - 1]) != key(order[j]),
                  "delaunay_triangulation: points " << std::min(order[j - 1], order[j]) << " and "
                                                    << std::max(order[j - 1], order[j])
                                                    << " are equal (" << points(0, order[j]) << ", "
                                                    << points(1, order[j]) << ")");
  }

  std::vector<std::pair<Kernel::Point_2, int>> input;
  input.reserve(n);
  for (int i = 0; i < n; ++i) {
    input.emplace_back(Kernel::Point_2(points(0, i), points(1, i)), i);
  }
  Delaunay delaunay(input.begin(), input.end());
  TESSERA_CHECK(delaunay.dimension() == 2,
                "delaunay_triangulation: all " << n << " points lie on one line");
  TESSERA_ASSERT(static_cast<int>(delaunay.number_of_vertices()) == n);

  std::vector<Triangle> triangles;
  triangles.reserve(delaunay.number_of_faces());
  for (auto face = delaunay.finite_faces_begin(); face != delaunay.finite_faces_end(); ++face) {
    // CGAL's faces are counter-clockwise.
    triangles.push_back(
        {face->vertex(0)->info(), face->vertex(1)->info(), face->vertex(2)->info()});
  }
  const Eigen::VectorXd z = values.size() == 0 ? Eigen::VectorXd::Zero(n) : Eigen::VectorXd(values);
  PlanarTriangulation triangulation(points, z, std::move(triangles));
  const DelaunaySummary rule = apply_input_order_rule(triangulation);
  if (summary != nullptr) {
    *summary = rule;
  }
  // A deterministic triangle order (CGAL's depends on insertion order after spatial sorting):
  // each triangle starts at its smallest index, then triangles sorted.
  triangles = triangulation.triangles();
  for (Triangle& t : triangles) {
    std::rotate(t.begin(), std::min_element(t.begin(), t.end()), t.end());
  }
  std::sort(triangles.begin(), triangles.end());
  return PlanarTriangulation(points, z, std::move(triangles));
}

}  // namespace tessera
