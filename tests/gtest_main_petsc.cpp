// GoogleTest entry point shared by all unit tests: initialises SLEPc (which
// initialises PETSc and MPI) so that tests may create PETSc objects, and
// prints test output on rank 0 only. The BLAS kernels first, as pcsim's.
#include <gtest/gtest.h>
#include <mpi.h>
#include <slepcsys.h>

#include "pcsim/core/blas_kernels.hpp"

int main(int argc, char** argv) {
  ::testing::InitGoogleTest(&argc, argv);
  pcsim::select_blas_kernels();  // the kernels the pcsim executable runs (core/blas_kernels.hpp)
  if (SlepcInitialize(&argc, &argv, nullptr, nullptr) != 0) return 1;
  int rank = 0;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  if (rank != 0) {
    auto& listeners = ::testing::UnitTest::GetInstance()->listeners();
    delete listeners.Release(listeners.default_result_printer());
  }
  int result = RUN_ALL_TESTS();
  // A failure on any rank fails the test on every rank.
  int global_result = 0;
  MPI_Allreduce(&result, &global_result, 1, MPI_INT, MPI_MAX, PETSC_COMM_WORLD);
  SlepcFinalize();
  return global_result;
}
