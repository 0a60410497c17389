// SPDX-License-Identifier: MIT
#include "tessera/petsc/petsc_support.h"

#if defined(TESSERA_HAS_SLEPC)
#include <slepcsys.h>
#endif

#include "tessera/core/error.h"

namespace tessera::petsc {

void check(PetscErrorCode code, const char* what) {
  if (code == 0) {
    return;
  }
  const char* text = nullptr;
  char* specific = nullptr;  // the message of the error's origin, e.g. which pivot was zero
  PetscErrorMessage(code, &text, &specific);
  std::string message = std::string("PETSc: ") + what + " failed: " +
                        (text != nullptr ? text : "unknown error");
  if (specific != nullptr && specific[0] != '\0') {
    message += std::string(": ") + specific;
  }
  throw ComputationFailed(message + " (error " + std::to_string(static_cast<int>(code)) + ")");
}

template <>
void Owned<Vec>::reset() {
  if (handle_ != nullptr) {
    VecDestroy(&handle_);
  }
}
template <>
void Owned<Mat>::reset() {
  if (handle_ != nullptr) {
    MatDestroy(&handle_);
  }
}
template <>
void Owned<KSP>::reset() {
  if (handle_ != nullptr) {
    KSPDestroy(&handle_);
  }
}
template <>
void Owned<VecScatter>::reset() {
  if (handle_ != nullptr) {
    VecScatterDestroy(&handle_);
  }
}

PlacedArray::PlacedArray(Vec v, const double* data) : v_(v) {
  check(VecPlaceArray(v_, const_cast<double*>(data)), "VecPlaceArray");
}

PlacedArray::~PlacedArray() { VecResetArray(v_); }

Owned<Vec> array_vector(MPI_Comm communicator, PetscInt local_rows, PetscInt global_size) {
  Owned<Vec> v;
  check(VecCreateMPIWithArray(communicator, 1, local_rows, global_size, nullptr, v.out()),
        "VecCreateMPIWithArray");
  return v;
}

Session::Session(int* argc, char*** argv) {
#if defined(TESSERA_HAS_SLEPC)
  // SLEPc (the eigenvalues of --stability) starts PETSc and its own packages.
  check(SlepcInitialize(argc, argv, nullptr, nullptr), "SlepcInitialize");
#else
  check(PetscInitialize(argc, argv, nullptr, nullptr), "PetscInitialize");
#endif
  // Errors come back as codes, which `check` turns into exceptions with PETSc's message.
  check(PetscPushErrorHandler(PetscReturnErrorHandler, nullptr), "PetscPushErrorHandler");
}

Session::~Session() {
  PetscPopErrorHandler();
#if defined(TESSERA_HAS_SLEPC)
  SlepcFinalize();
#else
  PetscFinalize();
#endif
}

int Session::rank() const {
  int rank = 0;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  return rank;
}

int Session::size() const {
  int size = 1;
  MPI_Comm_size(PETSC_COMM_WORLD, &size);
  return size;
}

Eigen::VectorXd gather(Vec x) {
  Owned<VecScatter> to_all;
  Owned<Vec> all;
  check(VecScatterCreateToAll(x, to_all.out(), all.out()), "VecScatterCreateToAll");
  check(VecScatterBegin(to_all, x, all, INSERT_VALUES, SCATTER_FORWARD), "VecScatterBegin");
  check(VecScatterEnd(to_all, x, all, INSERT_VALUES, SCATTER_FORWARD), "VecScatterEnd");
  PetscInt n = 0;
  check(VecGetSize(all, &n), "VecGetSize");
  const PetscScalar* values = nullptr;
  check(VecGetArrayRead(all, &values), "VecGetArrayRead");
  Eigen::VectorXd result = Eigen::Map<const Eigen::VectorXd>(values, n);
  check(VecRestoreArrayRead(all, &values), "VecRestoreArrayRead");
  return result;
}

void scatter(const Eigen::Ref<const Eigen::VectorXd>& values, Vec x) {
  PetscInt n = 0;
  PetscInt first = 0;
  PetscInt end = 0;
  check(VecGetSize(x, &n), "VecGetSize");
  TESSERA_CHECK(values.size() == n, "petsc::scatter: " << values.size()
                                                       << " values for a vector of " << n
                                                       << " entries");
  check(VecGetOwnershipRange(x, &first, &end), "VecGetOwnershipRange");
  PetscScalar* local = nullptr;
  check(VecGetArray(x, &local), "VecGetArray");
  for (PetscInt i = first; i < end; ++i) {
    local[i - first] = values(i);
  }
  check(VecRestoreArray(x, &local), "VecRestoreArray");
}

double sum_over_ranks(double value, MPI_Comm communicator) {
  double sum = 0.0;
  MPI_Allreduce(&value, &sum, 1, MPI_DOUBLE, MPI_SUM, communicator);
  return sum;
}

}  // namespace tessera::petsc
