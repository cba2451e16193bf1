// PaintSession: each-stroke mode ends where end mode ends (issue 12 acceptance: "Replay after 50
// each-stroke re-parameterizations stays within 0.1 dB of end"), and its layout after every stroke is
// the one end mode computes for the history so far (path independence).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <memory>

#include "../asan_detect.h"
#include "adaptex/adapt/session.h"
#include "adaptex/core/errors.h"
#include "adaptex/core/shapes.h"
#include "adaptex/paint/eval.h"
#include "adaptex/paint/generate.h"
#include "adaptex/param/stretch.h"
#include "adaptex/param/unwrap.h"

namespace adaptex {
namespace {

StrokeFile generated(const TriMesh& mesh, StrokeKind kind, int count, std::uint64_t seed) {
  GenerateOptions go;
  go.kind = kind;
  go.count = count;
  go.seed = seed;
  return generate_strokes(mesh, go);
}

/// A session over the first \p n strokes of \p strokes (all: n < 0) with the method of \p base
/// (default: the default method), replay.
std::unique_ptr<PaintSession> painted(const TriMesh& mesh, const Parameterization& param, const StrokeFile& strokes,
                                      ReparamSchedule schedule, int size, int n = -1, PaintSessionOptions so = {}) {
  so.texture_size = size;
  so.schedule = schedule;
  auto s = std::make_unique<PaintSession>(mesh, param, so, strokes.background);
  const size_t count = n < 0 ? strokes.strokes.size() : static_cast<size_t>(n);
  for (size_t k = 0; k < count; ++k) s->add_stroke(strokes.strokes[k]);
  s->finish();
  return s;
}

/// Each-stroke mode at \p size with a cycle after every stroke (none skipped for a small predicted gain).
PaintSessionOptions every_stroke(int size) {
  PaintSessionOptions so;
  so.texture_size = size;
  so.schedule = ReparamSchedule::EachStroke;
  so.min_gain_db = 0;
  return so;
}

bool same_layout(PaintSession& a, PaintSession& b) {
  return a.mesh().num_faces() == b.mesh().num_faces() && a.param().uv == b.param().uv &&
         a.param().uv_faces == b.param().uv_faces && a.texture().data == b.texture().data;
}

TEST(PaintSession, EachStrokeEndsWithinATenthOfADecibelOfEndAfter50Strokes) {
#ifdef ADAPTEX_TEST_ASAN
  GTEST_SKIP() << "a quality figure over 50 strokes: checked in the Release pass (about 70 s under the sanitizers, "
                  "whose code paths the shorter session tests cover)";
#endif
  const TriMesh mesh = shapes::torus(48, 24);
  const Parameterization param = unwrap(mesh).param;
  const StrokeFile strokes = generated(mesh, StrokeKind::Lines, 50, 3);
  const int N = 128;
  const auto end = painted(mesh, param, strokes, ReparamSchedule::End, N);
  PaintSessionOptions every;
  every.min_gain_db = 0;  // 50 re-parameterizations, none skipped for a small predicted gain
  const auto each = painted(mesh, param, strokes, ReparamSchedule::EachStroke, N, -1, every);
  ASSERT_EQ(end->reports().size(), 1u);
  // One cycle per stroke; finish() owes none (the last cycle saw the whole history, replayed exactly).
  ASSERT_EQ(each->reports().size(), strokes.strokes.size());
  int accepted = 0;
  for (const AdaptReport& r : each->reports()) accepted += r.accepted;
  EvalOptions eo;
  eo.samples = 400000;
  const double p_end = evaluate_texture(end->mesh(), end->param(), end->texture(), strokes, eo).psnr;
  const double p_each = evaluate_texture(each->mesh(), each->param(), each->texture(), strokes, eo).psnr;
  std::printf("torus lines 50 strokes at %d: end %.3f dB, each-stroke %.3f dB (%d of %zu accepted)\n", N, p_end,
              p_each, accepted, each->reports().size());
  // Not trivial: the end-mode candidate was taken, and each-stroke mode adapted along the way.
  EXPECT_TRUE(end->reports().back().accepted);
  EXPECT_GT(accepted, 1);
  EXPECT_LE(std::abs(p_each - p_end), 0.1);
  // The reason: the last each-stroke re-parameterization is end mode's computation, judged the same way.
  EXPECT_TRUE(same_layout(*each, *end));
  const StretchStats st = measure_stretch(each->mesh(), each->param());
  EXPECT_EQ(st.flipped, 0);
  EXPECT_EQ(st.degenerate, 0);
}

TEST(PaintSession, PolishedLatticeRaisesThePsnrOfDots) {
  // density-flow with and without the error-model polish of the flow lattice (error_polish.h): one
  // chart (the torus unwraps to one square chart), hard dots, end mode.
  const TriMesh mesh = shapes::torus(48, 24);
  const Parameterization param = unwrap(mesh).param;
  ASSERT_EQ(param.num_charts, 1);
  const StrokeFile strokes = generated(mesh, StrokeKind::Dots, 40, 5);
  const int N = 128;
  PaintSessionOptions off;
  off.adapt.density_flow.polish.sweeps = 0;
  const auto plain = painted(mesh, param, strokes, ReparamSchedule::End, N, -1, off);
  const auto polished = painted(mesh, param, strokes, ReparamSchedule::End, N);
  const AdaptReport& r = polished->reports().back();
  ASSERT_TRUE(r.accepted);
  EXPECT_EQ(plain->reports().back().polish_sweeps, 0);
  EXPECT_GT(r.polish_sweeps, 0);
  EXPECT_LT(r.polish_error_after, r.polish_error_before);
  EvalOptions eo;
  eo.samples = 400000;
  const double p_plain = evaluate_texture(plain->mesh(), plain->param(), plain->texture(), strokes, eo).psnr;
  const double p_polished = evaluate_texture(polished->mesh(), polished->param(), polished->texture(), strokes, eo).psnr;
  std::printf("torus dots at %d: flow %.3f dB, polished %.3f dB (model gain %.2f dB, %d sweeps)\n", N, p_plain,
              p_polished, 10 * std::log10(r.polish_error_before / r.polish_error_after), r.polish_sweeps);
  EXPECT_GT(p_polished, p_plain + 0.5);  // measured +1.78 dB
  const StretchStats st = measure_stretch(polished->mesh(), polished->param());
  EXPECT_EQ(st.flipped, 0);
  EXPECT_EQ(st.degenerate, 0);
}

TEST(PaintSession, EachStrokeLayoutIsEndModesLayoutForTheHistorySoFar) {
  // Hard dots at 64², 8 strokes of seed 16: the sixth candidate wins against the fixed layout, the
  // seventh and eighth lose (measured), so the session adapts and returns to the initial layout.
  // (Seed 1's four strokes did this until session 16's unwrap, max_halvings 1, moved the sphere's
  // layout by a little.)
  const TriMesh mesh = shapes::sphere(32, 16);
  const Parameterization param = unwrap(mesh).param;
  const StrokeFile strokes = generated(mesh, StrokeKind::Dots, 8, 16);
  const int n = 8, N = 64;
  PaintSessionOptions so = every_stroke(N);
  // The measured accept / reject sequence above is that of the session-8 flow: a 128-cell lattice
  // with every point advected, blur 4, no polish. Coarse-to-fine advection, the finer default lattice
  // or the polish (error_polish.h) change the candidates by a fraction of a texel and this knife-edge
  // case then accepts or rejects all four. Path independence does not depend on it.
  so.adapt.density_flow.polish.sweeps = 0;
  so.adapt.density_flow.flow.interpolation_tolerance = 0;
  so.adapt.density_flow.flow.cells = 128;
  so.adapt.density_flow.flow.tolerance = 1e-2;
  so.adapt.density_flow.flow.max_step_cells = 2;
  so.adapt.density_flow.density.blur_cells = 4;
  PaintSession each(mesh, param, so, strokes.background);
  int accepted = 0, rejected_after_accept = 0;
  for (int k = 0; k < n; ++k) {
    each.add_stroke(strokes.strokes[k]);
    const bool acc = each.reports().back().accepted;
    rejected_after_accept += !acc && accepted > 0;
    accepted += acc;
    const auto end = painted(mesh, param, strokes, ReparamSchedule::End, N, k + 1, so);
    // Path independence: the layout (and so the replayed texture) depends on the history only, not on
    // which earlier candidates were taken. A rejected candidate means the initial layout, as in end mode.
    EXPECT_TRUE(same_layout(each, *end)) << "after stroke " << k;
    EXPECT_EQ(acc, end->reports().back().accepted) << "after stroke " << k;
  }
  std::printf("sphere dots %d strokes: %d accepted, %d rejected after an accepted one\n", n, accepted,
              rejected_after_accept);
  EXPECT_GT(accepted, 0);
  EXPECT_GT(rejected_after_accept, 0);
}

TEST(PaintSession, EachStrokeSkipsTheCyclesThatGainLessThanMinGainAndEndsOnEndModesLayout) {
  // min_gain_db: after a stroke the cycle computes the error model and stops there if the predicted
  // gain over the held layout is below min_gain_db. Three thresholds over the same history: 0 (a cycle
  // after every stroke), one that skips some cycles, and one no cycle reaches (every cycle skipped).
  const TriMesh mesh = shapes::torus(40, 20);
  const Parameterization param = unwrap(mesh).param;
  const StrokeFile strokes = generated(mesh, StrokeKind::Mixed, 12, 11);
  const int N = 128;
  PaintSessionOptions so;
  so.safeguard_samples = 8000;
  const auto end = painted(mesh, param, strokes, ReparamSchedule::End, N, -1, so);
  const int n = static_cast<int>(strokes.strokes.size());
  struct Case {
    double min_gain;
    int least_skipped, most_skipped;
  };
  for (const Case c : {Case{0.0, 0, 0}, Case{0.3, 1, n - 1}, Case{1e9, n, n}}) {
    const double min_gain = c.min_gain;
    so.min_gain_db = min_gain;
    so.texture_size = N;
    so.schedule = ReparamSchedule::EachStroke;
    PaintSession each(mesh, param, so, strokes.background);
    int skipped = 0;
    for (int k = 0; k < n; ++k) {
      const Parameterization held = each.param();
      const ImageRGBA8 held_texture = each.texture();
      each.add_stroke(strokes.strokes[k]);
      ASSERT_EQ(each.reports().size(), static_cast<size_t>(k + 1));
      const AdaptReport& r = each.reports().back();
      if (r.skipped) {
        ++skipped;
        EXPECT_LT(r.gain_over_held_db, min_gain) << "stroke " << k;
        EXPECT_FALSE(r.accepted);
        EXPECT_EQ(each.param().uv, held.uv) << "a skipped cycle keeps the layout, stroke " << k;
        EXPECT_NE(each.texture().data, held_texture.data) << "the stroke is painted on it, stroke " << k;
        EXPECT_GT(r.time_density, 0);
        EXPECT_EQ(r.time_polish + r.time_refine + r.time_remap + r.time_texel_map, 0);
      } else {  // a cycle that ran: the gain reached the threshold, or there is none
        EXPECT_TRUE(min_gain == 0 || r.gain_over_held_db >= min_gain) << "stroke " << k << ": " << r.gain_over_held_db;
      }
    }
    const size_t before_finish = each.reports().size();
    each.finish();
    // finish() catches up once when the last cycle was skipped: the session ends on end mode's layout.
    const bool owed = each.reports()[before_finish - 1].skipped;
    EXPECT_EQ(each.reports().size(), before_finish + (owed ? 1 : 0));
    EXPECT_FALSE(each.reports().back().skipped);
    EXPECT_TRUE(same_layout(each, *end)) << "min_gain " << min_gain;
    std::printf("torus mixed %d strokes, min_gain %g dB: %d cycles skipped\n", n, min_gain, skipped);
    EXPECT_GE(skipped, c.least_skipped) << "min_gain " << min_gain;
    EXPECT_LE(skipped, c.most_skipped) << "min_gain " << min_gain;
  }
}

TEST(PaintSession, AStrokeThatChangesNothingIsSkipped) {
  // A hard, opaque stroke painted twice: the second copy leaves the signal and the texture as they
  // were, so the predicted gain over the held layout is what it was after the first copy (0 if a
  // cycle ran then) and below any positive min_gain: the cycle is skipped.
  const TriMesh mesh = shapes::torus(40, 20);
  const Parameterization param = unwrap(mesh).param;
  StrokeFile strokes = generated(mesh, StrokeKind::Mixed, 8, 11);
  Stroke hard = strokes.strokes[5];
  hard.hardness = 1.0;
  hard.opacity = 1.0;
  strokes.strokes.push_back(hard);
  strokes.strokes.push_back(hard);
  for (int samples : {8000, 0}) {  // with the safeguard's samples (measured gain) and without (model only)
    PaintSessionOptions so;
    so.texture_size = 128;
    so.schedule = ReparamSchedule::EachStroke;
    so.safeguard_samples = samples;
    so.min_gain_db = 0.05;
    PaintSession s(mesh, param, so, strokes.background);
    for (const Stroke& st : strokes.strokes) s.add_stroke(st);
    const size_t n = s.reports().size();
    ASSERT_EQ(n, strokes.strokes.size());
    const AdaptReport& first = s.reports()[n - 2];
    const AdaptReport& second = s.reports()[n - 1];
    int accepted = 0;
    for (const AdaptReport& r : s.reports()) accepted += r.accepted;
    // Candidates are taken (without samples there is no safeguard: every candidate is).
    EXPECT_GT(accepted, 0) << "samples " << samples;
    EXPECT_TRUE(second.skipped) << "samples " << samples;
    EXPECT_NEAR(second.gain_over_held_db, first.skipped ? first.gain_over_held_db : 0.0, 1e-9) << "samples " << samples;
  }
}

TEST(PaintSession, BadMinGainIsRejected) {
  const TriMesh mesh = shapes::torus(12, 6);
  const Parameterization param = unwrap(mesh).param;
  for (const double bad : {-0.1, std::nan(""), HUGE_VAL}) {
    PaintSessionOptions so;
    so.texture_size = 32;
    so.min_gain_db = bad;
    EXPECT_THROW(PaintSession(mesh, param, so), InvalidInputError) << bad;
  }
}

}  // namespace
}  // namespace adaptex
