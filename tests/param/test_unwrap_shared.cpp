// unwrap() on every shared mesh (../shared/meshes; skipped with a message when absent): UVs in
// [0,1]^2, every chart a disk, zero flipped / degenerate / overlapping triangles, Yoshizawa lowers
// the L2 stretch of the Floater embedding.
#include <gtest/gtest.h>

#include <iostream>

#include "adaptex/io/mesh_io.h"
#include "test_support.h"
#include "unwrap_checks.h"

#if defined(__SANITIZE_ADDRESS__)
#define ADAPTEX_UNDER_SANITIZER 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define ADAPTEX_UNDER_SANITIZER 1
#endif
#endif

namespace adaptex {
namespace {

TEST(UnwrapShared, MeshesArePresent) {
  ADAPTEX_REQUIRE_SHARED();
  EXPECT_FALSE(test::shared_meshes().empty());
}

class UnwrapSharedMesh : public ::testing::TestWithParam<std::string> {};

TEST_P(UnwrapSharedMesh, UnwrapsIntoNonOverlappingDisks) {
  ADAPTEX_REQUIRE_SHARED();
  const std::filesystem::path path = *test::shared_meshes_dir() / GetParam();
#ifdef ADAPTEX_UNDER_SANITIZER
  if (GetParam() == "igea.ply" || GetParam() == "horse.ply")
    GTEST_SKIP() << GetParam() << " is too large to unwrap under the sanitizers; skipped";
#endif
  const TriMesh mesh = read_mesh(path);
  UnwrapResult r;
  test::check_unwrap(GetParam(), mesh, {}, &r);
  // Yoshizawa (with the augmented cut) strictly lowers the L2 stretch of the Floater embedding.
  EXPECT_LT(r.report.final_l2, r.report.floater_l2) << GetParam();
  std::cout << GetParam() << ": " << mesh.num_faces() << " faces, genus " << r.report.genus
            << ", loops " << r.report.boundary_loops << ", cut " << r.report.cut_length
            << ", L2 " << r.report.floater_l2 << " -> " << r.report.final_l2 << ", "
            << r.report.augmentations << " augmentation(s), " << r.report.time_total << " s\n";
}

std::vector<std::string> shared_names() {
  std::vector<std::string> names;
  for (const auto& p : test::shared_meshes()) names.push_back(p.filename().string());
  return names;
}

std::string test_name(const ::testing::TestParamInfo<std::string>& info) {
  std::string s = info.param;
  for (char& c : s)
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  return s;
}

INSTANTIATE_TEST_SUITE_P(Shared, UnwrapSharedMesh, ::testing::ValuesIn(shared_names()), test_name);
GTEST_ALLOW_UNINSTANTIATED_PARAMETERIZED_TEST(UnwrapSharedMesh);

}  // namespace
}  // namespace adaptex

namespace adaptex {
namespace {

TEST(UnwrapShared, SqueezedExtremitiesAreAugmentedBeyondTheBudgets) {
  // dino.off: the Floater embedding of its initial (diameter) cut squeezes the legs into degenerate
  // UV triangles; with both augmentation budgets at zero the rescue still augments the cut.
  ADAPTEX_REQUIRE_SHARED();
  const TriMesh mesh = read_mesh(*test::shared_meshes_dir() / "dino.off");
  UnwrapOptions opt;
  opt.charts = ChartMode::Single;  // the rescue of one chart per component
  opt.augment_face_budget = 0;
  opt.augment_time_budget = 0;
  UnwrapResult r;
  test::check_unwrap("dino.off without budget", mesh, opt, &r);
  EXPECT_GT(r.report.augmentations, 0);
  // Without augmentation at all the validity fallback (another layout or split charts) makes it
  // valid instead: never a degenerate UV triangle.
  opt.max_augmentations = 0;
  const UnwrapResult plain = unwrap(mesh, opt);
  EXPECT_TRUE(invalid_uv_faces(plain.param).empty());
}

}  // namespace
}  // namespace adaptex
