// SPDX-License-Identifier: MIT
// `tessera mesh --backend`: where the linear algebra runs. "serial": tessera's own sparse LU or
// dense QR in this process. "petsc": F, DF and the factorisations of the bordered Jacobian on
// PETSc's distributed objects (MUMPS by default) over the ranks of mpirun, every rank running
// the same covering. The atlas and the front run on split states (each rank holds its rows of
// every vertex, petsc::DistributedProblem); bezier on whole ones (petsc::ReplicatedProblem).
// docs/cluster.md.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "tessera/methods/covering_methods.h"
#include "tessera/problems/problem_setup.h"

namespace tessera {
struct StabilityOptions;
struct StabilityOutput;
class TriangleMesh;
}  // namespace tessera

namespace tessera::app {

/// Moves PETSc's own options out of argv (so that the command line parser does not see them):
/// an argument of one dash, a letter and an underscore somewhere (-ksp_type, -pc_type,
/// -mat_mumps_icntl_14, -log_view), with the argument after it when that is its value (does not
/// start with '-', or is a number). PETSc's options therefore go last on the command line.
std::vector<std::string> take_petsc_options(int& argc, char** argv);

/// `tessera` without PETSc: if the command line asks for --backend petsc, replaces this process
/// by `tessera-petsc` from the same folder (execv, same arguments), which has the backend; the
/// plain program does not load PETSc, MPI and their libraries (35 ms at every start). Returns
/// where nothing is to be done, or where that program is not there (SolverBackend then says so).
void become_petsc_program_if_asked(int argc, char** argv);

class SolverBackend {
 public:
  /// Starts the backend: for "petsc", PETSc (and MPI, when mpirun did not) with `petsc_options`.
  /// \throw InvalidArgument for an unknown name, for "petsc" in a tessera built without PETSc,
  ///        or for PETSc options given to the serial backend.
  SolverBackend(const std::string& name, const std::vector<std::string>& petsc_options);
  ~SolverBackend();
  SolverBackend(const SolverBackend&) = delete;
  SolverBackend& operator=(const SolverBackend&) = delete;

  const std::string& name() const { return name_; }
  /// This process's rank and the number of ranks (0 and 1 for the serial backend).
  int rank() const;
  int ranks() const;
  /// The rank that prints and writes files; the others compute alongside it.
  bool is_root() const { return rank() == 0; }
  /// True on every rank if `value` is true on any (collective on the PETSc backend): what one
  /// process notices (a signal, a spent time budget) becomes every rank's decision, so that
  /// the ranks keep making the same collective calls.
  bool any_rank(bool value) const;
  /// Puts setup's problem on this backend (PETSc: the catalogue's bvp and bratu2d), with the
  /// same start, domain and coordinate names. The backend must outlive the setup's problem.
  /// With `split_states` (the atlas, the front), every rank holds its rows of every n-vector:
  /// setup's problem, start and domain become this rank's rows of them (the mesh's points will
  /// be too).
  /// \throw InvalidArgument if the problem has no implementation on the backend.
  void adopt(ProblemSetup& setup, bool split_states = false);
  /// Whether adopt split the states.
  bool splits_states() const;
  /// tessera::cover on this backend: on split states the covering runs on the problem in its
  /// metric's coordinates y = W x (ScaledPetscProblem) and its mesh comes back to x.
  CoveringResult cover(const ProblemSetup& setup, const CoveringMethod& method,
                       const MethodSettings& settings) const;
  /// Refuses `option` (--stability, or what implies it) before the covering if this backend
  /// cannot compute eigenvalues: the PETSc backend of a tessera built without SLEPc.
  /// \throw InvalidArgument naming the option and how to get SLEPc.
  void check_stability_available(const std::string& option) const;
  /// The stability of every vertex of `mesh` (setup's problem, after cover) and its report:
  /// compute_stability_output, or on the PETSc backend on the ranks with MUMPS and SLEPc
  /// (petsc::compute_distributed_stability), split states or whole. The same on every rank.
  /// Collective on the PETSc backend.
  /// \throw InvalidArgument if the problem declares no dynamics.
  StabilityOutput stability_output(const ProblemSetup& setup, const TriangleMesh& mesh,
                                   const StabilityOptions& options) const;
  /// Ends every rank with `code` (MPI_Abort): after an error on some ranks, the others may wait
  /// in a collective call forever. The serial backend exits.
  [[noreturn]] void abort(int code) const;

 private:
  struct Petsc;
  void adopt_split(ProblemSetup& setup);
  std::string name_;
  std::unique_ptr<Petsc> petsc_;
};

}  // namespace tessera::app
