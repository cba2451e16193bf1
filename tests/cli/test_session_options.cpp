// The option strings of `adaptex paint` -> PaintSessionOptions (apps/cli/session_options.h).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <vector>

#include "adaptex/core/errors.h"
#include "session_options.h"

using namespace adaptex;
using namespace adaptex::cli;

TEST(CliSessionOptions, OptionsFromCliStrings) {
  const PaintSessionOptions o = make_session_options(512, 2, "single", {64}, -1, 0.5, "each-stroke", "resample");
  EXPECT_EQ(o.texture_size, 512);
  EXPECT_EQ(o.padding, 2);
  EXPECT_EQ(o.adapt.mode, AdaptMode::Single);
  EXPECT_EQ(o.adapt.thesis.fine_grid, 64);
  EXPECT_EQ(o.adapt.thesis.coarse_grid, AdaptOptions{}.thesis.coarse_grid);
  EXPECT_EQ(o.adapt.thesis.alpha, AdaptOptions{}.thesis.alpha);
  EXPECT_EQ(o.adapt.thesis.beta, 0.5);
  EXPECT_EQ(o.schedule, ReparamSchedule::EachStroke);
  EXPECT_EQ(o.update, TextureUpdate::Resample);
  EXPECT_TRUE(o.debug_dir.empty());
  const PaintSessionOptions t = make_session_options(256, 4, "two-stage", {16, 128}, 0.25, -1, "end", "replay", "dbg");
  EXPECT_EQ(t.adapt.mode, AdaptMode::TwoStage);
  EXPECT_EQ(t.adapt.thesis.coarse_grid, 16);
  EXPECT_EQ(t.adapt.thesis.fine_grid, 128);
  EXPECT_EQ(t.adapt.thesis.alpha, 0.25);
  EXPECT_EQ(t.schedule, ReparamSchedule::End);
  EXPECT_EQ(t.update, TextureUpdate::Replay);
  EXPECT_EQ(t.debug_dir, std::filesystem::path("dbg"));
}

TEST(CliSessionOptions, BadStringsThrowInvalidInput) {
  EXPECT_THROW(make_session_options(512, 2, "fancy", {}, -1, -1, "end", "replay"), InvalidInputError);
  EXPECT_THROW(make_session_options(512, 2, "none", {1, 2, 3}, -1, -1, "end", "replay"), InvalidInputError);
  EXPECT_THROW(make_session_options(512, 2, "none", {0}, -1, -1, "end", "replay"), InvalidInputError);
  EXPECT_THROW(make_session_options(512, 2, "none", {}, std::nan(""), -1, "end", "replay"), InvalidInputError);
  EXPECT_THROW(make_session_options(512, 2, "none", {}, -1, -1, "sometimes", "replay"), InvalidInputError);
  EXPECT_THROW(make_session_options(512, 2, "none", {}, -1, -1, "end", "copy"), InvalidInputError);
  EXPECT_EQ(parse_reparam_schedule("each_stroke"), ReparamSchedule::EachStroke);
  EXPECT_THROW(parse_reparam_schedule("End"), InvalidInputError);
  EXPECT_THROW(parse_texture_update(""), InvalidInputError);
}

TEST(CliSessionOptions, GridTextOfPaintAndReparam) {
  EXPECT_EQ(parse_grid("16,256"), (std::vector<int>{16, 256}));
  EXPECT_EQ(parse_grid("64"), (std::vector<int>{64}));
  EXPECT_EQ(parse_grid("64,64"), (std::vector<int>{64, 64}));
  for (const char* bad : {"", "16,x", "16,", ",16", "1", "8,64,128", "5000", "16 ,64", " 16", "+16", "-16", "0x10",
                          "256,16", "99999999999"})
    EXPECT_THROW(parse_grid(bad), InvalidInputError) << bad;
  AdaptOptions o;
  set_grid(o, {});
  EXPECT_EQ(o.thesis.fine_grid, AdaptOptions{}.thesis.fine_grid);
  EXPECT_EQ(o.thesis.coarse_grid, AdaptOptions{}.thesis.coarse_grid);
  set_grid(o, {8, 64});
  EXPECT_EQ(o.thesis.coarse_grid, 8);
  EXPECT_EQ(o.thesis.fine_grid, 64);
  EXPECT_THROW(set_grid(o, {8, 64, 128}), InvalidInputError);
  EXPECT_THROW(set_grid(o, {5000}), InvalidInputError);
}
