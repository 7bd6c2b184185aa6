// The plugin behind supernodal_factor.h: Eigen's CHOLMOD wrapper. Built as its
// own shared library so that only a process that factorises a large system
// loads CHOLMOD and the BLAS it needs.
#include <Eigen/CholmodSupport>

#include "linear_algebra/supernodal_factor.h"

namespace polycube {
namespace {

class SupernodalCholmod final : public SupernodalFactor {
 public:
  SupernodalCholmod() { llt_.cholmod().print = 0; }

  bool analyze(const Eigen::SparseMatrix<double>& matrix, bool reused) override {
    if (!reused) {
      llt_.cholmod().nmethods = 1;
      llt_.cholmod().method[0].ordering = CHOLMOD_AMD;
    }
    llt_.analyzePattern(matrix);
    return llt_.info() == Eigen::Success;
  }

  bool factorize(const Eigen::SparseMatrix<double>& matrix) override {
    llt_.factorize(matrix);
    return llt_.info() == Eigen::Success;
  }

  Eigen::MatrixX3d solve(const Eigen::MatrixX3d& rhs) const override { return llt_.solve(rhs); }
  Eigen::VectorXd solve(const Eigen::VectorXd& rhs) const override { return llt_.solve(rhs); }

 private:
  Eigen::CholmodSupernodalLLT<Eigen::SparseMatrix<double>> llt_;
};

}  // namespace
}  // namespace polycube

// The one symbol the plugin exports (supernodal_factor.cpp looks it up).
extern "C" __attribute__((visibility("default"))) polycube::SupernodalFactor* polycube_new_supernodal_factor() {
  return new polycube::SupernodalCholmod();
}
