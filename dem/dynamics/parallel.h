// OpenMP for the step's loops, when the build has it (POLYFLOE_OMP_FOR expands to nothing otherwise, so the loops
// stay plain serial loops and no unknown-pragma warning appears).
#pragma once

#ifdef _OPENMP
#include <omp.h>
#define POLYFLOE_PRAGMA(x) _Pragma(#x)
// A parallel loop over independent iterations with `threads` threads, static chunks of 256 (iterations are cheap;
// the partition does not change any result).
#define POLYFLOE_OMP_FOR(threads) POLYFLOE_PRAGMA(omp parallel for schedule(static, 256) num_threads(threads) if (threads > 1))
// The same over a few uneven iterations (chunks of work), handed out one at a time.
#define POLYFLOE_OMP_FOR_DYNAMIC(threads) POLYFLOE_PRAGMA(omp parallel for schedule(dynamic, 1) num_threads(threads) if (threads > 1))
inline int polyfloe_thread_index() { return omp_get_thread_num(); }
// Threads a run uses unless told: what OpenMP would use (the cores, or OMP_NUM_THREADS).
inline int polyfloe_default_threads() { return omp_get_max_threads(); }
#else
#define POLYFLOE_OMP_FOR(threads)
#define POLYFLOE_OMP_FOR_DYNAMIC(threads)
inline int polyfloe_thread_index() { return 0; }
inline int polyfloe_default_threads() { return 1; }
#endif
