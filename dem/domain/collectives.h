// The collectives the domain's layers share: every rank's lists to every rank (counts, then the items).
#pragma once

#include <mpi.h>

#include <algorithm>
#include <cstddef>
#include <limits>
#include <stdexcept>
#include <type_traits>
#include <vector>

namespace polyfloe::domain {

// Collective over `comm`: out[q] (any length, possibly empty) to rank q; returns in[q], what rank q sent this one.
// T is copied as bytes (trivially copyable, no padding that matters to the receiver).
template <class T>
std::vector<std::vector<T>> all_to_all(MPI_Comm comm, const std::vector<std::vector<T>>& out) {
  static_assert(std::is_trivially_copyable_v<T>);
  int ranks = 1;
  MPI_Comm_size(comm, &ranks);
  if (out.size() != static_cast<std::size_t>(ranks))
    throw std::invalid_argument("all_to_all: one list per rank of the communicator is needed");
  const auto n = out.size();
  std::vector<int> send_count(n), recv_count(n), send_at(n + 1, 0), recv_at(n + 1, 0);
  for (std::size_t q = 0; q < n; ++q) {
    if (out[q].size() * sizeof(T) > static_cast<std::size_t>(std::numeric_limits<int>::max() / 2))
      throw std::length_error("all_to_all: a message of more than 1 GiB");
    send_count[q] = static_cast<int>(out[q].size() * sizeof(T));
  }
  MPI_Alltoall(send_count.data(), 1, MPI_INT, recv_count.data(), 1, MPI_INT, comm);
  for (std::size_t q = 0; q < n; ++q) {
    send_at[q + 1] = send_at[q] + send_count[q];
    recv_at[q + 1] = recv_at[q] + recv_count[q];
  }
  std::vector<T> flat_out(static_cast<std::size_t>(send_at[n]) / sizeof(T));
  std::vector<T> flat_in(static_cast<std::size_t>(recv_at[n]) / sizeof(T));
  for (std::size_t q = 0; q < n; ++q)
    std::copy(out[q].begin(), out[q].end(), flat_out.begin() + send_at[q] / static_cast<int>(sizeof(T)));
  MPI_Alltoallv(flat_out.data(), send_count.data(), send_at.data(), MPI_BYTE, flat_in.data(), recv_count.data(),
                recv_at.data(), MPI_BYTE, comm);
  std::vector<std::vector<T>> in(n);
  for (std::size_t q = 0; q < n; ++q)
    in[q].assign(flat_in.begin() + recv_at[q] / static_cast<int>(sizeof(T)),
                 flat_in.begin() + recv_at[q + 1] / static_cast<int>(sizeof(T)));
  return in;
}

// Collective over `comm`: every rank's `mine` to every rank, by rank.
template <class T>
std::vector<std::vector<T>> all_gather(MPI_Comm comm, const std::vector<T>& mine) {
  static_assert(std::is_trivially_copyable_v<T>);
  int ranks = 1;
  MPI_Comm_size(comm, &ranks);
  if (mine.size() * sizeof(T) > static_cast<std::size_t>(std::numeric_limits<int>::max() / 2))
    throw std::length_error("all_gather: a message of more than 1 GiB");
  const int bytes = static_cast<int>(mine.size() * sizeof(T));
  const auto n = static_cast<std::size_t>(ranks);
  std::vector<int> count(n), at(n + 1, 0);
  MPI_Allgather(&bytes, 1, MPI_INT, count.data(), 1, MPI_INT, comm);
  for (std::size_t q = 0; q < n; ++q) at[q + 1] = at[q] + count[q];
  std::vector<T> flat(static_cast<std::size_t>(at[n]) / sizeof(T));
  MPI_Allgatherv(mine.data(), bytes, MPI_BYTE, flat.data(), count.data(), at.data(), MPI_BYTE, comm);
  std::vector<std::vector<T>> in(n);
  for (std::size_t q = 0; q < n; ++q)
    in[q].assign(flat.begin() + at[q] / static_cast<int>(sizeof(T)),
                 flat.begin() + at[q + 1] / static_cast<int>(sizeof(T)));
  return in;
}

// Collective over `comm`: every rank's `mine` to `root`, which gets them by rank (the others an empty list).
template <class T>
std::vector<std::vector<T>> gather_to(MPI_Comm comm, int root, const std::vector<T>& mine) {
  static_assert(std::is_trivially_copyable_v<T>);
  int rank = 0, ranks = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &ranks);
  if (mine.size() * sizeof(T) > static_cast<std::size_t>(std::numeric_limits<int>::max() / 2))
    throw std::length_error("gather_to: a message of more than 1 GiB");
  const int bytes = static_cast<int>(mine.size() * sizeof(T));
  const auto n = static_cast<std::size_t>(ranks);
  std::vector<int> count(rank == root ? n : 0), at(rank == root ? n + 1 : 0, 0);
  MPI_Gather(&bytes, 1, MPI_INT, count.data(), 1, MPI_INT, root, comm);
  std::vector<T> flat;
  if (rank == root) {
    for (std::size_t q = 0; q < n; ++q) at[q + 1] = at[q] + count[q];
    flat.resize(static_cast<std::size_t>(at[n]) / sizeof(T));
  }
  MPI_Gatherv(mine.data(), bytes, MPI_BYTE, flat.data(), count.data(), at.data(), MPI_BYTE, root, comm);
  std::vector<std::vector<T>> in(rank == root ? n : 0);
  for (std::size_t q = 0; q < in.size(); ++q)
    in[q].assign(flat.begin() + at[q] / static_cast<int>(sizeof(T)),
                 flat.begin() + at[q + 1] / static_cast<int>(sizeof(T)));
  return in;
}

}  // namespace polyfloe::domain
