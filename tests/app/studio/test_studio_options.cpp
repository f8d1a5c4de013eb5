// The studio's options hold the ranges its command line accepts; StudioApp refuses anything else by name.
#include <gtest/gtest.h>

#include <stdexcept>

#include "app/studio/studio_options.h"

namespace ipd::studio {
namespace {

TEST(StudioOptions, NameTheBadField) {
  StudioOptions o;
  EXPECT_EQ(o.validate(), "");
  o.cycle_scenes = -1;  // no cycling, as 0
  EXPECT_EQ(o.validate(), "");
  o.frames = 0;
  EXPECT_EQ(o.validate(), "frames must be at least 1, got 0");
  o.frames = 60;
  o.cycle_step = 0;
  EXPECT_EQ(o.validate(), "cycle_step must be at least 1, got 0");
  o.cycle_step = 1;
  o.texture_budget_mb = 8;
  EXPECT_EQ(o.validate(), "texture_budget_mb must be at least 16, got 8");
  o.texture_budget_mb = 512;
  o.width = 200;
  EXPECT_EQ(o.validate(), "the window must be at least 320 x 240, got 200 x 900");
  try {
    o.check();
    FAIL() << "check() accepted a 200-pixel window";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "studio options: the window must be at least 320 x 240, got 200 x 900");
  }
}

TEST(StudioOptions, SizeTakesWidthByHeightOrTheWidthAlone) {
  int w = 1600, h = 900;
  EXPECT_EQ(parse_window_size("1280x720", &w, &h), "");
  EXPECT_EQ(w, 1280);
  EXPECT_EQ(h, 720);
  EXPECT_EQ(parse_window_size("1920X1080", &w, &h), "");
  EXPECT_EQ(w, 1920);
  EXPECT_EQ(h, 1080);
  EXPECT_EQ(parse_window_size("1000", &w, &h), "");  // the width alone keeps the height
  EXPECT_EQ(w, 1000);
  EXPECT_EQ(h, 1080);
  EXPECT_EQ(parse_window_size("320x240", &w, &h), "");  // the smallest window
  EXPECT_EQ(w, 320);
  EXPECT_EQ(h, 240);
  const std::string pair_rule =
      "--size: expected WIDTHxHEIGHT with a width from 320 to 10000 and a height from 240 to 10000 (e.g. 1280x720), "
      "got ";
  EXPECT_EQ(parse_window_size("1280x200", &w, &h), pair_rule + "'1280x200'");
  EXPECT_EQ(parse_window_size("319x240", &w, &h), pair_rule + "'319x240'");
  EXPECT_EQ(parse_window_size("1280x", &w, &h), pair_rule + "'1280x'");
  EXPECT_EQ(parse_window_size("1280x720x2", &w, &h), pair_rule + "'1280x720x2'");
  EXPECT_EQ(parse_window_size("1280 x 720", &w, &h), pair_rule + "'1280 x 720'");
  EXPECT_EQ(parse_window_size("12.5", &w, &h),
            "--size: expected a width from 320 to 10000, or WIDTHxHEIGHT (e.g. 1280x720), got '12.5'");
  EXPECT_EQ(w, 320);  // a refused size changes nothing
  EXPECT_EQ(h, 240);
}

}  // namespace
}  // namespace ipd::studio
