#include "linear_algebra/sparse_cholesky.h"

#include <Eigen/SparseCholesky>

#include "mesh/mesh.h"

#ifdef POLYCUBE_WITH_CHOLMOD
#include <Eigen/CholmodSupport>
#endif

namespace polycube {

struct SparseCholesky::Backends {
  using Simplicial = Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>, Eigen::Lower, Eigen::AMDOrdering<int>>;
  std::unique_ptr<Simplicial> simplicial;
#ifdef POLYCUBE_WITH_CHOLMOD
  std::unique_ptr<Eigen::CholmodSupernodalLLT<Eigen::SparseMatrix<double>>> supernodal;
#endif
};

SparseCholesky::SparseCholesky() : backends_(std::make_unique<Backends>()) {}
SparseCholesky::~SparseCholesky() = default;

void SparseCholesky::analyze(const Eigen::SparseMatrix<double>& matrix, bool reused) {
  rows_ = matrix.rows();
  released_backend_ = nullptr;
  backends_ = std::make_unique<Backends>();
#ifdef POLYCUBE_WITH_CHOLMOD
  if (matrix.rows() >= kSupernodalThreshold) {
    backends_->supernodal = std::make_unique<Eigen::CholmodSupernodalLLT<Eigen::SparseMatrix<double>>>();
    // CHOLMOD prints its warnings ("not positive definite") on stdout, where
    // the program writes its JSON report; a failure is handled below.
    backends_->supernodal->cholmod().print = 0;
    if (!reused) {
      backends_->supernodal->cholmod().nmethods = 1;
      backends_->supernodal->cholmod().method[0].ordering = CHOLMOD_AMD;
    }
    backends_->supernodal->analyzePattern(matrix);
    if (backends_->supernodal->info() == Eigen::Success) return;
    backends_->supernodal.reset();
  }
#endif
  backends_->simplicial = std::make_unique<Backends::Simplicial>();
  backends_->simplicial->analyzePattern(matrix);
}

void SparseCholesky::factorize(const Eigen::SparseMatrix<double>& matrix) {
  ++factorizations_;
#ifdef POLYCUBE_WITH_CHOLMOD
  if (backends_->supernodal) {
    backends_->supernodal->factorize(matrix);
    if (backends_->supernodal->info() == Eigen::Success) return;
    backends_->supernodal.reset();  // not positive definite: LDLT from now on
    backends_->simplicial = std::make_unique<Backends::Simplicial>();
    backends_->simplicial->analyzePattern(matrix);
  }
#endif
  backends_->simplicial->factorize(matrix);
  if (backends_->simplicial->info() != Eigen::Success)
    throw Error("the sparse factorisation of the Laplacian failed (the mesh may be badly degenerate)");
}

Eigen::MatrixX3d SparseCholesky::solve(const Eigen::MatrixX3d& rhs) const {
#ifdef POLYCUBE_WITH_CHOLMOD
  if (backends_->supernodal) return backends_->supernodal->solve(rhs);
#endif
  return backends_->simplicial->solve(rhs);
}

Eigen::VectorXd SparseCholesky::solve(const Eigen::VectorXd& rhs) const {
#ifdef POLYCUBE_WITH_CHOLMOD
  if (backends_->supernodal) return backends_->supernodal->solve(rhs);
#endif
  return backends_->simplicial->solve(rhs);
}

void SparseCholesky::release() {
  released_backend_ = backend();
  backends_ = std::make_unique<Backends>();
}

const char* SparseCholesky::backend() const {
  if (released_backend_) return released_backend_;
#ifdef POLYCUBE_WITH_CHOLMOD
  if (backends_->supernodal) return "cholmod-supernodal";
#endif
  return "eigen-simplicial";
}

}  // namespace polycube
