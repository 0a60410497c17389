// SPDX-License-Identifier: MIT
#include "tessera/geometry/spatial_order.h"

#include <CGAL/Simple_cartesian.h>
#include <CGAL/Spatial_sort_traits_adapter_3.h>
#include <CGAL/hilbert_sort.h>

#include <cstddef>

#include "tessera/geometry/principal_view.h"

namespace tessera {

std::vector<int> hilbert_order(const Eigen::Ref<const Eigen::Matrix3Xd>& points) {
  using Kernel = CGAL::Simple_cartesian<double>;
  using Point = Kernel::Point_3;
  std::vector<Point> cgal_points;
  cgal_points.reserve(static_cast<std::size_t>(points.cols()));
  for (Eigen::Index k = 0; k < points.cols(); ++k) {
    cgal_points.emplace_back(points(0, k), points(1, k), points(2, k));
  }
  std::vector<std::ptrdiff_t> order(cgal_points.size());
  for (std::size_t k = 0; k < order.size(); ++k) {
    order[k] = static_cast<std::ptrdiff_t>(k);
  }
  // The indices are sorted, the points read through them (a pointer is a property map).
  using Traits = CGAL::Spatial_sort_traits_adapter_3<Kernel, Point*>;
  CGAL::hilbert_sort(order.begin(), order.end(), Traits(cgal_points.data()),
                     CGAL::Hilbert_sort_median_policy());
  return {order.begin(), order.end()};
}

std::vector<int> spatially_ordered(const TriangleMesh& mesh, std::vector<int> vertices) {
  if (vertices.size() < 3 || mesh.space().is_distributed()) {
    return vertices;
  }
  // Points with a coordinate that is not finite have no place on the curve (and would make the
  // sort's comparisons inconsistent): they come last, in the given order.
  std::vector<int> finite;
  std::vector<int> last;
  finite.reserve(vertices.size());
  for (const int v : vertices) {
    (mesh.point(v).allFinite() ? finite : last).push_back(v);
  }
  PrincipalView view(mesh.ambient_dimension());
  view.fit_sample(static_cast<int>(finite.size()),
                  [&](int i) { return mesh.point(finite[static_cast<std::size_t>(i)]); });
  Eigen::Matrix3Xd images(3, static_cast<Eigen::Index>(finite.size()));
  for (std::size_t k = 0; k < finite.size(); ++k) {
    images.col(static_cast<Eigen::Index>(k)) = view(mesh.point(finite[k]));
  }
  if (!images.allFinite()) {  // a view that overflowed: no order to be had
    return vertices;
  }
  std::vector<int> ordered;
  ordered.reserve(vertices.size());
  for (const int k : hilbert_order(images)) {
    ordered.push_back(finite[static_cast<std::size_t>(k)]);
  }
  ordered.insert(ordered.end(), last.begin(), last.end());
  return ordered;
}

}  // namespace tessera
