// The pictures are what an audit looks at: in a real window (Xvfb) at 1600 x 900 and 1920 x 1080, the two
// pictures of a 1936 x 1216 study take at least 30% of the window's area in the default layout and at least
// 50% in the focus view, as --frame-stats' picture_px line measures them. Run by ctest (StudioPictureArea,
// which sets IPD_STUDIO); skipped otherwise.
#include <gtest/gtest.h>

#include <fmt/format.h>
#include <cstdlib>
#include <filesystem>
#include <regex>
#include <string>

#include "core/util/atomic_file.h"
#include "tests/support/test_support.h"

namespace fs = std::filesystem;

namespace ipd {
namespace {

struct PictureArea {
  int left_w = 0, left_h = 0, right_w = 0, right_h = 0, window_w = 0, window_h = 0;
  double share() const { return (double(left_w) * left_h + double(right_w) * right_h) / (double(window_w) * window_h); }
};

// ipd-studio at `w` x `h` on the study, after `actions` (a replay), its picture_px line read back.
PictureArea measure(const test::TempDir& d, int w, int h, const std::string& actions, std::string* log) {
  test::write_text(d / "actions.txt", actions + "wait 5\n");
  const std::string cmd =
      fmt::format("XDG_CACHE_HOME={} sh {} {}x{}x24 {} {} --size {}x{} --replay {} --frame-stats >{} 2>&1", d / "cache",
                  IPD_TESTS_DIR "/e2e/run_in_xvfb.sh", w, h, std::getenv("IPD_STUDIO"), d / "study", w, h,
                  d / "actions.txt", d / "log.txt");
  std::system(cmd.c_str());
  *log = read_file(d / "log.txt");
  std::smatch m;
  PictureArea a;
  static const std::regex line(R"(picture_px left=(\d+)x(\d+) right=(\d+)x(\d+) window=(\d+)x(\d+) share=[0-9.]+)");
  if (std::regex_search(*log, m, line))
    a = {std::stoi(m[1]), std::stoi(m[2]), std::stoi(m[3]), std::stoi(m[4]), std::stoi(m[5]), std::stoi(m[6])};
  return a;
}

class StudioPictures : public ::testing::TestWithParam<std::pair<int, int>> {};

TEST_P(StudioPictures, TakeAThirdOfTheWindowAndHalfInTheFocusView) {
  if (!std::getenv("IPD_STUDIO") || !*std::getenv("IPD_STUDIO"))
    GTEST_SKIP() << "set IPD_STUDIO to the ipd-studio binary (ctest does)";
  const auto [w, h] = GetParam();
  test::TempDir d;
  ASSERT_EQ(
      test::run_ipd(fmt::format("demo {} --labels-only --scenes 3 --rocks 30 --width 1936 --height 1216", d / "study"))
          .exit_code,
      0);
  std::string log;
  const PictureArea normal = measure(d, w, h, "", &log);
  EXPECT_EQ(normal.window_w, w) << log;
  EXPECT_EQ(normal.window_h, h) << log;
  // Both pictures whole (fitted), the same size, 16:10 as the study's image_size.
  EXPECT_EQ(normal.left_w, normal.right_w) << log;
  EXPECT_NEAR(double(normal.left_w) / normal.left_h, 1936.0 / 1216, 0.02) << log;
  EXPECT_GE(normal.share(), 0.30) << log;
  const PictureArea focus = measure(d, w, h, "focus on\n", &log);
  EXPECT_GE(focus.share(), 0.50) << log;
}

INSTANTIATE_TEST_SUITE_P(Windows, StudioPictures,
                         ::testing::Values(std::make_pair(1600, 900), std::make_pair(1920, 1080)),
                         [](const auto& info) { return fmt::format("{}x{}", info.param.first, info.param.second); });

}  // namespace
}  // namespace ipd
