// SPDX-License-Identifier: MIT
// collapse_needles: needles planted into valid meshes of M are removed, the mesh stays valid,
// its angles improve, and the boundary is never touched.
#include "tessera/methods/improvement/needle_collapse.h"

#include <gtest/gtest.h>

#include <Eigen/Core>

#include <algorithm>

#include "geometry/mesh_examples.h"
#include "tessera/core/domain.h"
#include "tessera/geometry/mesh_quality.h"
#include "tessera/geometry/mesh_topology.h"
#include "tessera/geometry/mesh_validation.h"
#include "tessera/problems/examples.h"

namespace tessera {
namespace {

// Splits the edge (v, a) at a point w at `fraction` of the way from v (put on M by `lift`): the
// two triangles on the edge become four, two of them needles with the short edge (v, w).
template <typename Lift>
int plant_needles(TriangleMesh& mesh, int v, int a, double fraction, Lift lift) {
  const int w = mesh.add_vertex(
      lift(Eigen::VectorXd(mesh.point(v) + fraction * (mesh.point(a) - mesh.point(v)))));
  std::vector<Triangle> triangles;
  for (Triangle tri : mesh.triangles()) {
    const auto has = [&](int x) { return std::find(tri.begin(), tri.end(), x) != tri.end(); };
    if (has(v) && has(a)) {
      Triangle near = tri;
      Triangle far = tri;
      std::replace(near.begin(), near.end(), a, w);  // (v, w, opposite): the needle
      std::replace(far.begin(), far.end(), v, w);    // (w, a, opposite)
      triangles.push_back(near);
      triangles.push_back(far);
    } else {
      triangles.push_back(tri);
    }
  }
  mesh.set_triangles(std::move(triangles));
  return w;
}

TEST(NeedleCollapse, RemovesNeedlesPlantedInASphereMesh) {
  const Sphere sphere(1.0);
  const TriangleMesh original = examples::icosphere(3);
  TriangleMesh mesh = original;
  const MeshTopology topology(original);
  const auto lift = [](const Eigen::VectorXd& x) { return Eigen::VectorXd(x.normalized()); };
  // Needles at three places apart from each other, 1% and 0.1% of an edge long.
  int planted = 0;
  for (int e : {0, 200, 400}) {
    const auto edge = topology.edge(e);
    plant_needles(mesh, edge[0], edge[1], e == 200 ? 0.001 : 0.01, lift);
    ++planted;
  }
  const double planted_min = measure_shape(mesh).min_angle_degrees;
  ASSERT_LT(planted_min, 2.0);
  ASSERT_TRUE(validate(mesh, sphere, Domain()).is_valid());

  const NeedleCollapseSummary summary = collapse_needles(mesh, sphere);
  EXPECT_EQ(summary.collapsed_edges, planted) << summary.brief_report();
  const MeshValidation validation = validate(mesh, sphere, Domain());
  EXPECT_TRUE(validation.is_valid()) << validation.report();
  EXPECT_EQ(validation.euler_characteristic, 2);
  EXPECT_EQ(mesh.triangle_count(), original.triangle_count());
  EXPECT_EQ(mesh.vertex_count(), original.vertex_count()) << "the unused vertices are dropped";
  EXPECT_GE(measure_shape(mesh).min_angle_degrees,
            measure_shape(original).min_angle_degrees - 1e-9);
  for (int v = 0; v < mesh.vertex_count(); ++v) {
    EXPECT_NEAR(mesh.point(v).norm(), 1.0, 1e-12) << "vertices never move off M";
  }
}

TEST(NeedleCollapse, LeavesNeedlesOnTheBoundaryAndAWellShapedMeshAlone) {
  const Plane plane;
  const TriangleMesh square = examples::square_grid(6);  // in R², put on the plane z = 0
  Eigen::MatrixXd points = Eigen::MatrixXd::Zero(3, square.vertex_count());
  points.topRows(2) = square.points();
  TriangleMesh grid(points, square.triangles());
  const TriangleMesh untouched = grid;
  EXPECT_EQ(collapse_needles(grid, plane).collapsed_edges, 0);
  EXPECT_EQ(grid.triangles(), untouched.triangles());

  // A needle whose short edge lies on the boundary: both its ends are boundary vertices.
  const MeshTopology topology(grid);
  const auto edge = topology.edge(topology.boundary_edges().front());
  plant_needles(grid, edge[0], edge[1], 0.01, [](const Eigen::VectorXd& x) { return x; });
  const int before = grid.triangle_count();
  const NeedleCollapseSummary summary = collapse_needles(grid, plane);
  EXPECT_EQ(summary.collapsed_edges, 0) << summary.brief_report();
  EXPECT_EQ(grid.triangle_count(), before);
  EXPECT_TRUE(validate(grid, plane, Domain()).is_valid());
}

}  // namespace
}  // namespace tessera
