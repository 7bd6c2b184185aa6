// The plugin behind supernodal_factor.h: Eigen's CHOLMOD wrapper. Built as its
// own shared library so that only a process that factorises a large system
// loads CHOLMOD and the BLAS it needs.
#include <Eigen/CholmodSupport>

#ifdef _OPENMP
#include <omp.h>
#endif

#include "linear_algebra/supernodal_factor.h"

namespace polycube {
namespace {

// Debian's CHOLMOD (3.0) opens an OpenMP team of a fixed 4 threads for the
// scatter of every large supernode, whatever OMP_NUM_THREADS says: on two
// cores that is thousands of wake-ups per factorisation (armadillo refined
// 4 times: 9 million context switches and a quarter of the run's time in the
// kernel). Its work per team is far below a thread's wake-up, so CHOLMOD's
// regions run on the calling thread: no region opened while this lives is
// active.
class SerialOpenMP {
 public:
#ifdef _OPENMP
  SerialOpenMP() : levels_(omp_get_max_active_levels()) { omp_set_max_active_levels(0); }
  ~SerialOpenMP() { omp_set_max_active_levels(levels_); }

 private:
  int levels_;
#endif
};

class SupernodalCholmod final : public SupernodalFactor {
 public:
  SupernodalCholmod() { llt_.cholmod().print = 0; }

  bool analyze(const Eigen::SparseMatrix<double>& matrix, bool reused) override {
    if (!reused) {
      llt_.cholmod().nmethods = 1;
      llt_.cholmod().method[0].ordering = CHOLMOD_AMD;
    }
    const SerialOpenMP serial;
    llt_.analyzePattern(matrix);
    return llt_.info() == Eigen::Success;
  }

  bool factorize(const Eigen::SparseMatrix<double>& matrix) override {
    const SerialOpenMP serial;
    llt_.factorize(matrix);
    return llt_.info() == Eigen::Success;
  }

  Eigen::MatrixX3d solve(const Eigen::MatrixX3d& rhs) const override {
    const SerialOpenMP serial;
    return llt_.solve(rhs);
  }
  Eigen::VectorXd solve(const Eigen::VectorXd& rhs) const override {
    const SerialOpenMP serial;
    return llt_.solve(rhs);
  }

 private:
  Eigen::CholmodSupernodalLLT<Eigen::SparseMatrix<double>> llt_;
};

}  // namespace
}  // namespace polycube

// The one symbol the plugin exports (supernodal_factor.cpp looks it up).
extern "C" __attribute__((visibility("default"))) polycube::SupernodalFactor* polycube_new_supernodal_factor() {
  return new polycube::SupernodalCholmod();
}
