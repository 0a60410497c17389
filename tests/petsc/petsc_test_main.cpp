// SPDX-License-Identifier: MIT
// The main of the PETSc backend's tests: starts PETSc (and MPI) around GoogleTest. Every rank
// runs every test (the backend's functions are collective); rank 0 prints, and the process
// fails on every rank if a test failed on any.
#include <gtest/gtest.h>

#include "tessera/petsc/petsc_support.h"

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  int status = 0;
  {
    tessera::petsc::Session session(&argc, &argv);
    if (session.rank() != 0) {
      auto& listeners = testing::UnitTest::GetInstance()->listeners();
      delete listeners.Release(listeners.default_result_printer());
    }
    const int local = RUN_ALL_TESTS();
    MPI_Allreduce(&local, &status, 1, MPI_INT, MPI_MAX, session.communicator());
  }
  return status;
}
