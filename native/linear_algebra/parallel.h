// How many threads a loop over `work` items gets: one below a size where
// starting threads costs more than it saves, else OpenMP's count (the
// machine's cores, or OMP_NUM_THREADS). Without OpenMP, always one.
// The size is where a loop of the measurements takes about a millisecond:
// below it, a worker thread that a busy machine has descheduled holds up
// the join for longer than the loop takes (B0's 30,000 edges, measured 10
// times a run under a load of 5 on 2 cores: 1.02 s with two threads, 0.87
// s with one).
#pragma once

#include <algorithm>

#ifdef _OPENMP
#include <omp.h>
#endif

namespace polycube {

constexpr long kParallelThreshold = 50'000;

inline int parallel_threads(long work) {
#ifdef _OPENMP
  return work < kParallelThreshold ? 1 : omp_get_max_threads();
#else
  (void)work;
  return 1;
#endif
}

// How many parts a loop over `work` items is split into for run_in_parts()
// (run_tasks.h), whose threads sleep between tasks instead of spinning like
// OpenMP's: a part for each tenth of the threshold above (a loop of about
// a tenth of a millisecond, a few times what a sleeping thread takes to
// wake), at most a thread each, so that many cores do not split a small
// loop into parts of nothing.
constexpr long kTaskLoopThreshold = kParallelThreshold / 10;

inline int loop_parts(long work) {
#ifdef _OPENMP
  return static_cast<int>(std::clamp(work / kTaskLoopThreshold, 1L, static_cast<long>(omp_get_max_threads())));
#else
  (void)work;
  return 1;
#endif
}

// How many threads share `tasks` independent tasks of milliseconds each (a
// factorisation each): at that grain a descheduled worker costs less than
// the tasks, so no threshold; at most one thread a task.
inline int task_threads(int tasks) {
#ifdef _OPENMP
  return tasks < 1 ? 1 : std::min(tasks, omp_get_max_threads());
#else
  (void)tasks;
  return 1;
#endif
}

}  // namespace polycube
