// SPDX-License-Identifier: MIT
// Closed surfaces beyond the catalogue close with the Euler characteristic of their topology.
#include <gtest/gtest.h>

#include "support/test_support.h"
#include "tessera/geometry/mesh_quality.h"
#include "tessera/geometry/mesh_validation.h"
#include "tessera/methods/front/advancing_front.h"
#include "tessera/problems/problem_file.h"

namespace tessera {
namespace {

// A thickened figure eight: genus 2, χ = −2. Its neck at x = 1 makes the front split and
// rejoin around two holes.
TEST(FrontTopology, GenusTwoSurfaceClosesWithEulerCharacteristicMinusTwo) {
  const ProblemSetup setup = load_problem_file(testing::source_path("examples/problems/genus2.tsr"));
  FrontOptions options;
  options.step = setup.suggested_step;
  const CoveringResult result =
      triangulate_by_front(*setup.problem, setup.start, setup.domain, options);
  ASSERT_TRUE(result.summary.is_complete()) << result.summary.message;
  const MeshValidation validation = validate(result.mesh);
  EXPECT_TRUE(validation.is_valid()) << validation.report();
  EXPECT_TRUE(validation.is_closed());
  EXPECT_EQ(validation.euler_characteristic, -2);
  EXPECT_EQ(validation.genus, 2);
  EXPECT_LT(measure_quality(result.mesh, *setup.problem).vertex_residual.max, 1e-8);
}

}  // namespace
}  // namespace tessera
