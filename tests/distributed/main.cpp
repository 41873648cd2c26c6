// The distributed tests' main: MPI for the life of the run (one rank without mpiexec or MPI), and
// gtest's report from rank 0 only. Every rank runs every test in the same order, so that the
// collective calls inside them pair up.
#include <gtest/gtest.h>

#include "distributed/communicator.hpp"

int main(int argc, char** argv) {
  rupture::MpiSession mpi(argc, argv);
  ::testing::InitGoogleTest(&argc, argv);
  if (rupture::Communicator::world().rank() != 0) {
    auto& listeners = ::testing::UnitTest::GetInstance()->listeners();
    delete listeners.Release(listeners.default_result_printer());
  }
  return RUN_ALL_TESTS();
}
