// The demo generator's options name the field that is wrong and its range; nothing is written for them.
#include <gtest/gtest.h>

#include <filesystem>
#include <stdexcept>

#include "core/demo/demo_study.h"
#include "tests/support/test_support.h"

namespace ipd {
namespace {

TEST(DemoStudyOptions, NameTheBadField) {
  DemoStudyOptions o;
  EXPECT_EQ(o.validate(), "");
  o.scenes = 0;
  EXPECT_EQ(o.validate(), "scenes must be at least 1, got 0");
  o.scenes = 2;
  o.min_rocks = 20;
  o.max_rocks = 10;
  EXPECT_EQ(o.validate(), "rocks per scene must satisfy 0 <= min_rocks <= max_rocks, got [20, 10]");
  o.min_rocks = 5;
  o.height = 32;
  EXPECT_EQ(o.validate(), "width and height must be at least 64 pixels, got 960 x 32");
  const test::TempDir d;
  try {
    write_demo_study(d / "demo", o);
    FAIL() << "write_demo_study accepted 32-pixel pictures";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "demo study options: width and height must be at least 64 pixels, got 960 x 32");
  }
  EXPECT_FALSE(std::filesystem::exists(d / "demo"));
}

}  // namespace
}  // namespace ipd
