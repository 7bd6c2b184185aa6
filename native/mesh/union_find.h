// Disjoint sets over 0..n-1 (charts, components, merged unknowns). The root
// of a set is always its lowest member, so numbering roots in index order
// numbers the sets by their lowest member, deterministically. Paths are
// halved on lookup.
#pragma once

#include <algorithm>
#include <numeric>
#include <vector>

namespace polycube {

class UnionFind {
 public:
  explicit UnionFind(int count = 0) : parent_(count) { std::iota(parent_.begin(), parent_.end(), 0); }

  // Back to `count` single sets, keeping the storage.
  void reset(int count) {
    parent_.resize(count);
    std::iota(parent_.begin(), parent_.end(), 0);
  }

  int size() const { return static_cast<int>(parent_.size()); }

  int root(int v) {
    while (parent_[v] != v) {
      parent_[v] = parent_[parent_[v]];
      v = parent_[v];
    }
    return v;
  }

  // Returns false when a and b were in one set already.
  bool join(int a, int b) {
    a = root(a);
    b = root(b);
    if (a == b) return false;
    parent_[std::max(a, b)] = std::min(a, b);
    return true;
  }

 private:
  std::vector<int> parent_;
};

}  // namespace polycube
