// unwrap() (§3.2 surgery + packing) on meshes built in code: one test body, many meshes.
#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <atomic>
#include <cmath>
#include <limits>
#include <string>

#include "adaptex/core/errors.h"
#include "adaptex/core/shapes.h"
#include "adaptex/core/topology.h"
#include "adaptex/param/pack.h"
#include "adaptex/param/stretch.h"
#include "adaptex/param/unwrap.h"
#include "unwrap_checks.h"

namespace adaptex {
namespace {

using test::check_unwrap;

/// \p a and \p b are the same layout, bit for bit.
void expect_same_layout(const UnwrapResult& a, const UnwrapResult& b) {
  EXPECT_EQ(a.report.num_charts, b.report.num_charts);
  EXPECT_EQ(a.report.final_l2, b.report.final_l2);
  ASSERT_EQ(a.param.uv.size(), b.param.uv.size());
  EXPECT_TRUE(a.param.uv == b.param.uv);
  EXPECT_TRUE(a.param.uv_faces == b.param.uv_faces);
}

/// Flips the winding of every face (as the CW-wound shared meshes are).
TriMesh flipped(TriMesh m) {
  for (Face& t : m.faces) std::swap(t[1], t[2]);
  return m;
}

TEST(Unwrap, EveryShapeBecomesNonOverlappingDisks) {
  check_unwrap("sphere", shapes::sphere(32, 16));
  check_unwrap("icosphere", shapes::icosphere(3));
  check_unwrap("torus", shapes::torus(48, 16));
  check_unwrap("double_torus", shapes::double_torus(32));
  check_unwrap("open_cylinder", shapes::open_cylinder(32, 12));
  check_unwrap("disk_with_holes", shapes::disk_with_holes(3, 32));
  check_unwrap("two_components", shapes::two_components());
  check_unwrap("trefoil_knot", shapes::trefoil_knot(120, 16));
  check_unwrap("plane", shapes::plane(12));
}

TEST(Unwrap, ClockwiseWindingGivesPositiveUvAreas) {
  check_unwrap("sphere CW", flipped(shapes::sphere(24, 12)));
  check_unwrap("torus CW", flipped(shapes::torus(32, 12)));
  check_unwrap("disk_with_holes CW", flipped(shapes::disk_with_holes(2, 24)));
}

TEST(Unwrap, WithoutAugmentationOrYoshizawa) {
  UnwrapOptions opt;
  opt.max_augmentations = 0;
  check_unwrap("torus no augmentation", shapes::torus(32, 12), opt);
  opt.yoshizawa_max_iterations = 0;
  check_unwrap("torus Floater only", shapes::torus(32, 12), opt);
  opt.weights = EmbeddingWeights::MeanValue;
  check_unwrap("two components mean value", shapes::two_components(), opt);
}

/// A 17-face pleat of a depth scan (two of its faces lie folded back over their neighbours), with
/// the scan's float32 coordinates: with shape-preserving weights its disk parameterization has a
/// degenerate UV triangle (area ~1e-21) that only the cut augmentation removed.
TriMesh pleated_fragment() {
  TriMesh m;
  m.positions = {{8.41003704071045, -0.12906289100646973, 6.491103172302246},
                 {8.41003704071045, -0.13002562522888184, 6.545981407165527},
                 {8.386930465698242, -0.12593388557434082, 6.550073146820068},
                 {8.41003704071045, -0.12497115135192871, 6.62589168548584},
                 {8.41003704071045, -0.11389923095703125, 6.6080803871154785},
                 {8.41003704071045, -0.13002562522888184, 6.586899280548096},
                 {8.41003704071045, -0.11004805564880371, 6.53009557723999},
                 {8.41003704071045, -0.11991643905639648, 6.531058311462402},
                 {8.41003704071045, -0.11101078987121582, 6.5700507164001465},
                 {8.410999298095703, -0.15096592903137207, 6.513006210327148},
                 {8.41003704071045, -0.11004805564880371, 6.550073146820068},
                 {8.410999298095703, -0.16492629051208496, 6.571013450622559},
                 {8.41003704071045, -0.16805529594421387, 6.648998260498047},
                 {8.398964881896973, -0.13098835945129395, 6.643943786621094}};
  m.faces = {{0, 1, 2},  {3, 4, 5},  {6, 7, 1},  {8, 6, 1},  {1, 0, 9},   {10, 6, 8},
             {11, 12, 3}, {5, 1, 11}, {5, 8, 1},  {1, 9, 11}, {11, 3, 5},  {13, 4, 3},
             {13, 3, 12}, {10, 2, 1}, {10, 1, 7}, {7, 6, 10}, {2, 10, 8}};
  return m;
}

TEST(Unwrap, LayoutIsValidWhateverTheOptions) {
  // Without augmentation nothing removed the pleat's degenerate UV triangle: the validity
  // fallback (another layout, or a split of the chart) must, in every mode.
  const TriMesh mesh = pleated_fragment();
  for (const ChartMode charts : {ChartMode::Single, ChartMode::Auto})
    for (const int augmentations : {0, 8})
      for (const EmbeddingWeights w : {EmbeddingWeights::ShapePreserving, EmbeddingWeights::MeanValue}) {
        SCOPED_TRACE(std::string(enum_name(charts)) + " augmentations " + std::to_string(augmentations) +
                     (w == EmbeddingWeights::MeanValue ? " mean-value" : " shape-preserving"));
        UnwrapOptions opt;
        opt.charts = charts;
        opt.max_augmentations = augmentations;
        opt.weights = w;
        const UnwrapResult r = unwrap(mesh, opt);
        const StretchStats s = measure_stretch(mesh, r.param);
        EXPECT_EQ(s.flipped, 0);
        EXPECT_EQ(s.degenerate, 0);
        EXPECT_EQ(count_overlapping_triangles(r.param), 0);
        EXPECT_TRUE(invalid_uv_faces(r.param).empty());
        EXPECT_GT(r.report.effective_texel_share, 0.05);
        for (const Vec2& t : r.param.uv) EXPECT_TRUE(t.x() >= 0 && t.x() <= 1 && t.y() >= 0 && t.y() <= 1);
      }
}

TEST(Unwrap, AugmentationLowersStretchOnTheSphere) {
  UnwrapOptions none;
  none.max_augmentations = 0;
  // An icosphere (the UV sphere of 32 x 16 is not augmented: its poles' cut is already good enough).
  const TriMesh mesh = shapes::icosphere(3);
  const UnwrapResult a = unwrap(mesh, none);
  const UnwrapResult b = unwrap(mesh);
  EXPECT_EQ(a.report.augmentations, 0);
  // The initial short cut leaves high stretch: the default options must augment it, lengthening the
  // cut and lowering the stretch (measured: 1 augmentation, cut 3.32 -> 4.98, L2 1.227 -> 1.183).
  ASSERT_GT(b.report.augmentations, 0);
  EXPECT_GT(b.report.cut_length, a.report.cut_length);
  EXPECT_LT(b.report.final_l2, a.report.final_l2);
}

TEST(Unwrap, ManyComponentsArePacked) {
  // Five tori of different sizes: five charts, sized by their area, no overlap.
  check_unwrap("five tori", test::five_tori());
}

TEST(Unwrap, ProgressAndCancel) {
  std::vector<std::string> phases;
  UnwrapOptions opt;
  opt.progress = [&](std::string_view ph, double f) {
    EXPECT_GE(f, 0.0);
    EXPECT_LE(f, 1.0);
    if (phases.empty() || phases.back() != ph) phases.emplace_back(ph);
    return true;
  };
  unwrap(shapes::torus(24, 8), opt);
  EXPECT_NE(std::find(phases.begin(), phases.end(), "cut"), phases.end());
  EXPECT_NE(std::find(phases.begin(), phases.end(), "pack"), phases.end());
  opt.progress = [](std::string_view, double) { return false; };
  EXPECT_THROW(unwrap(shapes::torus(24, 8), opt), CancelledError);
}

TEST(Unwrap, RejectsNonManifoldAndEmptyInput) {
  EXPECT_THROW(unwrap(shapes::nonmanifold_fan()), TopologyError);
  // A pinched vertex is not an error: it is split (test_unwrap_pinched.cpp).
  EXPECT_EQ(unwrap(shapes::bowtie_vertex()).report.num_components, 2);
  EXPECT_THROW(unwrap(TriMesh{}), TopologyError);
  UnwrapOptions bad;
  bad.chart_padding = 0.5;
  EXPECT_THROW(unwrap(shapes::plane(2), bad), InvalidInputError);
}

TEST(Unwrap, AutoStopsAtTheLargestChartCount) {
  // An unreachable share and the largest max_charts: auto tries 4, 6, 8, ... up to INT_MAX and
  // stops (the count after 3 * 2^29 does not fit an int; it used to wrap and cycle for ever).
  UnwrapOptions o;
  o.min_texel_share = 2;
  o.max_charts = std::numeric_limits<int>::max();
  const TriMesh m = shapes::plane(2);
  const UnwrapResult r = unwrap(m, o);
  EXPECT_GE(r.report.num_charts, 1);
  EXPECT_LE(r.report.num_charts, m.num_faces());
}

TEST(Unwrap, ProbeSkipsAHopelessSingleChartAndOnlyReordersTheCounts) {
  // Genus 3: the single chart's first cheap parameterization has an L2 of about 11 (> 3), so auto
  // gives it up; with probe_first_charts = 12 (the default) the segmentation starts at 12
  // (docs/charts.md).
  const TriMesh m = shapes::genus_surface(3);
  const UnwrapOptions from12;
  ASSERT_EQ(from12.probe_first_charts, 12);
  UnwrapResult probed;
  test::check_unwrap("probe", m, from12, &probed);
  EXPECT_GE(probed.report.num_charts, 12);
  EXPECT_GE(probed.report.effective_texel_share, 0.5);
  // Starting at 4 charts, the probe only skips the single chart: the layout is the one auto made
  // without the probe (single chart in full, then 4, 6, ...), bit for bit.
  UnwrapOptions from4;
  from4.probe_first_charts = 4;
  UnwrapOptions no_probe;
  no_probe.single_probe_l2 = 0;
  const UnwrapResult a = unwrap(m, from4);
  const UnwrapResult b = unwrap(m, no_probe);
  ASSERT_GT(b.report.num_charts, 1);
  EXPECT_LT(b.report.num_charts, 12);
  expect_same_layout(a, b);
}

TEST(Unwrap, ProbeKeepsAGoodSingleChartAndFallsBackToIt) {
  // A sphere: its single chart reaches the share, and the probe (L2 about 1.2 < 3) keeps it.
  const TriMesh m = shapes::genus_surface(0);
  UnwrapOptions single;
  single.charts = ChartMode::Single;
  const UnwrapResult one = unwrap(m, single);
  const UnwrapResult def = unwrap(m);
  EXPECT_EQ(def.report.num_charts, 1);
  EXPECT_TRUE(def.param.uv == one.param.uv);
  // A probe that gives up every chart (every L2 is >= 1) and no chart count to try (max_charts
  // < 4): the single chart is built after all, the same layout as ChartMode::Single.
  UnwrapOptions give_up;
  give_up.single_probe_l2 = 0.5;
  give_up.max_charts = 3;
  const UnwrapResult fallback = unwrap(m, give_up);
  EXPECT_EQ(fallback.report.num_charts, 1);
  expect_same_layout(fallback, one);
  // An unreachable share: every count is tried, and the result is never below the single chart.
  give_up.max_charts = 16;
  give_up.min_texel_share = 2;
  UnwrapResult best;
  test::check_unwrap("unreachable share", m, give_up, &best);
  EXPECT_GE(best.report.effective_texel_share, one.report.effective_texel_share);
  // Bad probe options.
  UnwrapOptions bad;
  bad.single_probe_l2 = -1;
  EXPECT_THROW(unwrap(m, bad), InvalidInputError);
  bad.single_probe_l2 = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(unwrap(m, bad), InvalidInputError);
  bad = UnwrapOptions{};
  bad.probe_first_charts = -1;
  EXPECT_THROW(unwrap(m, bad), InvalidInputError);
}

TEST(Unwrap, SpeculativeAttemptsGiveTheSequentialLayout) {
  // Genus 4: the probe gives the single chart up and auto builds 4, 6, 8 and 12 charts (12 is
  // kept). With speculation the next counts are built while one is decided; the layout must be the
  // one of one count after the other on one thread, bit for bit, for any window and thread count.
  const TriMesh m = shapes::genus_surface(4);
  UnwrapOptions sequential;
  sequential.speculative_attempts = 1;
  UnwrapResult ref;
  {
    const tbb::global_control one_thread(tbb::global_control::max_allowed_parallelism, 1);
    ref = unwrap(m, sequential);
  }
  ASSERT_GE(ref.report.num_charts, 8);  // several counts were tried
  EXPECT_GE(ref.report.effective_texel_share, 0.5);
  for (const int window : {1, 2, 3, 8}) {
    for (const int threads : {1, 2, 4}) {
      SCOPED_TRACE("window " + std::to_string(window) + ", threads " + std::to_string(threads));
      const tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
      UnwrapOptions o;
      o.speculative_attempts = window;
      expect_same_layout(unwrap(m, o), ref);
    }
  }
  // The path without the probe (single chart built in full, then 4, 6, ... charts, each count
  // skipped unless it has more pieces than the best layout so far) and the path where no count
  // reaches the share (the best of all counts is kept).
  UnwrapOptions no_probe;
  no_probe.single_probe_l2 = 0;
  no_probe.speculative_attempts = 1;
  const UnwrapResult ref_no_probe = unwrap(m, no_probe);
  no_probe.speculative_attempts = 4;
  expect_same_layout(unwrap(m, no_probe), ref_no_probe);
  UnwrapOptions unreachable;
  unreachable.min_texel_share = 2;
  unreachable.max_charts = 16;
  unreachable.speculative_attempts = 1;
  const UnwrapResult ref_best = unwrap(m, unreachable);
  unreachable.speculative_attempts = 3;
  expect_same_layout(unwrap(m, unreachable), ref_best);
  EXPECT_GT(ref_best.report.num_charts, 1);
  // A cancel while several counts are being built (at the packing of the first count, 4 charts,
  // while the next ones are under way) is still a CancelledError, and bad windows are rejected.
  UnwrapOptions cancel;
  cancel.speculative_attempts = 4;
  int packs = 0;
  cancel.progress = [&](std::string_view phase, double) { return phase != "pack" || ++packs > 1; };
  EXPECT_THROW(unwrap(m, cancel), CancelledError);
  EXPECT_EQ(packs, 1);
  UnwrapOptions bad;
  bad.speculative_attempts = 0;
  EXPECT_THROW(unwrap(m, bad), InvalidInputError);
}

TEST(Unwrap, ACancelWhileChartsAreBuiltInParallelIsACancelledError) {
  // A cancel in one chart while the others are built on other threads (and, with speculation, in
  // counts built ahead) must reach the caller as a CancelledError from every point of the work.
  // It once cancelled the TBB task group of the other charts, whose nested parallel loops then
  // returned with their work undone: a read out of bounds or an InvalidInputError instead.
  const TriMesh m = shapes::genus_surface(4);
  for (const int window : {1, 4}) {
    UnwrapOptions o;
    o.speculative_attempts = window;
    std::atomic<int> calls{0};
    o.progress = [&](std::string_view, double) {
      ++calls;
      return true;
    };
    unwrap(m, o);
    const int total = calls.load();
    ASSERT_GT(total, 20);
    int reached = 0;
    for (int i = 1; i <= 16; ++i) {
      const int at = total * i / 17;
      SCOPED_TRACE("window " + std::to_string(window) + ", cancel at report " + std::to_string(at));
      calls = 0;
      o.progress = [&](std::string_view, double) { return ++calls < at; };
      // With speculation the number of reports varies from run to run (counts built ahead are
      // abandoned at different points), so a late cancel point may not be reached: then the
      // unwrap must finish normally. Any other exception fails the test.
      bool cancelled = false;
      try {
        unwrap(m, o);
      } catch (const CancelledError&) {
        cancelled = true;
      }
      EXPECT_EQ(cancelled, calls.load() >= at);
      reached += cancelled ? 1 : 0;
    }
    // Without speculation the work, hence the number of reports, is the same every run. With it,
    // only the head count reports, and a count that becomes the head after being built ahead has
    // lost the reports of that part: only the cut and augmentation before it are sure.
    EXPECT_GE(reached, window == 1 ? 16 : 1);
  }
}

TEST(Pack, SquaresAreDisjointPaddedAndInside) {
  for (int n : {1, 2, 3, 7, 40, 500}) {
    std::vector<double> areas(n);
    for (int i = 0; i < n; ++i) areas[i] = 1.0 + (i * 37 % 11);
    const double pad = 0.01;
    const auto pl = pack_charts(areas, pad);
    ASSERT_EQ(static_cast<int>(pl.size()), n);
    if (n == 1) {
      EXPECT_EQ(pl[0].scale, 1.0);
      continue;
    }
    double used = 0;
    for (int i = 0; i < n; ++i) {
      EXPECT_GE(pl[i].offset.x(), 0.0);
      EXPECT_GE(pl[i].offset.y(), 0.0);
      EXPECT_LE(pl[i].offset.x() + pl[i].scale, 1.0);
      EXPECT_LE(pl[i].offset.y() + pl[i].scale, 1.0);
      used += pl[i].scale * pl[i].scale;
      for (int j = 0; j < i; ++j) {
        const bool apart = pl[i].offset.x() + pl[i].scale <= pl[j].offset.x() ||
                           pl[j].offset.x() + pl[j].scale <= pl[i].offset.x() ||
                           pl[i].offset.y() + pl[i].scale <= pl[j].offset.y() ||
                           pl[j].offset.y() + pl[j].scale <= pl[i].offset.y();
        EXPECT_TRUE(apart) << i << " " << j;
      }
    }
    // Sizes follow sqrt(area).
    for (int i = 1; i < n; ++i)
      EXPECT_NEAR(pl[i].scale / pl[0].scale, std::sqrt(areas[i] / areas[0]), 1e-9);
    if (n <= 40) {
      EXPECT_GT(used, 0.3) << "packing wastes too much of the square";
    }
  }
  EXPECT_THROW(pack_charts({}, 0.01), InvalidInputError);
}


TEST(Unwrap, ParallelChartsGiveTheSequentialLayout) {
  // Multi-chart layouts build their charts in parallel when the augmentation face budget cannot run
  // out: (1 + max_augmentations) cheap evaluations of 2 face-solves per face (augment_yoshizawa_
  // iterations = 1) = 18 F. One unit less forces the sequential path, which then cannot run out
  // either unless every chart used all 8 augmentations; both must give the same layout bit for bit.
  const TriMesh m = shapes::genus_surface(2);
  UnwrapOptions parallel;
  parallel.augment_face_budget = 18L * m.num_faces();
  UnwrapOptions sequential = parallel;
  sequential.augment_face_budget = parallel.augment_face_budget - 1;
  const UnwrapResult a = unwrap(m, parallel);
  const UnwrapResult b = unwrap(m, sequential);
  ASSERT_GT(a.report.num_charts, 1);
  EXPECT_GT(a.report.augmentations, 0);
  EXPECT_EQ(a.report.augmentations, b.report.augmentations);
  expect_same_layout(a, b);
}

}  // namespace
}  // namespace adaptex
