// SPDX-License-Identifier: MIT
// What every file of the PETSc backend needs: PETSc error codes turned into tessera's exceptions,
// owners of PETSc objects (destroyed with their scope), the library's start and end, and
// conversions between distributed vectors and Eigen vectors for tests and output.
#pragma once

#include <petscksp.h>

#include <Eigen/Core>
#include <string>
#include <utility>

namespace tessera::petsc {

/// Throws ComputationFailed naming `what` and PETSc's own message when `code` is an error.
/// Errors are returned, not printed: Session installs PETSc's return-error handler.
void check(PetscErrorCode code, const char* what);

/// Owns one PETSc object: `Owned<Vec>`, `Owned<Mat>`, `Owned<KSP>`, `Owned<VecScatter>`.
/// Move-only; the object is destroyed with the owner.
template <typename Handle>
class Owned {
 public:
  Owned() = default;
  explicit Owned(Handle handle) : handle_(handle) {}
  ~Owned() { reset(); }
  Owned(const Owned&) = delete;
  Owned& operator=(const Owned&) = delete;
  Owned(Owned&& other) noexcept : handle_(std::exchange(other.handle_, nullptr)) {}
  Owned& operator=(Owned&& other) noexcept {
    if (this != &other) {
      reset();
      handle_ = std::exchange(other.handle_, nullptr);
    }
    return *this;
  }
  Handle get() const { return handle_; }
  operator Handle() const { return handle_; }  // NOLINT: passes to PETSc's C functions
  /// For PETSc's create functions: `VecDuplicate(x, v.out())`. Destroys what was held.
  Handle* out() {
    reset();
    return &handle_;
  }
  explicit operator bool() const { return handle_ != nullptr; }
  void reset();

 private:
  Handle handle_ = nullptr;
};

/// Lends an array (Eigen's memory) to a vector made by `array_vector` for the object's lifetime,
/// without copying (VecPlaceArray … VecResetArray).
class PlacedArray {
 public:
  PlacedArray(Vec v, const double* data);
  ~PlacedArray();
  PlacedArray(const PlacedArray&) = delete;
  PlacedArray& operator=(const PlacedArray&) = delete;

 private:
  Vec v_;
};

/// A distributed vector of `global_size` entries, `local_rows` of them here, with no memory of
/// its own: PlacedArray lends it an array for a call.
Owned<Vec> array_vector(MPI_Comm communicator, PetscInt local_rows, PetscInt global_size);

/// Starts PETSc (and MPI, if nobody did) for the object's lifetime and makes PETSc return its
/// errors instead of printing them. One per process, before any other PETSc call: the CLI's
/// main and the tests' main make it. `argc`/`argv` carry PETSc's options (-ksp_type, -pc_type,
/// -mat_mumps_icntl_14, …); PETSc leaves the others alone.
class Session {
 public:
  Session(int* argc, char*** argv);
  ~Session();
  Session(const Session&) = delete;
  Session& operator=(const Session&) = delete;
  MPI_Comm communicator() const { return PETSC_COMM_WORLD; }
  int rank() const;
  int size() const;
};

/// All n entries of a distributed vector, on every rank (collective). For tests, output and
/// small vectors: it costs 8n bytes per rank.
Eigen::VectorXd gather(Vec x);
/// Sets the entries this rank owns from a full-length vector (collective).
/// \pre values.size() equals x's global size.
void scatter(const Eigen::Ref<const Eigen::VectorXd>& values, Vec x);

/// Global reductions of this backend's collective code: the sum of `value` over the ranks of
/// `communicator`, and the rank holding the largest value (lowest rank on ties).
double sum_over_ranks(double value, MPI_Comm communicator);

}  // namespace tessera::petsc
