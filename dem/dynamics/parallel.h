// OpenMP for the step's loops, when the build has it (POLYFLOE_OMP_FOR expands to nothing otherwise, so the loops
// stay plain serial loops and no unknown-pragma warning appears).
#pragma once

#include <cstddef>

#ifdef _OPENMP
#include <omp.h>
#define POLYFLOE_PRAGMA(x) _Pragma(#x)
// A parallel loop over independent iterations with `threads` threads, each thread taking one contiguous stretch
// (the partition does not change any result). Every loop over the bodies, the slots or blocks of slots cuts the
// same way, so a thread mostly reads what it wrote in the loop before: at a thousand floes a loop lasts a few
// microseconds, and data fetched from the other core's cache, or chunks handed out one at a time, cost as much
// again (docs/performance.md, "Two threads at a thousand floes").
#define POLYFLOE_OMP_FOR(threads) \
  POLYFLOE_PRAGMA(omp parallel for schedule(static) num_threads(threads) if (threads > 1))
// The same, each thread or-ing into its own copies of the bools named after `threads`, or-ed together at the end.
#define POLYFLOE_OMP_FOR_ANY(threads, ...) \
  POLYFLOE_PRAGMA(omp parallel for schedule(static) num_threads(threads) if (threads > 1) reduction(|| : __VA_ARGS__))
inline int polyfloe_thread_index() { return omp_get_thread_num(); }
// Threads a run uses unless told: what OpenMP would use (the cores, or OMP_NUM_THREADS).
inline int polyfloe_default_threads() { return omp_get_max_threads(); }
#else
#define POLYFLOE_OMP_FOR(threads)
#define POLYFLOE_OMP_FOR_ANY(threads, ...)
inline int polyfloe_thread_index() { return 0; }
inline int polyfloe_default_threads() { return 1; }
#endif

// body(i) for i in [0, n): on `threads` threads (POLYFLOE_OMP_FOR), or as a plain loop on this one when threads is
// 1 (no call into the OpenMP runtime, whose start-up a loop over a few hundred bodies notices).
template <class Body>
void polyfloe_parallel_for(std::ptrdiff_t n, int threads, Body&& body) {
  if (threads <= 1) {
    for (std::ptrdiff_t i = 0; i < n; ++i) body(i);
    return;
  }
  POLYFLOE_OMP_FOR(threads)
  for (std::ptrdiff_t i = 0; i < n; ++i) body(i);
}
