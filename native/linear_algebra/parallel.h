// How many threads a loop over `work` items gets: one below a size where
// starting threads costs more than it saves, else OpenMP's count (the
// machine's cores, or OMP_NUM_THREADS). Without OpenMP, always one.
#pragma once

#ifdef _OPENMP
#include <omp.h>
#endif

namespace polycube {

constexpr long kParallelThreshold = 20'000;

inline int parallel_threads(long work) {
#ifdef _OPENMP
  return work < kParallelThreshold ? 1 : omp_get_max_threads();
#else
  (void)work;
  return 1;
#endif
}

}  // namespace polycube
