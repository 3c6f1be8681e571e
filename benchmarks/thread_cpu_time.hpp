// CPU time of the calling thread (s): what the benchmark programs time, so
// that a loaded machine's other processes are not counted.
#pragma once

#include <ctime>

inline double thread_cpu_seconds() {
  timespec now{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &now);
  return static_cast<double>(now.tv_sec) + 1e-9 * static_cast<double>(now.tv_nsec);
}
