// SPDX-License-Identifier: MIT
// The output of a split mesh (every rank its rows of every vertex, docs/cluster.md): its view
// by reductions over the ranks, its states streamed to rank 0, both as in one process.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "tessera/geometry/triangle_mesh.h"
#include "tessera/io/npy.h"
#include "tessera/io/split_mesh_output.h"
#include "tessera/io/view_mesh.h"
#include "tessera/methods/covering_methods.h"
#include "tessera/petsc/distributed_problem.h"
#include "tessera/petsc/petsc_bratu.h"
#include "tessera/problems/catalogue.h"
#include "tessera/problems/view.h"
#include "petsc/split_support.h"

namespace tessera::petsc {
namespace {

int rank() {
  int value = 0;
  MPI_Comm_rank(PETSC_COMM_WORLD, &value);
  return value;
}

int ranks() {
  int value = 1;
  MPI_Comm_size(PETSC_COMM_WORLD, &value);
  return value;
}

const ProblemSetup& bratu_setup() {
  static const ProblemSetup setup = make_catalogue_problem("bratu2d:N=6");
  return setup;
}

// A covering of bratu2d:N=6 in one process (every rank makes the same one).
const TriangleMesh& serial_mesh() {
  static const TriangleMesh mesh = [] {
    MethodSettings settings;
    settings.step = 0.3;
    const CoveringResult covered = cover(bratu_setup(), find_covering_method("atlas"), settings);
    EXPECT_TRUE(covered.summary.is_complete()) << covered.summary.message;
    return covered.mesh;
  }();
  return mesh;
}

// Two splits of R^n over the ranks: PETSc's even one, and a skewed one where rank 0 holds no
// row (on two ranks or more) and the others ever more, so that blocks and the coordinates
// lambda, epsilon fall on any rank and a rank's part of a block may be empty.
std::vector<std::shared_ptr<const AmbientSpace>> splits(int n) {
  // The space outlives the problem (PETSc's objects must go before PETSc ends).
  const PetscArrheniusBratu bratu(PETSC_COMM_WORLD, 2, 6);
  const DistributedProblem distributed(bratu);
  EXPECT_EQ(distributed.space()->dimension(), n);
  const int count = ranks();
  // Rank r ≥ 1 holds [n (r−1)²/(R−1)², n r²/(R−1)²) of the R − 1 ranks after rank 0.
  const auto boundary = [&](int r) {
    return count == 1 ? n * r : n * (r - 1) * (r - 1) / ((count - 1) * (count - 1));
  };
  const int first = rank() == 0 ? 0 : boundary(rank());
  const int end = rank() == 0 ? (count == 1 ? n : 0) : boundary(rank() + 1);
  return {distributed.space(),
          std::make_shared<DistributedSpace>(PETSC_COMM_WORLD, n, first, end - first)};
}

// The same bits (EXPECT_EQ takes −0.0 for 0.0).
bool is_identical(double a, double b) {
  return std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b);
}

std::string file_bytes(const std::string& path) {
  std::ifstream file(path, std::ios::binary);
  EXPECT_TRUE(file.good()) << path;
  return {std::istreambuf_iterator<char>(file), std::istreambuf_iterator<char>()};
}

// The same bytes (a message naming the files, not their bytes).
bool is_same_file(const std::string& path, const std::string& expected) {
  const std::string bytes = file_bytes(path);
  const bool same = !bytes.empty() && bytes == file_bytes(expected);
  if (!same) {
    ADD_FAILURE() << path << " (" << bytes.size() << " bytes) differs from " << expected;
  }
  return same;
}

// A folder of its own for each test, named by rank 0's process (every rank the same path).
std::filesystem::path test_folder(const std::string& name) {
  int id = static_cast<int>(getpid());
  MPI_Bcast(&id, 1, MPI_INT, 0, PETSC_COMM_WORLD);
  const auto folder = std::filesystem::temp_directory_path() /
                      ("tessera_distributed_output_" + std::to_string(id) + "_" + name);
  if (rank() == 0) {
    std::filesystem::create_directories(folder);
  }
  MPI_Barrier(PETSC_COMM_WORLD);
  return folder;
}

void remove_folder(const std::filesystem::path& folder) {
  MPI_Barrier(PETSC_COMM_WORLD);  // every rank done with it
  if (rank() == 0) {
    std::filesystem::remove_all(folder);
  }
}

TEST(DistributedOutput, TheViewOfASplitMeshIsTheSerialOne) {
  const TriangleMesh& mesh = serial_mesh();
  const ImplicitProblem& problem = *bratu_setup().problem;
  const View view = parse_view(
      "lambda, max:u, min:u, absmax:u, u_3_4, s = lambda * u_1_1 - epsilon, epsilon, mean:u, "
      "norm:u, norm",
      problem);
  const TriangleMesh serial = mesh_in_view(mesh, view);
  ASSERT_EQ(serial.ambient_dimension(), view.size());
  constexpr int kFirstRounded = 7;  // mean:u, norm:u, norm: partial sums added in rank order
  for (const auto& space : splits(problem.ambient_dimension())) {
    const TriangleMesh shown = mesh_in_view(split_rows(mesh, space), view);
    ASSERT_EQ(shown.ambient_dimension(), view.size());
    ASSERT_EQ(shown.vertex_count(), serial.vertex_count());
    EXPECT_EQ(shown.triangles(), serial.triangles());
    int different = 0;
    for (int v = 0; v < serial.vertex_count(); ++v) {
      for (int i = 0; i < view.size(); ++i) {
        const double expected = serial.point(v)(i);
        const double value = shown.point(v)(i);
        if (i < kFirstRounded || ranks() == 1) {
          different += is_identical(value, expected) ? 0 : 1;
        } else {
          EXPECT_NEAR(value, expected, 1e-14 * std::abs(expected) + 1e-300) << view.names()[i];
        }
      }
    }
    EXPECT_EQ(different, 0) << "values not bit for bit the serial view's, split at rank "
                            << rank() << " from row " << space->first_row();
    // Every rank has the same view, to the bit: a hash of its bytes is rank 0's.
    const auto points = shown.points();
    unsigned long long hash = std::hash<std::string_view>{}(std::string_view(
        reinterpret_cast<const char*>(points.data()), sizeof(double) * points.size()));
    unsigned long long root_hash = hash;
    MPI_Bcast(&root_hash, 1, MPI_UNSIGNED_LONG_LONG, 0, PETSC_COMM_WORLD);
    EXPECT_EQ(hash, root_hash);
  }
}

TEST(DistributedOutput, TheStatesOfASplitMeshAreTheSerialFiles) {
  const TriangleMesh& mesh = serial_mesh();
  const int n = bratu_setup().problem->ambient_dimension();
  const auto folder = test_folder("states");
  const std::string serial_path = (folder / "serial.npy").string();
  if (rank() == 0) {
    write_states_npy(serial_path, mesh);
  }
  int case_number = 0;
  for (const auto& space : splits(n)) {
    const TriangleMesh local = split_rows(mesh, space);
    // The default block (every vertex at once here), 7 vertices, 1 vertex at a time.
    const std::size_t vertex_bytes = sizeof(double) * static_cast<std::size_t>(n);
    for (const std::size_t gather_bytes : {kStatesGatherBytes, 7 * vertex_bytes + 5,
                                           std::size_t{1}}) {
      const std::string name = "split" + std::to_string(case_number++) + ".npy";
      const std::string path = (folder / name).string();
      write_split_states_npy(path, local, gather_bytes);
      MPI_Barrier(PETSC_COMM_WORLD);
      if (rank() == 0) {
        EXPECT_TRUE(is_same_file(path, serial_path)) << gather_bytes << " bytes a gather";
        EXPECT_TRUE(is_same_file(triangles_npy_path(path), triangles_npy_path(serial_path)));
        // Only rank 0 wrote: no other file appeared.
        EXPECT_EQ(std::distance(std::filesystem::directory_iterator(folder),
                                std::filesystem::directory_iterator()),
                  2 + 2 * case_number);
      }
    }
    // write_states_npy dispatches to the streaming writer for a split mesh.
    const std::string path = (folder / "dispatched.npy").string();
    write_states_npy(path, local);
    MPI_Barrier(PETSC_COMM_WORLD);
    if (rank() == 0) {
      EXPECT_TRUE(is_same_file(path, serial_path));
      std::filesystem::remove(path);
      std::filesystem::remove(triangles_npy_path(path));
    }
  }
  remove_folder(folder);
}

// The CLI's writer: the mesh file in a view (exact functionals, so the same bytes), every
// coordinate (n = 38 ≤ 50: gathered), the states.
TEST(DistributedOutput, TheMeshFilesOfASplitMeshAreTheSerialFiles) {
  const TriangleMesh& mesh = serial_mesh();
  const ImplicitProblem& problem = *bratu_setup().problem;
  const auto folder = test_folder("files");
  MeshFileOptions options;
  options.comments = {"a split mesh"};
  const View view = parse_view("lambda, epsilon, max:u, min:u", problem);
  const View every = all_coordinates_view(problem);
  const MeshOutput serial_in_view{(folder / "serial_view.ply").string(), view, options,
                                  (folder / "serial.npy").string()};
  const MeshOutput serial_whole{(folder / "serial_whole.vtk").string(), every, options, ""};
  if (rank() == 0) {
    EXPECT_EQ(write_mesh_output(mesh, serial_in_view).size(), 3u);
    write_mesh_output(mesh, serial_whole);
  }
  for (const auto& space : splits(problem.ambient_dimension())) {
    const TriangleMesh local = split_rows(mesh, space);
    const MeshOutput in_view{(folder / "view.ply").string(), view, options,
                             (folder / "states.npy").string()};
    const MeshOutput whole{(folder / "whole.vtk").string(), every, options, ""};
    const std::vector<std::string> written = write_mesh_output(local, in_view);
    EXPECT_EQ(written, (std::vector<std::string>{in_view.mesh_path, in_view.states_path,
                                                 triangles_npy_path(in_view.states_path)}));
    write_mesh_output(local, whole);
    MPI_Barrier(PETSC_COMM_WORLD);
    if (rank() == 0) {
      EXPECT_TRUE(is_same_file(in_view.mesh_path, serial_in_view.mesh_path));
      EXPECT_TRUE(is_same_file(in_view.states_path, serial_in_view.states_path));
      EXPECT_TRUE(is_same_file(triangles_npy_path(in_view.states_path),
                               triangles_npy_path(serial_in_view.states_path)));
      EXPECT_TRUE(is_same_file(whole.mesh_path, serial_whole.mesh_path));
    }
    MPI_Barrier(PETSC_COMM_WORLD);  // read before the next split writes again
  }
  remove_folder(folder);
}

// Every coordinate of a split mesh at large n is refused before any communication, naming
// the way out; in one process it is the ordinary writer.
TEST(DistributedOutput, EveryCoordinateOfALargeSplitMeshIsRefused) {
  const ProblemSetup setup = make_catalogue_problem("bvp:points=100");
  const int n = setup.problem->ambient_dimension();
  ASSERT_GT(n, kMaxGatheredDimension);
  const View every = all_coordinates_view(*setup.problem);
  const int first = n * rank() / ranks();
  const auto space = std::make_shared<DistributedSpace>(PETSC_COMM_WORLD, n, first,
                                                        n * (rank() + 1) / ranks() - first);
  EXPECT_NO_THROW(check_split_mesh_output(AmbientSpace(n), every));
  EXPECT_NO_THROW(check_split_mesh_output(*space, default_view(*setup.problem)));
  try {
    check_split_mesh_output(*space, every);
    ADD_FAILURE() << "every coordinate of a split mesh in R^" << n << " was not refused";
  } catch (const InvalidArgument& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find("--states"), std::string::npos) << message;
    EXPECT_NE(message.find("--view"), std::string::npos) << message;
  }
  TriangleMesh local(Eigen::MatrixXd::Zero(space->local_rows(), 3), {{0, 1, 2}});
  local.set_space(space);
  EXPECT_THROW(write_mesh_output(local, {"never.ply", every, {}, ""}), InvalidArgument);
}

// A file rank 0 cannot write fails every rank (none waits in a gather for it).
TEST(DistributedOutput, AFailedWriteFailsEveryRank) {
  const TriangleMesh& mesh = serial_mesh();
  const ImplicitProblem& problem = *bratu_setup().problem;
  const std::string missing = "/nonexistent-tessera-folder/states.npy";
  for (const auto& space : splits(problem.ambient_dimension())) {
    const TriangleMesh local = split_rows(mesh, space);
    EXPECT_THROW(write_split_states_npy(missing, local, 1), InvalidArgument);
    EXPECT_THROW(write_mesh_in_view("/nonexistent-tessera-folder/view.ply", local,
                                    parse_view("lambda, epsilon, max:u", problem)),
                 InvalidArgument);
  }
}

}  // namespace
}  // namespace tessera::petsc
