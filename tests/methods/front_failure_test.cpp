// SPDX-License-Identifier: MIT
// When the front cannot close, it says where, and the work it returns is a valid mesh.
#include <gtest/gtest.h>

#include <string>

#include "tessera/geometry/mesh_validation.h"
#include "tessera/methods/front/advancing_front.h"
#include "tessera/problems/catalogue.h"

namespace tessera {
namespace {

// The trough's arch is about 0.03 wide; a step of 0.1 cannot follow it, and the front runs
// into itself. The run must stop with FrontCollision, name a vertex and its coordinates, and
// return a valid (partial) mesh.
TEST(FrontFailure, ACollisionIsReportedWithItsLocationAndAValidMesh) {
  const ProblemSetup setup = make_catalogue_problem("trough");
  FrontOptions options;
  options.step = 0.1;
  const CoveringResult result =
      triangulate_by_front(*setup.problem, setup.start, setup.domain, options);
  ASSERT_FALSE(result.summary.is_complete());
  EXPECT_EQ(result.summary.termination, CoveringTermination::FrontCollision);
  EXPECT_NE(result.summary.message.find("vertex"), std::string::npos) << result.summary.message;
  EXPECT_NE(result.summary.message.find("("), std::string::npos) << result.summary.message;
  EXPECT_GT(result.mesh.triangle_count(), 0);
  const MeshValidation validation = validate(result.mesh);
  EXPECT_TRUE(validation.is_valid()) << validation.report();
}

// With the paper's FIFO order, tessera refuses to create the overlaps PITMAN would leave to
// later merges; wherever such a run stops, the partial mesh must still be valid (connections
// to the front that were not yet glued are undone).
class FifoOrder : public ::testing::TestWithParam<std::string> {};

TEST_P(FifoOrder, EveryRunEndsWithAValidMesh) {
  const ProblemSetup setup = make_catalogue_problem(GetParam());
  FrontOptions options;
  options.step = setup.suggested_step;
  options.order = FrontOrder::Fifo;
  const CoveringResult result =
      triangulate_by_front(*setup.problem, setup.start, setup.domain, options);
  const MeshValidation validation = validate(result.mesh);
  EXPECT_TRUE(validation.is_valid()) << result.summary.message << "\n" << validation.report();
  if (!result.summary.is_complete()) {
    EXPECT_FALSE(result.summary.message.empty());
  }
}

INSTANTIATE_TEST_SUITE_P(Catalogue, FifoOrder,
                         ::testing::Values("sphere", "sphere_cut", "plane", "equipotential",
                                           "torus", "whitney_pleat", "trough", "cstr"));

// Stopping at the vertex limit keeps a valid partial mesh too.
TEST(FrontFailure, VertexLimitKeepsAValidMesh) {
  const ProblemSetup setup = make_catalogue_problem("torus");
  FrontOptions options;
  options.step = setup.suggested_step;
  options.max_vertices = 300;
  const CoveringResult result =
      triangulate_by_front(*setup.problem, setup.start, setup.domain, options);
  EXPECT_EQ(result.summary.termination, CoveringTermination::VertexLimit);
  const MeshValidation validation = validate(result.mesh);
  EXPECT_TRUE(validation.is_valid()) << validation.report();
  EXPECT_GE(result.mesh.vertex_count(), 300);
}

}  // namespace
}  // namespace tessera
