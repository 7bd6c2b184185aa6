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

// Eigen's wrapper, whose analysis can also start from a known ordering
// (CHOLMOD_GIVEN), or take the matrix in its elimination order already
// (CHOLMOD_NATURAL), and tell the ordering it used.
class Llt : public Eigen::CholmodSupernodalLLT<Eigen::SparseMatrix<double>> {
 public:
  void analyze_given(const Eigen::SparseMatrix<double>& matrix, const Eigen::VectorXi& ordering) {
    analyze_with(matrix, CHOLMOD_GIVEN, const_cast<int*>(ordering.data()));
  }
  void analyze_in_order(const Eigen::SparseMatrix<double>& matrix) {
    // A postorder would leave the factor's ordering no longer natural
    // (cholmod_analyze_p2), and factorisations permuting again.
    const int postorder = cholmod().postorder;
    cholmod().postorder = 0;
    analyze_with(matrix, CHOLMOD_NATURAL, nullptr);
    cholmod().postorder = postorder;
  }
  // Takes a copy of `other`'s symbolic analysis (CHOLMOD's pattern-only
  // factor); false when it has none or has been factorised since.
  bool copy_analysis_from(const Llt& other) {
    cholmod_factor* const symbolic = other.m_cholmodFactor;  // cholmod_copy_factor only reads it
    if (!symbolic || symbolic->xtype != CHOLMOD_PATTERN) return false;
    m_cholmodFactor = cholmod_copy_factor(symbolic, &cholmod());
    m_isInitialized = true;
    m_analysisIsOk = m_cholmodFactor != nullptr;
    m_factorizationIsOk = false;
    m_info = m_analysisIsOk ? Eigen::Success : Eigen::NumericalIssue;
    return m_analysisIsOk;
  }
  Eigen::VectorXi ordering() const {
    if (!m_cholmodFactor || !m_cholmodFactor->Perm) return {};
    return Eigen::Map<const Eigen::VectorXi>(static_cast<const int*>(m_cholmodFactor->Perm),
                                             static_cast<Eigen::Index>(m_cholmodFactor->n));
  }

 private:
  // The analysis by the one `method`, with `ordering` when it is given.
  void analyze_with(const Eigen::SparseMatrix<double>& matrix, int method, int* ordering) {
    if (m_cholmodFactor) {
      cholmod_free_factor(&m_cholmodFactor, &cholmod());
      m_cholmodFactor = nullptr;
    }
    cholmod_sparse a = Eigen::viewAsCholmod(matrix.selfadjointView<Eigen::Lower>());
    cholmod().nmethods = 1;
    cholmod().method[0].ordering = method;
    m_cholmodFactor = cholmod_analyze_p(&a, ordering, nullptr, 0, &cholmod());
    m_isInitialized = true;
    m_info = m_cholmodFactor ? Eigen::Success : Eigen::InvalidInput;
    m_analysisIsOk = m_cholmodFactor != nullptr;
    m_factorizationIsOk = false;
  }
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

  bool analyze(const Eigen::SparseMatrix<double>& matrix, const Eigen::VectorXi& ordering) override {
    const SerialOpenMP serial;
    llt_.analyze_given(matrix, ordering);
    return llt_.info() == Eigen::Success;
  }

  bool analyze_in_order(const Eigen::SparseMatrix<double>& matrix) override {
    const SerialOpenMP serial;
    llt_.analyze_in_order(matrix);
    return llt_.info() == Eigen::Success;
  }

  Eigen::VectorXi ordering() const override { return llt_.ordering(); }

  std::unique_ptr<SupernodalFactor> copy_analysis() const override {
    auto copy = std::make_unique<SupernodalCholmod>();
    if (!copy->llt_.copy_analysis_from(llt_)) return nullptr;
    return copy;
  }

  bool factorize(const Eigen::SparseMatrix<double>& matrix) override {
    const SerialOpenMP serial;
    llt_.factorize(matrix);
    return llt_.info() == Eigen::Success;
  }

  Eigen::MatrixXd solve(const Eigen::MatrixXd& rhs) const override {
    const SerialOpenMP serial;
    return llt_.solve(rhs);
  }

 private:
  Llt llt_;
};

}  // namespace
}  // namespace polycube

// The one symbol the plugin exports (supernodal_factor.cpp looks it up).
extern "C" __attribute__((visibility("default"))) polycube::SupernodalFactor* polycube_new_supernodal_factor() {
  return new polycube::SupernodalCholmod();
}
