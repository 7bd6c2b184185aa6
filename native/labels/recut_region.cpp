#include "labels/recut_region.h"

#include <utility>

namespace polycube {

std::vector<int> recut_region(const LabelEnergy& energy, const std::vector<int>& labels, const std::vector<int>& region,
                              int axis) {
  constexpr double kForbidden = 1e6;  // the barred axis
  std::vector<int> local(labels.size(), -1);
  for (size_t k = 0; k < region.size(); ++k) local[region[k]] = static_cast<int>(k);
  LabelEnergy sub;
  sub.data.resize(static_cast<Eigen::Index>(region.size()), 6);
  for (size_t k = 0; k < region.size(); ++k)
    for (int l = 0; l < 6; ++l) sub.data(k, l) = l / 2 == axis ? kForbidden : energy.data(region[k], l);
  sub.label_cost = energy.label_cost;
  for (size_t p = 0; p < energy.pairs.size(); ++p) {
    const int f = energy.pairs[p][0], g = energy.pairs[p][1];
    const double w = energy.weights[p];
    if (local[f] >= 0 && local[g] >= 0) {
      sub.pairs.push_back({local[f], local[g]});
      sub.weights.push_back(w);
    } else if (local[f] >= 0 || local[g] >= 0) {
      const int inside = local[f] >= 0 ? f : g, held = inside == f ? g : f;
      for (int l = 0; l < 6; ++l) sub.data(local[inside], l) += w * energy.label_cost(l, labels[held]);
    }
  }
  std::vector<int> start(region.size());
  for (size_t k = 0; k < region.size(); ++k) {
    int best = -1;
    for (int l = 0; l < 6; ++l)
      if (l / 2 != axis && (best < 0 || sub.data(k, l) < sub.data(k, best))) best = l;
    start[k] = best;
  }
  const std::vector<int> cut = alpha_expansion(sub, std::move(start));
  std::vector<int> result = labels;
  for (size_t k = 0; k < region.size(); ++k) result[region[k]] = cut[k];
  return result;
}

}  // namespace polycube
