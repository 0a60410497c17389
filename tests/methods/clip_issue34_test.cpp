// SPDX-License-Identifier: MIT
// Regression tests of issue 34: python/examples/bvp_scipy.py (the catalogue's bvp written in
// SciPy, in the box u_i ≤ 20 for every i rather than the catalogue's bound on the middle point
// alone) failed in the clipping: "clipping to the face 'u26 <= 20' would fold the triangle".
// On an even grid the states are symmetric, u_{N/2} = u_{N/2+1}, so the bounds on those twin
// coordinates coincide on M. The vertices that the first bound's clipping put on
// M ∩ {u_{N/2} = 20} lay across the second by rounding (±4e-16, either sign); counted as
// across, each got a cut point a rounding error away (a needle that folds), or one projected
// onto both faces at once (a singular system: "no point of M on the face", "the cut point lies
// outside the face 'u3 <= 20' by 8.9e-16"). The C++ problem in the same box fails the same way
// in 47 of 64 runs of N = 6 … 50, step 0.07 … 0.16, front and atlas; these are the smallest.
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "tessera/core/domain.h"
#include "tessera/geometry/mesh_validation.h"
#include "tessera/methods/covering_methods.h"
#include "tessera/problems/catalogue.h"

namespace tessera {
namespace {

// bvp:points=N in the box of python/examples/bvp_scipy.py: u_i ≤ 20 for every i, then
// λ ∈ [0.5, 10] and ε ∈ [epsilon_low, epsilon_high], in the order a box lists them (the faces
// of u first, as tessera.Problem(box=...) builds them).
ProblemSetup bvp_in_python_box(int N, double epsilon_low, double epsilon_high) {
  ProblemSetup setup = make_catalogue_problem("bvp:points=" + std::to_string(N));
  const double infinity = std::numeric_limits<double>::infinity();
  Eigen::VectorXd lower = Eigen::VectorXd::Constant(N + 2, -infinity);
  Eigen::VectorXd upper = Eigen::VectorXd::Constant(N + 2, 20.0);
  lower(N) = 0.5;
  upper(N) = 10.0;
  lower(N + 1) = epsilon_low;
  upper(N + 1) = epsilon_high;
  setup.domain = Domain::box(lower, upper, setup.problem->coordinate_names());
  return setup;
}

struct Case {
  const char* method;
  int N;
  double step;
  double epsilon_low;
  double epsilon_high;
  double tolerance;
};

class Issue34 : public ::testing::TestWithParam<Case> {};

TEST_P(Issue34, ClipsToBoundsOnTwinCoordinatesOfSymmetricStates) {
  const Case& c = GetParam();
  const ProblemSetup setup = bvp_in_python_box(c.N, c.epsilon_low, c.epsilon_high);
  MethodSettings settings;
  settings.step = c.step;
  settings.tolerance = c.tolerance;
  const CoveringResult result = cover(setup, find_covering_method(c.method), settings);
  // Before: projection failed, the triangles across the face removed instead.
  EXPECT_TRUE(result.summary.is_complete()) << result.summary.message;
  const MeshValidation validation = validate(result.mesh, *setup.problem, setup.domain);
  EXPECT_TRUE(validation.is_valid()) << validation.report();
  EXPECT_EQ(validation.euler_characteristic, 1);  // M ∩ S is a disk (catalogue.cpp, make_bvp)
  // Every vertex inside S with no tolerance (clipped vertices are put on their faces exactly),
  // and the boundary on M ∩ {u = 20}, on both twin faces at once, not a ragged edge short of it.
  const int middle = (c.N - 1) / 2;  // u_{N/2}, 0-based; its twin follows
  int on_both_twins = 0;
  for (int v = 0; v < result.mesh.vertex_count(); ++v) {
    const Eigen::VectorXd x = result.mesh.point(v);
    for (int k = 0; k < static_cast<int>(setup.domain.half_spaces().size()); ++k) {
      ASSERT_GE(setup.domain.signed_distance(k, x), 0.0)
          << "vertex " << v << " lies outside " << setup.domain.half_spaces()[k].label;
    }
    on_both_twins += x(middle) == 20.0 && x(middle + 1) == 20.0 ? 1 : 0;
  }
  EXPECT_GE(on_both_twins, 3);
}

// Each failed before: the first with "cannot clip the mesh to the face 'u4 <= 20': no point of
// M on the face near the edge …" (0.3 s), the next two with "would fold the triangle", the last
// with the first's message, and the tolerance's refinement bisects boundary edges on both faces.
INSTANTIATE_TEST_SUITE_P(
    Configurations, Issue34,
    ::testing::Values(Case{"front", 6, 0.13, 0.18, 0.22, 0.0},
                      Case{"front", 8, 0.16, 0.0, 0.3, 0.0}, Case{"atlas", 10, 0.16, 0.0, 0.3, 0.0},
                      Case{"front", 6, 0.13, 0.18, 0.22, 1e-3}),
    [](const ::testing::TestParamInfo<Case>& info) {
      const Case& c = info.param;
      return std::string(c.method) + "_points" + std::to_string(c.N) + "_step" +
             std::to_string(static_cast<int>(std::lround(100 * c.step))) + "_epsilon" +
             std::to_string(static_cast<int>(std::lround(100 * c.epsilon_low))) + "to" +
             std::to_string(static_cast<int>(std::lround(100 * c.epsilon_high))) +
             (c.tolerance > 0 ? "_tolerance" : "");
    });

}  // namespace
}  // namespace tessera
