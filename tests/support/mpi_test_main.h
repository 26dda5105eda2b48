// The main of the MPI tests (tests/mpi/): MPI around gtest. Every rank runs every test; rank 0 prints gtest's usual
// report, the other ranks their failures only, each line naming its rank; the run fails when any rank's does.
// Include it once, in the test's source file.
#pragma once

#include <gtest/gtest.h>
#include <mpi.h>

#include <cstdio>

namespace polyfloe::tsupport {

inline int mpi_rank() {
  int r = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &r);
  return r;
}
inline int mpi_ranks() {
  int r = 1;
  MPI_Comm_size(MPI_COMM_WORLD, &r);
  return r;
}

// Collective: whether the running test has failed on any rank. A test that stops early must stop on every rank
// (the others would wait in a collective for ever): `if (any_rank_failed()) return;`, never HasFailure() alone.
inline bool any_rank_failed(MPI_Comm comm = MPI_COMM_WORLD) {
  int mine = ::testing::Test::HasFailure() ? 1 : 0, any = 0;
  MPI_Allreduce(&mine, &any, 1, MPI_INT, MPI_MAX, comm);
  return any != 0;
}

class RankFailures : public ::testing::EmptyTestEventListener {
  void OnTestPartResult(const ::testing::TestPartResult& r) override {
    if (r.failed())
      std::fprintf(stderr, "rank %d: %s:%d: %s\n", mpi_rank(), r.file_name() ? r.file_name() : "?", r.line_number(),
                   r.summary());
  }
};

}  // namespace polyfloe::tsupport

int main(int argc, char** argv) {
  MPI_Init(&argc, &argv);
  ::testing::InitGoogleTest(&argc, argv);
  if (polyfloe::tsupport::mpi_rank() != 0) {
    auto& listeners = ::testing::UnitTest::GetInstance()->listeners();
    delete listeners.Release(listeners.default_result_printer());
    listeners.Append(new polyfloe::tsupport::RankFailures);
  }
  int failed = RUN_ALL_TESTS(), any = 0;
  MPI_Allreduce(&failed, &any, 1, MPI_INT, MPI_MAX, MPI_COMM_WORLD);
  MPI_Finalize();
  return any;
}
