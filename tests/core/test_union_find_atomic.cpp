// core/union_find.h (the one union-find of adaptex) against a naive reference, and AtomicOutput's
// all-or-nothing contract (core/atomic_output.h): nothing is left behind on failure, and a commit
// onto a directory is refused before any file is renamed into place.
#include <gtest/gtest.h>

#include <fstream>
#include <random>

#include "adaptex/core/atomic_output.h"
#include "adaptex/core/errors.h"
#include "adaptex/core/union_find.h"
#include "test_support.h"

namespace adaptex {
namespace {

TEST(UnionFind, MatchesANaiveLabellingAndRootsAreTheSmallestElements) {
  const int n = 2000;
  UnionFind uf(n);
  std::vector<int> label(n);  // naive: relabel a whole set on every union
  for (int i = 0; i < n; ++i) label[i] = i;
  std::mt19937 rng(11);
  for (int u = 0; u < 1500; ++u) {
    const int a = static_cast<int>(rng() % n), b = static_cast<int>(rng() % n);
    uf.unite(a, b);
    const int from = label[b], to = label[a];
    for (int& l : label)
      if (l == from) l = to;
  }
  EXPECT_EQ(uf.size(), n);
  std::vector<int> smallest(n, n);
  for (int i = 0; i < n; ++i) smallest[label[i]] = std::min(smallest[label[i]], i);
  for (int i = 0; i < n; ++i) ASSERT_EQ(uf.find(i), smallest[label[i]]) << i;
}

std::string slurp(const std::filesystem::path& p) {
  std::ifstream in(p);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

TEST(AtomicOutput, CommitRefusesADirectoryBeforeRenamingAnything) {
  test::TempDir dir;
  std::filesystem::create_directory(dir.path / "taken");
  {
    AtomicOutput out;
    std::ofstream(out.add(dir.path / "a.txt")) << "a";
    std::ofstream(out.add(dir.path / "taken")) << "b";
    EXPECT_THROW(out.commit(), OutputError);
  }
  EXPECT_FALSE(std::filesystem::exists(dir.path / "a.txt"));  // not renamed into place
  EXPECT_TRUE(std::filesystem::is_directory(dir.path / "taken"));
  // Only the directory is left: every temporary was removed.
  int entries = 0;
  for ([[maybe_unused]] const auto& e : std::filesystem::directory_iterator(dir.path)) ++entries;
  EXPECT_EQ(entries, 1);
}

TEST(AtomicOutput, UncommittedOutputsAndCreatedDirectoriesAreRemoved) {
  test::TempDir dir;
  {
    AtomicOutput out;
    std::ofstream(out.add(dir.path / "new" / "deeper" / "x.txt")) << "x";
  }
  EXPECT_FALSE(std::filesystem::exists(dir.path / "new"));
  AtomicOutput out;
  std::ofstream(out.add(dir.path / "new" / "y.txt")) << "y";
  out.commit();
  EXPECT_EQ(slurp(dir.path / "new" / "y.txt"), "y");
}

TEST(AtomicOutput, ADirectoryThatCannotBeCreatedIsAnOutputError) {
  AtomicOutput out;
  EXPECT_THROW(out.add("/proc/adaptex-no-such-dir/x.txt"), OutputError);
}

}  // namespace
}  // namespace adaptex
