// SPDX-License-Identifier: MIT
// FrontState's repairs of pinched vertices (a vertex shared by fans that share no edge).
#include "tessera/methods/front/front_state.h"

#include <gtest/gtest.h>

#include <Eigen/Core>

#include "tessera/geometry/mesh_validation.h"

namespace tessera {
namespace {

// Two triangles that touch only at vertex 0: a pinch, as two parts of the front connected to
// the same exterior vertex leave it.
FrontState bow_tie(VertexType centre_type) {
  FrontState state(3, 0.1);
  state.add_vertex(Eigen::Vector3d(0.0, 0.0, 0.0), centre_type);
  state.add_vertex(Eigen::Vector3d(1.0, 0.2, 0.0), VertexType::Exterior);
  state.add_vertex(Eigen::Vector3d(1.0, 1.0, 0.0), VertexType::Exterior);
  state.add_vertex(Eigen::Vector3d(-1.0, -0.2, 0.0), VertexType::Exterior);
  state.add_vertex(Eigen::Vector3d(-1.0, -1.0, 0.0), VertexType::Exterior);
  state.add_triangle(0, 1, 2);
  state.add_triangle(0, 3, 4);
  return state;
}

TEST(FrontStatePinches, AnExteriorVertexIsSplitOneCopyPerFan) {
  FrontState state = bow_tie(VertexType::Exterior);
  ASSERT_EQ(state.fan_chains(0).size(), 2u);
  EXPECT_EQ(state.split_pinched_exterior_vertices(), 1);
  EXPECT_EQ(state.fan_chains(0).size(), 1u);
  EXPECT_EQ(state.fan_chains(5).size(), 1u);
  EXPECT_EQ(state.point(5), state.point(0));
  EXPECT_EQ(state.live_triangle_count(), 2);
  const TriangleMesh mesh = state.take_mesh();
  EXPECT_EQ(mesh.vertex_count(), 6);
  const MeshValidation validation = validate(mesh);
  EXPECT_EQ(validation.non_manifold_vertex_count, 0) << validation.report();
}

TEST(FrontStatePinches, OnlyExteriorVerticesAreSplit) {
  // A pinch at a vertex inside S is a fold of the covering there, not a touch outside it.
  FrontState state = bow_tie(VertexType::Frontal);
  EXPECT_EQ(state.split_pinched_exterior_vertices(), 0);
  EXPECT_EQ(state.fan_chains(0).size(), 2u);
}

}  // namespace
}  // namespace tessera
