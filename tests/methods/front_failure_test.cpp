// SPDX-License-Identifier: MIT
// When the front cannot close, it says where, and the work it returns is a valid mesh.
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <string>
#include <vector>

#include "support/sparse_view.h"
#include "support/test_support.h"
#include "tessera/geometry/mesh_validation.h"
#include "tessera/methods/covering_methods.h"
#include "tessera/methods/front/advancing_front.h"
#include "tessera/problems/catalogue.h"
#include "tessera/problems/problem_file.h"

namespace tessera {
namespace {

// The unit sphere in the slab |z| <= 0.1 at a step of 0.17: the belt is narrower than the
// step, and the front runs into itself there even after deferring the vertices concerned. The
// run must stop with FrontCollision, name a vertex and its coordinates, and return a valid
// (partial) mesh. (The trough at h = 0.1, this test's case before vertices were deferred, now
// completes: see the next test.)
TEST(FrontFailure, ACollisionIsReportedWithItsLocationAndAValidMesh) {
  const ProblemSetup setup =
      load_problem_file(testing::source_path("tests/stress/problems/sphere_belt.tsr"));
  FrontOptions options;
  options.step = 0.17370585305992345;
  Eigen::VectorXd start(3);
  start << 0.86616996340077146, 0.56909136068239774, -0.078950363006863422;
  const CoveringResult result = triangulate_by_front(*setup.problem, start, setup.domain, options);
  ASSERT_FALSE(result.summary.is_complete());
  EXPECT_EQ(result.summary.termination, CoveringTermination::FrontCollision);
  EXPECT_NE(result.summary.message.find("vertex"), std::string::npos) << result.summary.message;
  EXPECT_NE(result.summary.message.find("("), std::string::npos) << result.summary.message;
  EXPECT_GT(result.mesh.triangle_count(), 0);
  const MeshValidation validation = validate(result.mesh);
  EXPECT_TRUE(validation.is_valid()) << validation.report();
}

// A step that runs into the mesh is undone and the vertex tried again after its neighbours
// (FrontBuilder::defer). On the sphere in the box [-0.97, 0.97]³, whose six caps outside S are
// about as wide as the step, these runs stopped with "the front overlaps itself" (19 of the
// stress campaign's 25); the trough's arch, 0.03 wide, stopped a step of 0.1 the same way.
TEST(FrontFailure, DeferredVerticesLetTheFrontCloseWhereItRanIntoItself) {
  struct Case {
    std::string problem;
    double step;
  };
  for (const Case& c : {Case{"tests/stress/problems/sphere_box.tsr", 0.1},
                        Case{"tests/stress/problems/sphere_box.tsr", 0.15},
                        Case{"tests/stress/problems/sphere_box.tsr", 0.3}, Case{"trough", 0.1}}) {
    const ProblemSetup setup = c.problem.find('/') != std::string::npos
                                   ? load_problem_file(testing::source_path(c.problem))
                                   : make_catalogue_problem(c.problem);
    MethodSettings settings;
    settings.step = c.step;
    const CoveringResult result = cover(setup, find_covering_method("front"), settings);
    const std::string what = c.problem + " at step " + std::to_string(c.step);
    ASSERT_TRUE(result.summary.is_complete()) << what << ": " << result.summary.message;
    const MeshValidation validation = validate(result.mesh);
    EXPECT_TRUE(validation.is_valid()) << what << ": " << validation.report();
    EXPECT_EQ(validation.euler_characteristic, *setup.expected_euler_characteristic) << what;
    bool deferred = false;  // the completion is the deferral's doing, and the summary says so
    for (const std::string& note : result.summary.notes) {
      deferred = deferred || note.find("were undone") != std::string::npos;
    }
    EXPECT_TRUE(deferred) << what;
  }
}

// Where S cuts a hole into M smaller than the step (a cap of the sphere beyond a face of the
// box [-0.97, 0.97]³, 0.48 across, at h ≈ 0.5), the front's triangles can close over it with
// every corner inside S, and clipping sees no edge across the face. The run used to end
// "completed" with χ −2 for −4 (stress campaign, case 439, at h = 0.493); the pipeline now finds
// the triangle whose part of M lies beyond the face and says where. Which steps close over a
// hole depends on rounding (case 439's step completes correctly since issue 35 changed the QR of
// one equation), so every step here must either cover the six holes or fail saying why, and at
// h = 0.45 the front closes over the hole beyond y = −0.97.
TEST(FrontFailure, AHoleOfMInsideSSmallerThanTheStepIsNotCoveredOver) {
  ProblemSetup from_case =
      load_problem_file(testing::source_path("tests/stress/problems/sphere_box.tsr"));
  from_case.start = Eigen::Vector3d(0.84977847491860048, -0.44724862996100495, 0.12033287592431689);
  from_case.expected_euler_characteristic.reset();  // judged without knowing χ
  for (const double step : {0.45, 0.48, 0.49324898681853396, 0.52}) {
    MethodSettings settings;
    settings.step = step;
    const CoveringResult result = cover(from_case, find_covering_method("front"), settings);
    if (result.summary.is_complete()) {
      const MeshValidation validation = validate(result.mesh);
      EXPECT_TRUE(validation.is_valid()) << "step " << step << ": " << validation.report();
      EXPECT_EQ(validation.euler_characteristic, -4) << "step " << step;
    } else {
      EXPECT_FALSE(result.summary.message.empty()) << "step " << step;
    }
    if (step == 0.45) {
      ASSERT_FALSE(result.summary.is_complete());
      EXPECT_EQ(result.summary.termination, CoveringTermination::TriangulationFailed);
      EXPECT_NE(result.summary.message.find("covers a part of M outside the domain"),
                std::string::npos)
          << result.summary.message;
      EXPECT_NE(result.summary.message.find("y >= -0.97"), std::string::npos)
          << result.summary.message;
    }
  }
}

// Failed runs of the stress campaign (seed 2034) whose partial meshes were not valid: a front
// that ran into itself left two triangles of edge 1 on top of each other (sphere_box, case 664;
// the validation missed it, the chart's distortion bound exceeding their overlap's width), and
// a Bézier run whose final check removed a flipped triangle, exposing a fan that overlaps itself
// (cstr, case 965). Both runs say that they failed; what they return must be valid on M.
TEST(FrontFailure, PartialMeshesOfCollidingFrontsAreValidOnM) {
  struct Case {
    const char* problem;
    const char* method;
    double step;
    double tolerance;
    std::vector<double> start;
  };
  const std::vector<Case> cases = {
      {"tests/stress/problems/sphere_box.tsr", "front", 0.56272365094030063, 0.0,
       {0.15350769038731438, 0.89840427299855374, -0.4744388067340875}},
      {"cstr", "bezier", 0.19684427447110309, 0.0026046230572396695,
       {0.21910781887383105, 0.0032279253412978853, 0.055180547913637613, 5.0110363172793475}},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.problem);
    ProblemSetup setup = std::string(c.problem).ends_with(".tsr")
                             ? load_problem_file(testing::source_path(c.problem))
                             : make_catalogue_problem(c.problem);
    setup.start = Eigen::Map<const Eigen::VectorXd>(c.start.data(), c.start.size());
    MethodSettings settings;
    settings.step = c.step;
    settings.tolerance = c.tolerance;
    const CoveringResult result = cover(setup, find_covering_method(c.method), settings);
    EXPECT_FALSE(result.summary.is_complete());
    const MeshValidation validation = validate(result.mesh, *setup.problem, setup.domain);
    EXPECT_TRUE(validation.is_valid()) << result.summary.message << "\n" << validation.report();
    EXPECT_GT(result.mesh.triangle_count(), 50) << "most of the work is kept";
  }
}

// The same run on the sparse path (the sphere seen through its sparse Jacobian, as a PDE's
// problem is), with a tolerance: there the check looks only within twice the tolerance of a
// face. Here refinement reaches the cap first (the run stops: 2 triangles 0.042 from M after 3
// rounds of bisection; at tolerances 0.05-0.2 the final check removes overlapping triangles);
// what must never happen is a completed run with a hole covered over.
TEST(FrontFailure, OnTheSparsePathAHoleIsNeverCoveredOverSilently) {
  const ProblemSetup setup =
      load_problem_file(testing::source_path("tests/stress/problems/sphere_box.tsr"));
  const testing::SparseView sparse(*setup.problem);
  FrontOptions options;
  options.step = 0.49324898681853396;
  options.tolerance = 0.02;
  const Eigen::Vector3d start(0.84977847491860048, -0.44724862996100495, 0.12033287592431689);
  const CoveringResult result = triangulate_by_front(sparse, start, setup.domain, options);
  const MeshValidation validation = validate(result.mesh);
  ASSERT_TRUE(validation.is_valid()) << validation.report();
  // Either the run says where M ∩ S was covered over, or its mesh has all six holes.
  if (result.summary.is_complete()) {
    EXPECT_EQ(validation.euler_characteristic, -4) << "a hole covered over, not reported";
  } else {
    EXPECT_NE(result.summary.message.find("("), std::string::npos) << result.summary.message;
  }
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
