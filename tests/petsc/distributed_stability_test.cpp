// SPDX-License-Identifier: MIT
// The stability on the PETSc backend (MUMPS's inertia, SLEPc's eigenvalues) against the serial
// computation at the same points, on split and on whole states, on however many ranks mpiexec
// started: the same counts vertex for vertex, certain, and the same eigenvalues nearest 0.
#include "tessera/petsc/petsc_stability.h"

#include <gtest/gtest.h>

#include <cmath>

#include "petsc/split_support.h"
#include "tessera/core/error.h"
#include "tessera/petsc/distributed_problem.h"
#include "tessera/petsc/petsc_bratu.h"
#include "tessera/problems/examples.h"

namespace tessera::petsc {
namespace {

// A strip of triangles over points of M on the S-shaped branch (ε = 0.1, 0.12) from amplitude
// 0.3 to 9: it crosses both folds, so its vertices have 0 and 1 unstable eigenvalues.
template <typename Serial>
TriangleMesh strip_across_the_folds(const Serial& serial) {
  constexpr int kColumns = 14;
  Eigen::MatrixXd points(serial.ambient_dimension(), 2 * kColumns);
  std::vector<Triangle> triangles;
  for (int j = 0; j < kColumns; ++j) {
    const double amplitude = 0.3 + 8.7 * j / (kColumns - 1.0);
    points.col(2 * j) = serial.point_with_amplitude(amplitude, 0.1);
    points.col(2 * j + 1) = serial.point_with_amplitude(amplitude, 0.12);
    if (j + 1 < kColumns) {
      triangles.push_back({2 * j, 2 * j + 2, 2 * j + 1});
      triangles.push_back({2 * j + 1, 2 * j + 2, 2 * j + 3});
    }
  }
  return TriangleMesh(points, triangles);
}

// The PETSc result against the serial one: counts vertex for vertex (certain: the inertia), and
// the leading eigenvalue to 10⁻⁸ relative (both converge Ritz values to 10⁻¹⁰).
void expect_same_stability(const StabilityResult& result, const StabilityResult& expected) {
  ASSERT_EQ(result.vertices.size(), expected.vertices.size());
  for (std::size_t v = 0; v < result.vertices.size(); ++v) {
    const VertexStability& got = result.vertices[v];
    const VertexStability& want = expected.vertices[v];
    ASSERT_FALSE(got.has_failed()) << "vertex " << v << ": " << got.message;
    EXPECT_EQ(got.unstable_count, want.unstable_count) << "vertex " << v;
    EXPECT_EQ(got.is_certain, want.is_certain) << "vertex " << v;
    EXPECT_NEAR(got.leading_real_part, want.leading_real_part,
                1e-8 * (1.0 + std::abs(want.leading_real_part)))
        << "vertex " << v;
    EXPECT_EQ(got.eigenvalues.size(), want.eigenvalues.size()) << "vertex " << v;
  }
  EXPECT_EQ(result.index_counts, expected.index_counts);
  EXPECT_EQ(result.uncertain_count, expected.uncertain_count);
  EXPECT_EQ(result.eigenvalue_count, expected.eigenvalue_count);
}

template <typename Serial>
void expect_the_serial_counts(const Serial& serial, int spatial_dimension, int grid_size) {
  const TriangleMesh mesh = strip_across_the_folds(serial);
  const StabilityResult expected = compute_stability(serial, mesh);
  ASSERT_EQ(expected.failed_count, 0);
  ASSERT_EQ(expected.uncertain_count, 0);       // symmetric: the inertia
  ASSERT_GE(expected.index_counts.size(), 2u);  // stable and unstable vertices
  ASSERT_GT(expected.index_counts[0], 0);
  ASSERT_GT(expected.index_counts[1], 0);

  PetscArrheniusBratu bratu(PETSC_COMM_WORLD, spatial_dimension, grid_size);
  const DistributedProblem split(bratu);
  // Split states: each rank its rows of every vertex, as the covering leaves them.
  const StabilityResult on_split =
      compute_distributed_stability(bratu, split_rows(mesh, split.space()));
  expect_same_stability(on_split, expected);
  EXPECT_EQ(on_split.failed_count, 0);
  EXPECT_EQ(on_split.jacobian_evaluations, mesh.vertex_count());
  EXPECT_GE(on_split.factorisations, mesh.vertex_count());
  EXPECT_NE(on_split.method.find("inertia"), std::string::npos) << on_split.method;
  // Whole states on every rank (a ReplicatedProblem's mesh).
  expect_same_stability(compute_distributed_stability(bratu, mesh), expected);
}

TEST(DistributedStability, Bratu2dHasTheSerialCountsVertexForVertex) {
  if (!has_slepc()) {
    GTEST_SKIP() << "built without SLEPc";
  }
  expect_the_serial_counts(ArrheniusBratu2D(8), 2, 8);
}

TEST(DistributedStability, BvpHasTheSerialCountsVertexForVertex) {
  if (!has_slepc()) {
    GTEST_SKIP() << "built without SLEPc";
  }
  expect_the_serial_counts(ArrheniusBratu(60), 1, 60);
}

// At most StabilityOptions::dense_state_limit states, every eigenvalue, as in serial.
TEST(DistributedStability, FewStatesGetEveryEigenvalue) {
  if (!has_slepc()) {
    GTEST_SKIP() << "built without SLEPc";
  }
  const ArrheniusBratu serial(20);
  const TriangleMesh mesh = strip_across_the_folds(serial);
  const StabilityResult expected = compute_stability(serial, mesh);
  ASSERT_EQ(expected.method, "dense");
  PetscArrheniusBratu bratu(PETSC_COMM_WORLD, 1, 20);
  const DistributedProblem split(bratu);
  const StabilityResult result =
      compute_distributed_stability(bratu, split_rows(mesh, split.space()));
  EXPECT_EQ(result.method, "dense");
  expect_same_stability(result, expected);
  for (std::size_t v = 0; v < result.vertices.size(); ++v) {
    ASSERT_EQ(result.vertices[v].eigenvalues.size(), 20u);
    for (std::size_t i = 0; i < 20; ++i) {
      EXPECT_NEAR(result.vertices[v].eigenvalues[i].real(),
                  expected.vertices[v].eigenvalues[i].real(),
                  1e-9 * (1.0 + std::abs(expected.vertices[v].eigenvalues[i])));
    }
  }
}

// A problem without dynamics (here the metric's coordinates, which forward none, as
// ScaledProblem does) is refused with the way to declare them.
TEST(DistributedStability, AProblemWithoutDynamicsIsRefused) {
  if (!has_slepc()) {
    GTEST_SKIP() << "built without SLEPc";
  }
  PetscArrheniusBratu bratu(PETSC_COMM_WORLD, 1, 60);
  const ScaledPetscProblem scaled(bratu);
  const ArrheniusBratu serial(60);
  const TriangleMesh mesh = strip_across_the_folds(serial);
  try {
    compute_distributed_stability(scaled, mesh);
    ADD_FAILURE() << "no exception";
  } catch (const InvalidArgument& error) {
    EXPECT_NE(std::string(error.what()).find("declares no dynamics"), std::string::npos)
        << error.what();
  }
}

}  // namespace
}  // namespace tessera::petsc
