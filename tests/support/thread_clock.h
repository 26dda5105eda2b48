// CPU time of the calling thread [s], for benchmark counters that must not count time the thread was descheduled.
#pragma once

#include <time.h>

namespace polyfloe::tsupport {

inline double thread_cpu_seconds() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

}  // namespace polyfloe::tsupport
