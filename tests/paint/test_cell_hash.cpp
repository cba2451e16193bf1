// Direct tests of CellHash and the 3-D Morton code (src/paint/cell_hash.h), the index under the
// painter's texel grid and the signal's dab index: every present key finds exactly its run, absent
// keys find nothing, coarse keys (shifted) find the union of their fine runs.
#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <random>

#include "cell_hash.h"

namespace adaptex::detail {
namespace {

/// Sorted keys with runs of 1-5 equal keys, drawn from a range where hash collisions are frequent.
std::vector<std::uint64_t> sorted_keys(int n, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::vector<std::uint64_t> keys;
  while (static_cast<int>(keys.size()) < n) {
    const std::uint64_t k = rng() % 100000;
    const int run = 1 + static_cast<int>(rng() % 5);
    for (int r = 0; r < run; ++r) keys.push_back(k);
  }
  std::sort(keys.begin(), keys.end());
  return keys;
}

/// The reference: key (after the shift) -> [first, last + 1) by a linear scan.
std::map<std::uint64_t, std::pair<std::uint32_t, std::uint32_t>> runs_of(const std::vector<std::uint64_t>& keys,
                                                                         int shift) {
  std::map<std::uint64_t, std::pair<std::uint32_t, std::uint32_t>> out;
  for (std::uint32_t k = 0; k < keys.size(); ++k) {
    auto [it, fresh] = out.try_emplace(keys[k] >> shift, k, k + 1);
    if (!fresh) it->second.second = k + 1;
  }
  return out;
}

void expect_matches(const CellHash& h, const std::vector<std::uint64_t>& keys, int shift) {
  const auto ref = runs_of(keys, shift);
  for (const auto& [key, range] : ref) {
    std::uint32_t b = 7, e = 3;
    h.find(key, b, e);
    ASSERT_EQ(b, range.first) << key;
    ASSERT_EQ(e, range.second) << key;
  }
  // Keys that are not there (including ones that hash like present ones) find an empty range.
  std::mt19937_64 rng(99);
  int absent = 0;
  for (int t = 0; t < 20000; ++t) {
    const std::uint64_t key = rng() % (200000 >> shift);
    if (ref.count(key)) continue;
    ++absent;
    std::uint32_t b = 7, e = 3;
    h.find(key, b, e);
    ASSERT_EQ(b, e) << key;
  }
  EXPECT_GT(absent, 5000);
}

TEST(CellHash, EveryKeyFindsExactlyItsRun) {
  const auto keys = sorted_keys(30000, 1);
  expect_matches(CellHash(keys), keys, 0);
}

TEST(CellHash, ShiftedKeysFindTheUnionOfTheirFineRuns) {
  const auto keys = sorted_keys(30000, 2);
  for (int shift : {3, 6, 9}) {
    SCOPED_TRACE(shift);
    expect_matches(CellHash(keys, shift), keys, shift);
  }
}

TEST(CellHash, BuiltFromRunsEqualsBuiltFromKeys) {
  const auto keys = sorted_keys(5000, 3);
  std::vector<CellHash::Run> runs;
  for (const auto& [key, range] : runs_of(keys, 0)) runs.push_back({key, range.first, range.second});
  expect_matches(CellHash(runs), keys, 0);
}

TEST(CellHash, EmptyTableFindsNothing) {
  std::uint32_t b = 1, e = 2;
  CellHash().find(42, b, e);
  EXPECT_EQ(b, e);
  EXPECT_TRUE(CellHash().empty());
  CellHash(std::vector<std::uint64_t>{}).find(0, b, e);
  EXPECT_EQ(b, e);
}

TEST(MortonCode, InterleavesTheBitsAndCoarseCellsArePrefixes) {
  std::mt19937 rng(5);
  for (int t = 0; t < 2000; ++t) {
    const std::uint32_t x = rng() & 0x1fffff, y = rng() & 0x1fffff, z = rng() & 0x1fffff;
    const std::uint64_t m = morton3(x, y, z);
    for (int bit = 0; bit < 21; ++bit) {
      ASSERT_EQ((m >> (3 * bit)) & 1, (x >> bit) & 1);
      ASSERT_EQ((m >> (3 * bit + 1)) & 1, (y >> bit) & 1);
      ASSERT_EQ((m >> (3 * bit + 2)) & 1, (z >> bit) & 1);
    }
    EXPECT_EQ(m >> 63, 0u);
    for (int level : {1, 4, 20}) ASSERT_EQ(m >> (3 * level), morton3(x >> level, y >> level, z >> level));
  }
  EXPECT_EQ(spread_bits_21(0xffffffff), spread_bits_21(0x1fffff));  // only the low 21 bits count
}

}  // namespace
}  // namespace adaptex::detail
