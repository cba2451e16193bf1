#pragma once
/// \file union_find.h
/// Disjoint sets over the integers [0, n) (Tarjan 1975) with path halving. The one union-find of
/// adaptex: vertex fans and face components (core/topology.cpp), corner groups of the repair
/// (io/mesh_validate.cpp), OBJ charts (io/obj_io.cpp), the cut graph and wedges of param/cut.cpp.
#include <algorithm>
#include <numeric>
#include <vector>

namespace adaptex {

/// Disjoint sets of [0, n). The root of a set is its smallest element (deterministic, whatever the
/// order of the unions).
class UnionFind {
 public:
  /// \p n singletons {0}, ..., {n-1}. \pre n >= 0
  explicit UnionFind(int n) : parent_(static_cast<size_t>(n)) { std::iota(parent_.begin(), parent_.end(), 0); }
  /// The root (smallest element) of the set of \p x. \pre 0 <= x < n
  int find(int x) {
    while (parent_[x] != x) x = parent_[x] = parent_[parent_[x]];
    return x;
  }
  /// Merges the sets of \p a and \p b. \return false if they were one set already.
  /// \pre 0 <= a, b < n
  bool unite(int a, int b) {
    a = find(a);
    b = find(b);
    if (a == b) return false;
    parent_[std::max(a, b)] = std::min(a, b);
    return true;
  }
  /// Number of elements n.
  int size() const { return static_cast<int>(parent_.size()); }

 private:
  std::vector<int> parent_;  ///< n: parent of every element (a root is its own parent).
};

}  // namespace adaptex
