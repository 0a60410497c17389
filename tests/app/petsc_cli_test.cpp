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
#include "tessera/io/mesh_io.h"
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
// few hundred vertices: MUMPS's set-up costs milliseconds per factorisation at this n. The
// report measures 30 points of each kind: below n = 500 it measures every one by default, a
// few collective solves each on two ranks (BothBackendsReportTheSameMeshTheSameWay does).
std::string small_bvp_run() {
  const ProblemSetup setup = make_catalogue_problem("bvp:points=20");
  const int n = setup.problem->ambient_dimension();
  const double lambda = setup.start(n - 2);
  const double epsilon = setup.start(n - 1);
  return "mesh bvp:points=20 --box lambda=" + std::to_string(lambda - 0.3) + ":" +
         std::to_string(lambda + 0.3) + ",epsilon=" + std::to_string(epsilon - 0.05) + ":" +
         std::to_string(epsilon + 0.05) + " --tolerance 0.02 --report-samples 30";
}

#if defined(TESSERA_MPIEXEC)

// bratu2d with N = 8 (n = 66, grid values weighted by the mesh width in its metric) in a box
// around its start: about 300 vertices.
std::string small_bratu2d_run() {
  const ProblemSetup setup = make_catalogue_problem("bratu2d:N=8");
  const int n = setup.problem->ambient_dimension();
  const double lambda = setup.start(n - 2);
  return "mesh bratu2d:N=8 --box lambda=" + std::to_string(lambda - 0.35) + ":" +
         std::to_string(lambda + 0.35) + ",epsilon=0.15:0.25 --tolerance 0.02";
}

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

nlohmann::json read_summary(const std::string& path) {
  std::ifstream file(path);
  return nlohmann::json::parse(file);
}

// Two reports of the same mesh (its vertices within 1e-10, the same triangles) agree: counts,
// topology, validity, shape and area, and the distances with the number of points measured.
void expect_same_report(const nlohmann::json& serial, const nlohmann::json& petsc) {
  EXPECT_EQ(petsc["counts"], serial["counts"]);
  EXPECT_EQ(petsc["topology"], serial["topology"]);
  EXPECT_EQ(petsc["valid"], serial["valid"]);
  const auto near = [](const nlohmann::json& a, const nlohmann::json& b, const char* what) {
    const double x = a.get<double>();
    const double y = b.get<double>();
    // Vertices 1e-10 apart move angles, lengths and areas by ~1e-10 relative to the shortest
    // edge (1.7e-3 here).
    EXPECT_NEAR(x, y, 1e-6 * (1.0 + std::abs(y))) << what;
  };
  for (const char* key :
       {"min_angle_degrees", "max_angle_degrees", "min_edge_length", "max_edge_length", "area"}) {
    near(petsc["shape"][key], serial["shape"][key], key);
  }
  // An angle within 1e-6° of 30° would be a coincidence.
  EXPECT_EQ(petsc["shape"]["fraction_angles_below_30_degrees"],
            serial["shape"]["fraction_angles_below_30_degrees"]);
  const auto& distances = petsc["distance_to_manifold"];
  const auto& serial_distances = serial["distance_to_manifold"];
  EXPECT_EQ(distances["failed_projections"], serial_distances["failed_projections"]);
  for (const char* kind : {"vertex_residual_F", "vertices", "centroids", "edge_midpoints"}) {
    SCOPED_TRACE(kind);
    EXPECT_EQ(distances[kind]["count"], serial_distances[kind]["count"]);
    EXPECT_EQ(distances[kind]["population"], serial_distances[kind]["population"]);
    // Every point below n = 500 (--report-samples' help), within the time budget.
    EXPECT_EQ(distances[kind]["count"], distances[kind]["population"]);
  }
  // The vertices lie on M to the corrector's tolerance on both backends: their distances and
  // residuals are rounding, not comparable digit by digit.
  EXPECT_LE(distances["vertices"]["max"].get<double>(), 1e-8);
  EXPECT_LE(distances["vertex_residual_F"]["max"].get<double>(), 1e-8);
  // Centroids and midpoints are O(h²) off M: the same projections give the same distances.
  for (const char* kind : {"centroids", "edge_midpoints"}) {
    for (const char* statistic : {"max", "mean"}) {
      const double x = distances[kind][statistic].get<double>();
      const double y = serial_distances[kind][statistic].get<double>();
      EXPECT_NEAR(x, y, 1e-6 * y + 1e-12) << kind << " " << statistic;
    }
  }
}

// One code path measures the report for every backend (issue 33): bratu2d's split mesh on the
// PETSc backend, on one rank and on two, gets the serial report of the same mesh. Its shape was
// measured in x instead of the problem's metric (at N = 32 angles 0.6°…179° for the serial
// 6.5°…143°, area 10454 for 128.65), its distances by Gauss–Newton instead of the serial chord,
// and the time budget of the report's samples from n = 500 on cut it below too (356 of N = 8's
// points on two ranks, where a factorisation by MUMPS costs a hundred serial ones).
TEST(PetscCli, BothBackendsReportTheSameMeshTheSameWay) {
  const std::string folder = testing::temporary_directory("petsc_cli_report");
  const std::string run = small_bratu2d_run() + " -q";
  // The PETSc backend does not share factorisations yet (issue 30); the serial run is told not
  // to either, so that both make the same mesh.
  const auto serial = run_shell("env TESSERA_SHARE_FACTORISATIONS=off " + std::string(TESSERA_CLI) +
                                " " + run + " -o " + folder + "/serial.ply --summary " + folder +
                                "/serial.json");
  ASSERT_EQ(serial.exit_code, 0) << serial.output;
  const nlohmann::json serial_summary = read_summary(folder + "/serial.json");
  EXPECT_EQ(serial_summary["ambient_dimension"], 66);
  for (int ranks : {1, 2}) {
    SCOPED_TRACE(std::to_string(ranks) + " rank(s)");
    const std::string name = folder + "/petsc" + std::to_string(ranks);
    const auto petsc = run_shell(mpiexec(ranks) + TESSERA_CLI + " " + run + " --backend petsc -o " +
                                 name + ".ply --summary " + name + ".json");
    ASSERT_EQ(petsc.exit_code, 0) << petsc.output;
    const nlohmann::json summary = read_summary(name + ".json");
    EXPECT_EQ(summary["backend"]["ranks"], ranks);
    EXPECT_EQ(summary["backend"]["states"], "split");
    expect_same_report(serial_summary, summary);
  }
}

// A run without a valid mesh (here: the start is too far from M) is validated by the report,
// not by the covering: on split states that threw ("has a metric; work in the metric's
// coordinates", exit 2) until 2026-11-28; now the report of the empty mesh, exit 1, as serially.
TEST(PetscCli, ARunWithoutAMeshIsReportedAsOnTheSerialBackend) {
  const std::string folder = testing::temporary_directory("petsc_cli_no_mesh");
  std::string start;
  for (int i = 0; i < 64; ++i) {
    start += "1,";
  }
  const std::string run = "mesh bratu2d:N=8 --start " + start +
                          "8,0.2 --max-start-distance 0.001 -q --summary " + folder +
                          "/summary.json -o " + folder + "/never.ply";
  const auto petsc = run_shell(mpiexec(1) + TESSERA_CLI + " " + run + " --backend petsc");
  EXPECT_EQ(petsc.exit_code, 1) << petsc.output;
  EXPECT_TRUE(contains(petsc.output, "start point failed")) << petsc.output;
  const nlohmann::json summary = read_summary(folder + "/summary.json");
  EXPECT_EQ(summary["run"]["termination"], "start point failed");
  EXPECT_EQ(summary["counts"]["triangles"], 0);
  EXPECT_FALSE(fs::exists(folder + "/never.ply"));
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

const std::vector<double>& scalars(const std::vector<VertexScalars>& data,
                                   const std::string& name) {
  for (const VertexScalars& scalars : data) {
    if (scalars.name == name) {
      return scalars.values;
    }
  }
  ADD_FAILURE() << "no point data " << name;
  static const std::vector<double> none;
  return none;
}

// `--stability` on two ranks, the states split: the serial counts vertex for vertex in the mesh
// file's point data (the same mesh, see expect_two_ranks_give_the_serial_mesh), certain (the
// inertia of MUMPS's LDLT), and the summary's stability block the serial one's.
TEST(PetscCli, StabilityOnTwoRanksHasTheSerialCounts) {
  const std::string folder = testing::temporary_directory("petsc_cli_stability");
  // A smaller box than small_bratu2d_run's, across the ignition fold: about 150 vertices, 88 of
  // them on the middle sheet (1 unstable eigenvalue), for a test of seconds on two ranks.
  const ProblemSetup setup = make_catalogue_problem("bratu2d:N=8");
  const double lambda = setup.start(setup.problem->ambient_dimension() - 2);
  const std::string run = "mesh bratu2d:N=8 --box lambda=" + std::to_string(lambda - 0.2) + ":" +
                          std::to_string(lambda + 0.2) +
                          ",epsilon=0.18:0.22 --tolerance 0.04 --report-samples 30 --stability";
  // The PETSc backend does not share factorisations yet (docs/cluster.md): the serial run
  // without sharing gives its mesh, vertex for vertex (with sharing, the same mesh to the
  // corrector's tolerance only: the chords from a borrowed factorisation stop farther from
  // their limit, and the Ritz values differed by 10⁻⁶ near the fold).
  const auto serial = run_shell("env TESSERA_SHARE_FACTORISATIONS=off " +
                                std::string(TESSERA_CLI) + " " + run + " -o " + folder +
                                "/serial.vtu --summary " + folder + "/serial.json -q");
  ASSERT_EQ(serial.exit_code, 0) << serial.output;
  const auto petsc = run_shell(mpiexec(2) + TESSERA_CLI + " " + run + " --backend petsc -o " +
                               folder + "/petsc.vtu --summary " + folder + "/petsc.json");
  ASSERT_EQ(petsc.exit_code, 0) << petsc.output;
  EXPECT_TRUE(contains(petsc.output, "counts from the inertia of s·D_uF (Sylvester's law): exact"))
      << petsc.output;
  const nlohmann::json expected = read_summary(folder + "/serial.json")["stability"];
  const nlohmann::json summary = read_summary(folder + "/petsc.json");
  EXPECT_EQ(summary["backend"]["states"], "split");
  const nlohmann::json& stability = summary["stability"];
  for (const char* key :
       {"parameters", "vertices", "stable_vertices", "vertices_by_index", "failed_vertices",
        "uncertain_vertices", "eigenvalues_per_vertex", "certainty"}) {
    EXPECT_EQ(stability.at(key), expected.at(key)) << key;
  }
  EXPECT_EQ(stability.at("uncertain_vertices"), 0);
  EXPECT_GE(stability.at("vertices_by_index").size(), 2u);  // the box reaches the unstable sheet
  EXPECT_EQ(stability.at("jacobian_evaluations"), stability.at("vertices"));
  std::vector<VertexScalars> serial_data;
  std::vector<VertexScalars> petsc_data;
  const TriangleMesh serial_mesh = read_mesh(folder + "/serial.vtu", serial_data);
  const TriangleMesh petsc_mesh = read_mesh(folder + "/petsc.vtu", petsc_data);
  ASSERT_EQ(petsc_mesh.vertex_count(), serial_mesh.vertex_count());
  EXPECT_EQ(scalars(petsc_data, "unstable_count"), scalars(serial_data, "unstable_count"));
  EXPECT_EQ(scalars(petsc_data, "stability_certain"), scalars(serial_data, "stability_certain"));
  const auto& leading = scalars(petsc_data, "leading_real_part");
  const auto& serial_leading = scalars(serial_data, "leading_real_part");
  ASSERT_EQ(leading.size(), serial_leading.size());
  for (std::size_t v = 0; v < leading.size(); ++v) {
    // Ritz values to 1e-10 relative, at vertices 1e-10 apart.
    EXPECT_NEAR(leading[v], serial_leading[v], 1e-7 * (1.0 + std::abs(serial_leading[v])))
        << "vertex " << v;
  }
}

// The Hopf curves need complex distributed systems, which the PETSc backend does not have: a
// usage error before the covering, naming what does work.
TEST(PetscCli, HopfIsRefusedOnThePetscBackendWithTheReason) {
  const std::string folder = testing::temporary_directory("petsc_cli_hopf");
  for (const std::string& option : {std::string("--hopf"), "--diagram " + folder + "/d.png"}) {
    const auto result = run_shell(mpiexec(2) + TESSERA_CLI + " " + small_bvp_run() + " " + option +
                                  " --backend petsc -o " + folder + "/h.ply");
    EXPECT_EQ(result.exit_code, kUsageError) << result.output;
    EXPECT_TRUE(contains(result.output, "not yet available with --backend petsc")) << result.output;
    EXPECT_TRUE(contains(result.output, "--stability alone runs on the PETSc backend"))
        << result.output;
    EXPECT_FALSE(fs::exists(folder + "/h.ply"));
  }
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
