// SPDX-License-Identifier: MIT
#include "tessera/geometry/mesh_topology.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <string>

#include "geometry/mesh_examples.h"
#include "tessera/core/error.h"

namespace tessera {
namespace {

// Every adjacency is symmetric and is across an edge the two triangles share.
void expect_adjacency_is_symmetric(const MeshTopology& topology) {
  for (int t = 0; t < topology.triangle_count(); ++t) {
    for (int k = 0; k < 3; ++k) {
      const int u = topology.adjacent_triangle(t, k);
      const int e = topology.triangle_edges(t)[k];
      if (u < 0) {
        EXPECT_NE(topology.edge_triangles(e).size(), 2u) << "triangle " << t << " edge " << k;
        continue;
      }
      const auto& u_edges = topology.triangle_edges(u);
      const int ku =
          static_cast<int>(std::find(u_edges.begin(), u_edges.end(), e) - u_edges.begin());
      ASSERT_LT(ku, 3) << "triangles " << t << " and " << u << " are adjacent but share no edge";
      EXPECT_EQ(topology.adjacent_triangle(u, ku), t);
    }
  }
}

// Twice the signed area enclosed by a polygon of points in R^2 (shoelace formula).
double twice_signed_area(const TriangleMesh& mesh, std::span<const int> loop) {
  double sum = 0;
  for (std::size_t i = 0; i < loop.size(); ++i) {
    const auto p = mesh.point(loop[i]);
    const auto q = mesh.point(loop[(i + 1) % loop.size()]);
    sum += p(0) * q(1) - q(0) * p(1);
  }
  return sum;
}

TEST(MeshTopology, OctahedronIsAClosedSphere) {
  const TriangleMesh mesh = examples::octahedron();
  const MeshTopology topology(mesh);
  EXPECT_EQ(topology.vertex_count(), 6);
  EXPECT_EQ(topology.referenced_vertex_count(), 6);
  EXPECT_EQ(topology.edge_count(), 12);
  EXPECT_EQ(topology.triangle_count(), 8);
  EXPECT_EQ(topology.euler_characteristic(), 2);
  EXPECT_TRUE(topology.is_closed());
  EXPECT_FALSE(topology.has_boundary());
  EXPECT_EQ(topology.boundary_loop_count(), 0);
  EXPECT_EQ(topology.component_count(), 1);
  for (int e = 0; e < topology.edge_count(); ++e) {
    EXPECT_EQ(topology.edge_triangles(e).size(), 2u) << "edge " << e;
    EXPECT_TRUE(topology.is_orientation_consistent(e)) << "edge " << e;
  }
  for (int v = 0; v < 6; ++v) {
    EXPECT_EQ(topology.vertex_triangles(v).size(), 4u) << "vertex " << v;  // octahedron: degree 4
  }
  expect_adjacency_is_symmetric(topology);
}

TEST(MeshTopology, EdgesAreSortedPairsAndIncidencesAreIncreasing) {
  const TriangleMesh mesh = examples::icosphere(1);
  const MeshTopology topology(mesh);
  EXPECT_EQ(topology.edge_count(), 120);
  EXPECT_TRUE(std::is_sorted(topology.edges().begin(), topology.edges().end()));
  for (int e = 0; e < topology.edge_count(); ++e) {
    EXPECT_LT(topology.edge(e)[0], topology.edge(e)[1]);
    const auto on_edge = topology.edge_triangles(e);
    EXPECT_TRUE(std::is_sorted(on_edge.begin(), on_edge.end()));
    EXPECT_EQ(topology.find_edge(topology.edge(e)[1], topology.edge(e)[0]), e);
  }
  for (int t = 0; t < topology.triangle_count(); ++t) {
    const Triangle& tri = mesh.triangle(t);
    for (int k = 0; k < 3; ++k) {
      EXPECT_EQ(topology.triangle_edges(t)[k], topology.find_edge(tri[k], tri[(k + 1) % 3]));
    }
  }
  for (int v = 0; v < topology.vertex_count(); ++v) {
    const auto around = topology.vertex_triangles(v);
    EXPECT_TRUE(std::is_sorted(around.begin(), around.end()));
    for (int t : around) {
      const Triangle& tri = mesh.triangle(t);
      EXPECT_TRUE(tri[0] == v || tri[1] == v || tri[2] == v);
    }
  }
}

TEST(MeshTopology, FindEdgeReturnsMinusOneForNonEdges) {
  const MeshTopology topology(examples::octahedron());
  EXPECT_EQ(topology.find_edge(0, 1), -1);  // +x and -x are opposite vertices
  EXPECT_EQ(topology.find_edge(0, 99), -1);
  const int e = topology.find_edge(4, 0);
  ASSERT_GE(e, 0);
  EXPECT_EQ(topology.edge(e), (MeshTopology::Edge{0, 4}));
}

TEST(MeshTopology, TorusHasEulerCharacteristicZero) {
  const MeshTopology topology(examples::torus(12, 8));
  EXPECT_EQ(topology.edge_count(), 3 * 12 * 8);
  EXPECT_EQ(topology.euler_characteristic(), 0);
  EXPECT_TRUE(topology.is_closed());
  EXPECT_EQ(topology.component_count(), 1);
  expect_adjacency_is_symmetric(topology);
}

TEST(MeshTopology, SquareGridHasOneBoundaryLoopFollowingOrientation) {
  const int k = 5;
  const TriangleMesh mesh = examples::square_grid(k);
  const MeshTopology topology(mesh);
  EXPECT_EQ(topology.euler_characteristic(), 1);
  EXPECT_EQ(topology.boundary_edges().size(), static_cast<std::size_t>(4 * k));
  ASSERT_EQ(topology.boundary_loop_count(), 1);
  const auto loop = topology.boundary_loop(0);
  ASSERT_EQ(loop.size(), static_cast<std::size_t>(4 * k));
  for (std::size_t i = 0; i < loop.size(); ++i) {
    const int e = topology.find_edge(loop[i], loop[(i + 1) % loop.size()]);
    ASSERT_GE(e, 0) << "loop vertices " << loop[i] << " and " << loop[(i + 1) % loop.size()];
    EXPECT_TRUE(topology.is_boundary_edge(e));
  }
  // Counter-clockwise triangles: the surface is on the left, so the loop encloses +1.
  EXPECT_NEAR(twice_signed_area(mesh, loop), 2.0, 1e-12);
}

TEST(MeshTopology, ReversedGridHasItsLoopReversed) {
  TriangleMesh mesh = examples::square_grid(3);
  std::vector<Triangle> reversed = mesh.triangles();
  for (Triangle& t : reversed) {
    std::swap(t[1], t[2]);
  }
  mesh.set_triangles(reversed);
  const MeshTopology topology(mesh);
  ASSERT_EQ(topology.boundary_loop_count(), 1);
  EXPECT_NEAR(twice_signed_area(mesh, topology.boundary_loop(0)), -2.0, 1e-12);
}

TEST(MeshTopology, ComponentsAreEdgeConnected) {
  const TriangleMesh mesh = examples::disjoint_union(examples::octahedron(), examples::torus(4, 3));
  const MeshTopology topology(mesh);
  EXPECT_EQ(topology.component_count(), 2);
  EXPECT_EQ(topology.euler_characteristic(), 2 + 0);
  for (int t = 0; t < topology.triangle_count(); ++t) {
    EXPECT_EQ(topology.component_of(t), t < 8 ? 0 : 1) << "triangle " << t;
  }
}

TEST(MeshTopology, BowTieHasTwoComponentsAndTwoLoops) {
  // Two triangles that share only vertex 0.
  Eigen::MatrixXd points(2, 5);
  points << 0, 1, 1, -1, -1,  //
      0, 0, 1, 0, -1;
  const MeshTopology topology(TriangleMesh(points, {{0, 1, 2}, {0, 3, 4}}));
  EXPECT_EQ(topology.component_count(), 2);
  EXPECT_EQ(topology.vertex_triangles(0).size(), 2u);
  ASSERT_EQ(topology.boundary_loop_count(), 2);
  EXPECT_EQ(topology.boundary_loop(0).size(), 3u);
  EXPECT_EQ(topology.boundary_loop(1).size(), 3u);
  EXPECT_EQ(topology.euler_characteristic(), 5 - 6 + 2);
}

TEST(MeshTopology, NonManifoldEdgeHasNoAdjacentTriangle) {
  Eigen::MatrixXd points(3, 5);
  points << 0, 1, 0, 0, 0.5,  //
      0, 0, 1, -1, 0.5,       //
      0, 0, 0, 0, 1;
  const MeshTopology topology(TriangleMesh(points, {{0, 1, 2}, {1, 0, 3}, {0, 1, 4}}));
  const int e = topology.find_edge(0, 1);
  ASSERT_GE(e, 0);
  EXPECT_FALSE(topology.is_manifold_edge(e));
  EXPECT_EQ(topology.edge_triangles(e).size(), 3u);
  EXPECT_EQ(topology.adjacent_triangle(0, 0), -1);
  EXPECT_EQ(topology.component_count(), 1);  // a non-manifold edge still connects
}

TEST(MeshTopology, MobiusStripIsNotOrientable) {
  const int m = 6;
  const MeshTopology topology(examples::mobius_strip(m));
  EXPECT_EQ(topology.euler_characteristic(), 0);
  ASSERT_EQ(topology.boundary_loop_count(), 1);
  EXPECT_EQ(topology.boundary_loop(0).size(), static_cast<std::size_t>(2 * m));
  const OrientationAssignment assignment = topology.orientation_assignment();
  ASSERT_EQ(assignment.is_component_orientable.size(), 1u);
  EXPECT_EQ(assignment.is_component_orientable[0], 0);
  int inconsistent = 0;
  for (int e = 0; e < topology.edge_count(); ++e) {
    inconsistent += topology.is_orientation_consistent(e) ? 0 : 1;
  }
  EXPECT_EQ(inconsistent, 1);  // the seam: every other interior edge agrees by construction
}

TEST(MeshTopology, OrientConsistentlyRepairsFlippedTriangles) {
  const TriangleMesh mesh = examples::octahedron();
  std::vector<Triangle> triangles = mesh.triangles();
  std::swap(triangles[3][0], triangles[3][1]);
  std::swap(triangles[6][1], triangles[6][2]);
  TriangleMesh flipped = mesh;
  flipped.set_triangles(triangles);
  const MeshTopology topology(flipped);
  int inconsistent = 0;
  for (int e = 0; e < topology.edge_count(); ++e) {
    inconsistent += topology.is_orientation_consistent(e) ? 0 : 1;
  }
  EXPECT_EQ(inconsistent, 6);  // triangles 3 and 6 share no edge: 3 edges each
  const auto assignment = topology.orientation_assignment();
  EXPECT_EQ(assignment.is_component_orientable[0], 1);

  bool is_orientable = false;
  const std::vector<Triangle> repaired = orient_consistently(flipped, &is_orientable);
  EXPECT_TRUE(is_orientable);
  // Triangle 0 keeps its orientation, so the repair restores the outward orientation; the
  // repaired triangles are cyclic rotations of the originals.
  for (int t = 0; t < 8; ++t) {
    const Triangle& want = mesh.triangle(t);
    const Triangle& got = repaired[t];
    const bool is_rotation = got == want || got == Triangle{want[1], want[2], want[0]} ||
                             got == Triangle{want[2], want[0], want[1]};
    EXPECT_TRUE(is_rotation) << "triangle " << t;
  }
}

TEST(MeshTopology, EmptyMeshHasNothing) {
  const MeshTopology topology(TriangleMesh(3));
  EXPECT_EQ(topology.edge_count(), 0);
  EXPECT_EQ(topology.component_count(), 0);
  EXPECT_EQ(topology.boundary_loop_count(), 0);
  EXPECT_EQ(topology.euler_characteristic(), 0);
  EXPECT_FALSE(topology.is_closed());
}

TEST(MeshTopology, RejectsIndexOutOfRangeNamingTheTriangle) {
  TriangleMesh mesh = examples::octahedron();
  mesh.add_triangle(0, 2, 9);
  try {
    const MeshTopology topology(mesh);
    FAIL() << "no exception";
  } catch (const InvalidArgument& e) {
    EXPECT_NE(
        std::string(e.what()).find("triangle 8 = (0, 2, 9) has vertex index 9 outside [0, 6)"),
        std::string::npos)
        << e.what();
  }
}

TEST(MeshTopology, RejectsRepeatedIndexNamingTheTriangle) {
  TriangleMesh mesh = examples::octahedron();
  mesh.add_triangle(4, 2, 4);
  try {
    const MeshTopology topology(mesh);
    FAIL() << "no exception";
  } catch (const InvalidArgument& e) {
    EXPECT_NE(std::string(e.what()).find("triangle 8 = (4, 2, 4) repeats a vertex"),
              std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace tessera
