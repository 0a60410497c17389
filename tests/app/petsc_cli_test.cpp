// SPDX-License-Identifier: MIT
// `mpiexec -n 2 tessera mesh … --backend petsc` as a cluster user runs it: the same mesh as the
// serial backend (states and triangles from --states, gathered from the ranks' rows), written
// once, the backend in the summary; and the misuses a user meets get a usage error that names the problem.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "io/npy_test_support.h"
#include "support/test_support.h"
#include "tessera/problems/catalogue.h"

namespace tessera {
namespace {

namespace fs = std::filesystem;
using npy_test::read_npy;
using testing::run_cli;
using testing::run_shell;

constexpr int kUsageError = 2;

bool contains(const std::string& text, const std::string& fragment) {
  return text.find(fragment) != std::string::npos;
}

// The catalogue's bvp with N = 20 in a small box around its start, so that the test covers a
// few hundred vertices: MUMPS's set-up costs milliseconds per factorisation at this n.
std::string small_bvp_run() {
  const ProblemSetup setup = make_catalogue_problem("bvp:points=20");
  const int n = setup.problem->ambient_dimension();
  const double lambda = setup.start(n - 2);
  const double epsilon = setup.start(n - 1);
  return "mesh bvp:points=20 --box lambda=" + std::to_string(lambda - 0.3) + ":" +
         std::to_string(lambda + 0.3) + ",epsilon=" + std::to_string(epsilon - 0.05) + ":" +
         std::to_string(epsilon + 0.05) + " --tolerance 0.02";
}

#if defined(TESSERA_MPIEXEC)

std::string mpiexec(int ranks) {
  // CI runs as root, which Open MPI refuses unless told; 2 ranks on 2 cores may oversubscribe.
  return std::string("env OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 ") +
         TESSERA_MPIEXEC + " -n " + std::to_string(ranks) + " --oversubscribe ";
}

// `run` on the serial backend and on two ranks with split states: the serial states (to 1e-8)
// and triangles, written once, valid, with the serial work. \return the PETSc run's output.
std::string expect_two_ranks_give_the_serial_mesh(const std::string& run,
                                                  const std::string& folder) {
  const auto serial = run_cli(run + " -o " + folder + "/serial.ply --states " + folder +
                              "/serial.npy --summary " + folder + "/serial.json -q");
  EXPECT_EQ(serial.exit_code, 0) << serial.output;
  const auto petsc = run_shell(mpiexec(2) + TESSERA_CLI + " " + run + " --backend petsc -o " +
                               folder + "/petsc.ply --states " + folder + "/petsc.npy --summary " +
                               folder + "/petsc.json");
  EXPECT_EQ(petsc.exit_code, 0) << petsc.output;
  if (serial.exit_code != 0 || petsc.exit_code != 0) {
    return petsc.output;
  }
  const auto serial_states = read_npy(folder + "/serial.npy");
  const auto petsc_states = read_npy(folder + "/petsc.npy");
  EXPECT_EQ(petsc_states.rows, serial_states.rows);
  EXPECT_EQ(petsc_states.columns, serial_states.columns);
  EXPECT_GT(serial_states.rows, 100);
  if (petsc_states.reals.size() == serial_states.reals.size()) {
    double largest_gap = 0.0;
    for (std::size_t k = 0; k < serial_states.reals.size(); ++k) {
      largest_gap =
          std::max(largest_gap, std::abs(serial_states.reals[k] - petsc_states.reals[k]));
    }
    EXPECT_LE(largest_gap, 1e-8);
  }
  const auto serial_triangles = read_npy(folder + "/serial.triangles.npy");
  const auto petsc_triangles = read_npy(folder + "/petsc.triangles.npy");
  EXPECT_EQ(petsc_triangles.integers, serial_triangles.integers);

  std::ifstream summary_file(folder + "/petsc.json");
  const auto summary = nlohmann::json::parse(summary_file);
  EXPECT_EQ(summary["backend"]["name"], "petsc");
  EXPECT_EQ(summary["backend"]["ranks"], 2);
  EXPECT_EQ(summary["backend"]["states"], "split");  // each rank its rows
  EXPECT_TRUE(summary["valid"].get<bool>());
  std::ifstream serial_summary_file(folder + "/serial.json");
  const auto serial_summary = nlohmann::json::parse(serial_summary_file);
  EXPECT_EQ(serial_summary["backend"]["name"], "serial");
  // The work is the serial backend's: the same steps, the factorisations by MUMPS.
  EXPECT_EQ(summary["run"]["factorisations"], serial_summary["run"]["factorisations"]);
  EXPECT_EQ(summary["run"]["jacobian_evaluations"], serial_summary["run"]["jacobian_evaluations"]);
  return petsc.output;
}

TEST(PetscCli, TwoRanksWriteTheSerialBackendsMeshOnce) {
  const std::string output = expect_two_ranks_give_the_serial_mesh(
      small_bvp_run(), testing::temporary_directory("petsc_cli"));
  // One report (rank 0 prints, the other rank computes alongside).
  EXPECT_EQ(output.find("wrote "), output.rfind("wrote ")) << output;
  EXPECT_TRUE(contains(output, "backend        petsc on 2 ranks")) << output;
}

// The advancing front on split states: the serial backend's states and triangles, from each
// rank's rows of every vertex.
TEST(PetscCli, TheFrontOnTwoRanksSplitsTheStatesAndGivesTheSerialMesh) {
  expect_two_ranks_give_the_serial_mesh(small_bvp_run() + " --method front",
                                        testing::temporary_directory("petsc_cli_front"));
}

TEST(PetscCli, AProblemWithoutAPetscImplementationIsAUsageErrorOnEveryRank) {
  const std::string folder = testing::temporary_directory("petsc_cli_misuse");
  const auto result =
      run_shell(mpiexec(2) + TESSERA_CLI + " mesh torus --backend petsc -o " + folder + "/t.ply");
  EXPECT_EQ(result.exit_code, kUsageError) << result.output;
  EXPECT_TRUE(contains(result.output, "problem 'torus' has no PETSc implementation"))
      << result.output;
  EXPECT_FALSE(fs::exists(folder + "/t.ply"));
}

// SuperLU_dist aborted the job (its own abort, exit 255) on the border rows' zero diagonal:
// now a usage error naming the reason, on every rank, before any work.
TEST(PetscCli, SuperLuDistIsRefusedWithTheReason) {
  const std::string folder = testing::temporary_directory("petsc_cli_superlu");
  const auto result = run_shell(mpiexec(2) + TESSERA_CLI + " " + small_bvp_run() +
                                " --backend petsc -o " + folder +
                                "/s.ply -pc_factor_mat_solver_type superlu_dist");
  EXPECT_EQ(result.exit_code, kUsageError) << result.output;
  EXPECT_TRUE(contains(result.output, "superlu_dist cannot factor")) << result.output;
  EXPECT_TRUE(contains(result.output, "MC64")) << result.output;
  EXPECT_FALSE(fs::exists(folder + "/s.ply"));
}

#endif

TEST(PetscCli, PetscOptionsNeedThePetscBackend) {
  const std::string folder = testing::temporary_directory("petsc_cli_options");
  const auto result = run_cli(small_bvp_run() + " -o " + folder + "/x.ply -ksp_type gmres");
  EXPECT_EQ(result.exit_code, kUsageError) << result.output;
  EXPECT_TRUE(contains(result.output, "-ksp_type")) << result.output;
  EXPECT_TRUE(contains(result.output, "--backend petsc")) << result.output;
  const auto elsewhere = run_cli("problems -log_view");
  EXPECT_EQ(elsewhere.exit_code, kUsageError) << elsewhere.output;
  EXPECT_TRUE(contains(elsewhere.output, "-log_view is an option of PETSc")) << elsewhere.output;
}

TEST(PetscCli, AnUnknownBackendIsAUsageError) {
  const auto result = run_cli("mesh sphere --backend cuda -o /tmp/never.ply");
  EXPECT_EQ(result.exit_code, kUsageError) << result.output;
  EXPECT_TRUE(contains(result.output, "--backend")) << result.output;
}

}  // namespace
}  // namespace tessera
