#include "linear_algebra/fill_reducing_order.h"

#include "linear_algebra/sparse_cholesky.h"

namespace polycube {

const std::vector<int>& FillReducingOrder::rank(const Eigen::SparseMatrix<double>& pattern) {
  if (made_) return rank_;
  made_ = true;
  SparseCholesky analysis;
  analysis.analyze(pattern, true);  // reused: the better of AMD and METIS (sparse_cholesky.h)
  const Eigen::VectorXi& eliminated = analysis.ordering().indices();
  rank_.resize(eliminated.size());
  for (Eigen::Index place = 0; place < eliminated.size(); ++place) rank_[eliminated[place]] = static_cast<int>(place);
  return rank_;
}

}  // namespace polycube
