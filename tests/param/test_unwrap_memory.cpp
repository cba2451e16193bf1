// The memory bound of unwrap() on scans (unwrap.h): the peak resident set grows by at most
// 1 KB per face during the unwrap of a scan-like mesh (measured: about 0.4 KB per face for the
// whole `adaptex unwrap --repair` of an 895k-face synthetic scan, docs/bench_unwrap.md, "Scans").
// Its own test binary: the process's peak (getrusage) must not include other tests.
#include <gtest/gtest.h>

#include <sys/resource.h>

#include <cstdio>

#include "adaptex/param/unwrap.h"
#include "scan_fixtures.h"

#include "../asan_detect.h"

namespace adaptex {
namespace {

long peak_rss_kb() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return u.ru_maxrss;  // KB on Linux
}

TEST(UnwrapMemory, PeakGrowsByAtMostOneKilobytePerFace) {
#if defined(ADAPTEX_TEST_ASAN)
  GTEST_SKIP() << "AddressSanitizer inflates the resident set";
#endif
  const TriMesh mesh = test::scan_like_mesh(200000);
  ASSERT_GT(mesh.num_faces(), 140000);
  const long before = peak_rss_kb();
  const UnwrapResult r = unwrap(mesh);
  const long grown = peak_rss_kb() - before;
  EXPECT_GT(r.report.num_charts, r.report.num_components);  // the scan segmentation ran
  EXPECT_LE(grown, static_cast<long>(mesh.num_faces()));   // 1 KB per face
  RecordProperty("peak_growth_kb", static_cast<int>(grown));
  std::printf("peak RSS grew by %ld KB for %d faces (%.0f bytes per face)\n", grown,
              mesh.num_faces(), 1024.0 * grown / mesh.num_faces());
}

}  // namespace
}  // namespace adaptex
