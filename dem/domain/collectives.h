// The collectives the domain's layers share: every rank's lists to every rank, or to one (counts, then the items).
#pragma once

#include <mpi.h>

#include <algorithm>
#include <cstddef>
#include <limits>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

namespace polyfloe::domain {

namespace detail {

// The bytes of `n` items of T as an MPI count; a message of more than 1 GiB is refused.
template <class T>
int byte_count(std::size_t n, const char* who) {
  static_assert(std::is_trivially_copyable_v<T>);
  if (n * sizeof(T) > static_cast<std::size_t>(std::numeric_limits<int>::max() / 2))
    throw std::length_error(std::string(who) + ": a message of more than 1 GiB");
  return static_cast<int>(n * sizeof(T));
}

// Offsets [bytes] of messages of `count` bytes laid end to end (one more than counts: the total last).
inline std::vector<int> offsets(const std::vector<int>& count) {
  std::vector<int> at(count.size() + 1, 0);
  for (std::size_t q = 0; q < count.size(); ++q) at[q + 1] = at[q] + count[q];
  return at;
}

// `flat`, messages laid end to end at byte offsets `at`, cut into one list per message.
template <class T>
std::vector<std::vector<T>> split(const std::vector<T>& flat, const std::vector<int>& at) {
  std::vector<std::vector<T>> out(at.empty() ? 0 : at.size() - 1);
  for (std::size_t q = 0; q < out.size(); ++q)
    out[q].assign(flat.begin() + at[q] / static_cast<int>(sizeof(T)),
                  flat.begin() + at[q + 1] / static_cast<int>(sizeof(T)));
  return out;
}

}  // namespace detail

// Collective over `comm`: out[q] (any length, possibly empty) to rank q; returns in[q], what rank q sent this one.
// T is copied as bytes (trivially copyable, no padding that matters to the receiver).
template <class T>
std::vector<std::vector<T>> all_to_all(MPI_Comm comm, const std::vector<std::vector<T>>& out) {
  int ranks = 1;
  MPI_Comm_size(comm, &ranks);
  if (out.size() != static_cast<std::size_t>(ranks))
    throw std::invalid_argument("all_to_all: one list per rank of the communicator is needed");
  std::vector<int> send_count(out.size()), recv_count(out.size());
  for (std::size_t q = 0; q < out.size(); ++q) send_count[q] = detail::byte_count<T>(out[q].size(), "all_to_all");
  MPI_Alltoall(send_count.data(), 1, MPI_INT, recv_count.data(), 1, MPI_INT, comm);
  const std::vector<int> send_at = detail::offsets(send_count), recv_at = detail::offsets(recv_count);
  std::vector<T> flat_out(static_cast<std::size_t>(send_at.back()) / sizeof(T));
  std::vector<T> flat_in(static_cast<std::size_t>(recv_at.back()) / sizeof(T));
  for (std::size_t q = 0; q < out.size(); ++q)
    std::copy(out[q].begin(), out[q].end(), flat_out.begin() + send_at[q] / static_cast<int>(sizeof(T)));
  MPI_Alltoallv(flat_out.data(), send_count.data(), send_at.data(), MPI_BYTE, flat_in.data(), recv_count.data(),
                recv_at.data(), MPI_BYTE, comm);
  return detail::split(flat_in, recv_at);
}

// Collective over `comm`: every rank's `mine` to every rank, by rank.
template <class T>
std::vector<std::vector<T>> all_gather(MPI_Comm comm, const std::vector<T>& mine) {
  int ranks = 1;
  MPI_Comm_size(comm, &ranks);
  const int bytes = detail::byte_count<T>(mine.size(), "all_gather");
  std::vector<int> count(static_cast<std::size_t>(ranks));
  MPI_Allgather(&bytes, 1, MPI_INT, count.data(), 1, MPI_INT, comm);
  const std::vector<int> at = detail::offsets(count);
  std::vector<T> flat(static_cast<std::size_t>(at.back()) / sizeof(T));
  MPI_Allgatherv(mine.data(), bytes, MPI_BYTE, flat.data(), count.data(), at.data(), MPI_BYTE, comm);
  return detail::split(flat, at);
}

// Collective over `comm`: every rank's `mine` to `root`, which gets them by rank (the others an empty list).
template <class T>
std::vector<std::vector<T>> gather_to(MPI_Comm comm, int root, const std::vector<T>& mine) {
  int rank = 0, ranks = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &ranks);
  const int bytes = detail::byte_count<T>(mine.size(), "gather_to");
  std::vector<int> count(rank == root ? static_cast<std::size_t>(ranks) : 0);
  MPI_Gather(&bytes, 1, MPI_INT, count.data(), 1, MPI_INT, root, comm);
  const std::vector<int> at = rank == root ? detail::offsets(count) : std::vector<int>{};
  std::vector<T> flat(rank == root ? static_cast<std::size_t>(at.back()) / sizeof(T) : 0);
  MPI_Gatherv(mine.data(), bytes, MPI_BYTE, flat.data(), count.data(), at.data(), MPI_BYTE, root, comm);
  return detail::split(flat, at);
}

}  // namespace polyfloe::domain
