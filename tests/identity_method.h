#pragma once
/// \file identity_method.h
/// A method added from outside the library (adapt/method.h): the identity warp of the square,
/// registered by a test with one line. The registry tests of the library, the CLI and Python use it.
#include <memory>
#include <utility>
#include <vector>

#include "adaptex/adapt/method.h"
#include "adaptex/adapt/uv_warp.h"

namespace adaptex::test {

/// The identity warp of the square; counts its solvers and their cycles.
class IdentityMethod final : public AdaptMethod {
 public:
  IdentityMethod() { ++made; }
  void compute(const WarpInput&, AdaptResult& result) override {
    ++computed;
    std::vector<GridWarp> lattices;
    lattices.push_back(GridWarp::uniform(8));
    result.warp = std::make_shared<const LatticeWarp>(std::move(lattices));
  }
  static inline int made = 0, computed = 0;
};

/// Registers IdentityMethod as "identity" (once per program). \return true
inline bool register_identity_method() {
  static const bool done = [] {
    register_adapt_method({"identity", "test: the identity warp", [] { return std::make_unique<IdentityMethod>(); }});
    return true;
  }();
  return done;
}

}  // namespace adaptex::test
