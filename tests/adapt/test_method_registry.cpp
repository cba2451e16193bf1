// A method added from outside the library (method.h): an identity warp, registered from this test
// with one line and no edit in the library, the CLI, the studio or Python. It is listed with the
// built-in methods, chosen by name, and runs through adapt_parameterization() and a painting session
// (one solver per session) like any method.
#include <gtest/gtest.h>

#include <algorithm>
#include <memory>
#include <string>

#include "adaptex/adapt/method.h"
#include "adaptex/adapt/session.h"
#include "adaptex/core/errors.h"
#include "adaptex/core/shapes.h"
#include "adaptex/paint/generate.h"
#include "adaptex/paint/painter.h"
#include "adaptex/param/unwrap.h"
#include "identity_method.h"

namespace adaptex {
namespace {

using test::IdentityMethod;

const bool registered = test::register_identity_method();

double largest_move(const Parameterization& a, const Parameterization& b) {
  double d = 0;
  for (size_t w = 0; w < a.uv.size(); ++w) d = std::max(d, (a.uv[w] - b.uv[w]).norm());
  return d;
}

TEST(MethodRegistry, ARegisteredMethodIsListedAndParsedByName) {
  ASSERT_TRUE(registered);
  std::vector<std::string> names;
  for (AdaptMode m : adapt_modes()) names.push_back(to_string(m));
  const std::vector<std::string> expected{"none", "single", "two-stage", "density-flow", "identity"};
  ASSERT_GE(names.size(), expected.size());
  EXPECT_TRUE(std::equal(expected.begin(), expected.end(), names.begin()));
  const AdaptMode m = parse_adapt_mode("identity");
  EXPECT_EQ(std::string(m.name()), "identity");
  EXPECT_FALSE(m == AdaptMode::DensityFlow);
  ASSERT_NE(find_adapt_method(m), nullptr);
  EXPECT_EQ(find_adapt_method(m)->description, "test: the identity warp");
  EXPECT_EQ(parse_adapt_mode("density-flow"), AdaptMode::DensityFlow);
  // The error for an unknown name lists every registered method.
  try {
    parse_adapt_mode("swirl");
    FAIL() << "no error for an unknown method";
  } catch (const InvalidInputError& e) {
    EXPECT_NE(std::string(e.what()).find("density-flow or identity"), std::string::npos) << e.what();
  }
}

TEST(MethodRegistry, NamesAreUniqueAndNeedAFactory) {
  ASSERT_TRUE(registered);
  EXPECT_THROW(register_adapt_method({"identity", "again", [] { return std::make_unique<IdentityMethod>(); }}),
               InvalidInputError);
  EXPECT_THROW(register_adapt_method({"", "nameless", [] { return std::make_unique<IdentityMethod>(); }}),
               InvalidInputError);
  EXPECT_THROW(register_adapt_method({"no-factory", "none", nullptr}), InvalidInputError);
  EXPECT_THROW(make_adapt_method(AdaptMode::None), InvalidInputError);
}

TEST(MethodRegistry, TheIdentityMethodRunsThroughTheAdaptation) {
  ASSERT_TRUE(registered);
  const TriMesh mesh = shapes::torus(24, 12);
  const Parameterization param = unwrap(mesh).param;
  PainterOptions po;
  po.width = po.height = 64;
  Painter p(mesh, param, po);
  AdaptOptions ao;
  ao.mode = parse_adapt_mode("identity");
  const int before = IdentityMethod::computed;
  const AdaptResult r = adapt_parameterization(mesh, param, p.texture(), p.texel_map(), ao);
  EXPECT_EQ(IdentityMethod::computed, before + 1);
  EXPECT_EQ(std::string(to_string(r.report.mode)), "identity");
  ASSERT_TRUE(r.warp);
  EXPECT_FALSE(r.refined_mesh);  // the method does not ask for refinement
  ASSERT_EQ(r.param.uv.size(), param.uv.size());
  EXPECT_LT(largest_move(r.param, param), 1e-12);
  EXPECT_EQ(r.report.flipped_after, 0);
}

TEST(MethodRegistry, ASessionKeepsOneSolverAndRunsACycleAfterEveryStroke) {
  ASSERT_TRUE(registered);
  const TriMesh mesh = shapes::torus(24, 12);
  const Parameterization param = unwrap(mesh).param;
  GenerateOptions go;
  go.count = 3;
  go.seed = 2;
  const StrokeFile strokes = generate_strokes(mesh, go);
  PaintSessionOptions so;
  so.texture_size = 64;
  so.schedule = ReparamSchedule::EachStroke;
  so.adapt.mode = parse_adapt_mode("identity");
  so.surface_cache = 0;  // every cycle replays exactly: finish() has nothing to redo
  const int made = IdentityMethod::made, computed = IdentityMethod::computed;
  PaintSession s(mesh, param, so, strokes.background);
  for (const Stroke& st : strokes.strokes) s.add_stroke(st);
  s.finish();
  EXPECT_EQ(IdentityMethod::made, made + 1);
  EXPECT_EQ(IdentityMethod::computed, computed + static_cast<int>(strokes.strokes.size()));
  ASSERT_EQ(s.reports().size(), strokes.strokes.size());
  for (const AdaptReport& r : s.reports()) EXPECT_EQ(std::string(to_string(r.mode)), "identity");
  EXPECT_LT(largest_move(s.param(), param), 1e-12);
}

}  // namespace
}  // namespace adaptex
