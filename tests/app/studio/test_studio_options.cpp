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

}  // namespace
}  // namespace ipd::studio
