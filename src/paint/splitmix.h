#pragma once
/// \file splitmix.h
/// Internal: the stroke generators' random numbers (generate.cpp, material_generate.cpp).
#include <cstdint>

namespace adaptex::detail {

/// splitmix64: fully specified, so files are identical on every platform and library.
struct Rng {
  std::uint64_t s;
  std::uint64_t next() {
    std::uint64_t z = (s += 0x9E3779B97F4A7C15ULL);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
    return z ^ (z >> 31);
  }
  double uniform() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }
  double uniform(double a, double b) { return a + (b - a) * uniform(); }
};

}  // namespace adaptex::detail
