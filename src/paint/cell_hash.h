#pragma once
/// \file cell_hash.h
/// Internal: a read-only open-addressing hash from 64-bit grid-cell keys to ranges of a key-sorted
/// array, and 3-D Morton codes. Shared by the texel grid (painter) and the dab index (signal).
#include <cstdint>
#include <vector>

namespace adaptex::detail {

/// Spreads the low 21 bits of x so that there are two zero bits between consecutive bits.
inline std::uint64_t spread_bits_21(std::uint64_t x) {
  x &= 0x1fffff;
  x = (x | x << 32) & 0x1f00000000ffffULL;
  x = (x | x << 16) & 0x1f0000ff0000ffULL;
  x = (x | x << 8) & 0x100f00f00f00f00fULL;
  x = (x | x << 4) & 0x10c30c30c30c30c3ULL;
  x = (x | x << 2) & 0x1249249249249249ULL;
  return x;
}

/// Morton code of cell (x, y, z), each in [0, 2^21). The code of a coarse cell (coordinates >> L)
/// is the fine code >> 3L, so coarse cells are contiguous ranges of fine-code order.
inline std::uint64_t morton3(std::uint32_t x, std::uint32_t y, std::uint32_t z) {
  return spread_bits_21(x) | spread_bits_21(y) << 1 | spread_bits_21(z) << 2;
}

/// Key -> [begin, end) of the runs of equal keys in a sorted key array.
class CellHash {
 public:
  CellHash() = default;
  /// \p sorted_keys ascending; \p shift: the key of element k is sorted_keys[k] >> shift.
  explicit CellHash(const std::vector<std::uint64_t>& sorted_keys, int shift = 0) {
    size_t runs = 0;
    for (size_t k = 0; k < sorted_keys.size(); ++k)
      if (k == 0 || (sorted_keys[k] >> shift) != (sorted_keys[k - 1] >> shift)) ++runs;
    size_t cap = 16;
    while (cap < 2 * runs) cap *= 2;
    mask_ = cap - 1;
    slots_.assign(cap, Slot{kEmpty, 0, 0});
    size_t k = 0;
    while (k < sorted_keys.size()) {
      const std::uint64_t key = sorted_keys[k] >> shift;
      size_t e = k + 1;
      while (e < sorted_keys.size() && (sorted_keys[e] >> shift) == key) ++e;
      size_t h = hash(key) & mask_;
      while (slots_[h].key != kEmpty) h = (h + 1) & mask_;
      slots_[h] = Slot{key, static_cast<std::uint32_t>(k), static_cast<std::uint32_t>(e)};
      k = e;
    }
  }
  /// Range of \p key; begin == end when absent.
  inline void find(std::uint64_t key, std::uint32_t& begin, std::uint32_t& end) const {
    if (slots_.empty()) {
      begin = end = 0;
      return;
    }
    size_t h = hash(key) & mask_;
    while (true) {
      const Slot& s = slots_[h];
      if (s.key == key) {
        begin = s.begin;
        end = s.end;
        return;
      }
      if (s.key == kEmpty) {
        begin = end = 0;
        return;
      }
      h = (h + 1) & mask_;
    }
  }
  bool empty() const { return slots_.empty(); }

  /// A run of equal keys: [begin, end) in the sorted array.
  struct Run {
    std::uint64_t key;
    std::uint32_t begin, end;
  };
  /// Builds the table from runs (distinct keys).
  explicit CellHash(const std::vector<Run>& runs) {
    size_t cap = 16;
    while (cap < 2 * runs.size()) cap *= 2;
    mask_ = cap - 1;
    slots_.assign(cap, Slot{kEmpty, 0, 0});
    for (const Run& r : runs) {
      size_t h = hash(r.key) & mask_;
      while (slots_[h].key != kEmpty) h = (h + 1) & mask_;
      slots_[h] = Slot{r.key, r.begin, r.end};
    }
  }

 private:
  static constexpr std::uint64_t kEmpty = ~0ULL;
  static inline size_t hash(std::uint64_t k) {
    k ^= k >> 33;
    k *= 0xff51afd7ed558ccdULL;
    k ^= k >> 33;
    return static_cast<size_t>(k);
  }
  struct Slot {
    std::uint64_t key;
    std::uint32_t begin, end;
  };
  std::vector<Slot> slots_;
  size_t mask_ = 0;
};

}  // namespace adaptex::detail
