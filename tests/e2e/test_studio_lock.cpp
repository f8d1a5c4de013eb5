// A second ipd-studio on a study another process holds (here: this test, through the same lock) opens it
// read-only, says who holds it, and writes no pairs file. Run by ctest under Xvfb (StudioReplayEdits, which
// sets IPD_STUDIO); skipped otherwise.
#include <gtest/gtest.h>
#include <unistd.h>

#include <fmt/format.h>
#include <cstdlib>
#include <filesystem>

#include "core/session/study_lock.h"
#include "core/util/atomic_file.h"
#include "tests/support/test_support.h"

namespace fs = std::filesystem;

namespace ipd {
namespace {

TEST(StudioReplay, ASecondWindowOpensReadOnlyNamingTheHolderAndSavesNothing) {
  const char* studio = std::getenv("IPD_STUDIO");
  if (!studio || !*studio) GTEST_SKIP() << "set IPD_STUDIO to the ipd-studio binary (ctest does)";
  test::TempDir d;
  ASSERT_EQ(test::run_ipd(fmt::format("demo {} --labels-only --scenes 3 --rocks 12", d / "study")).exit_code, 0);
  std::string why;
  const auto first_window = StudyLock::try_acquire(d / "study", &why);
  ASSERT_TRUE(first_window) << why;
  test::write_text(d / "actions.txt", "scene scene_00002\npair 2 3\n");
  const std::string cmd =
      fmt::format("XDG_CACHE_HOME={} {} {} --replay {}", d / "cache", studio, d / "study", d / "actions.txt");
  std::system(fmt::format("xvfb-run -a -s '-screen 0 1280x800x24' sh -c '{}' >{} 2>&1", cmd, d / "log.txt").c_str());
  char host[256] = {};
  ::gethostname(host, sizeof host - 1);
  const std::string log = read_file(d / "log.txt");
  EXPECT_NE(log.find(fmt::format("note: {}: read-only: another window holds this study (pid {} on {}): edits stay "
                                 "in memory\n",
                                 d / "study", ::getpid(), host)),
            std::string::npos)
      << log;
  EXPECT_FALSE(fs::exists(d / "study/pairs/real__principled/scene_00002.json"));
}

// A recent-studies list that can't be written (here a folder of its name) is no lost edit: the replay's edit
// is saved, the warning says what failed, and the run exits 0.
TEST(StudioReplay, AnUnwritableRecentStudiesListIsAWarningNotALostEdit) {
  const char* studio = std::getenv("IPD_STUDIO");
  if (!studio || !*studio) GTEST_SKIP() << "set IPD_STUDIO to the ipd-studio binary (ctest does)";
  test::TempDir d;
  ASSERT_EQ(test::run_ipd(fmt::format("demo {} --labels-only --scenes 3 --rocks 12", d / "study")).exit_code, 0);
  fs::create_directories(d / "cache/ipd-studio/recent.txt");
  test::write_text(d / "actions.txt", "scene scene_00002\npair 2 3\n");
  const std::string cmd = fmt::format("XDG_CACHE_HOME={} {} {} --replay {}; echo exit $?", d / "cache", studio,
                                      d / "study", d / "actions.txt");
  std::system(fmt::format("xvfb-run -a -s '-screen 0 1280x800x24' sh -c '{}' >{} 2>&1", cmd, d / "log.txt").c_str());
  const std::string log = read_file(d / "log.txt");
  EXPECT_NE(log.find("warning: the recent-studies list was not saved: " + d / "cache/ipd-studio/recent.txt" +
                     ": is not a regular file; not replaced\n"),
            std::string::npos)
      << log;
  EXPECT_EQ(log.find("edit not saved"), std::string::npos) << log;
  EXPECT_NE(log.find("exit 0"), std::string::npos) << log;
  EXPECT_TRUE(fs::exists(d / "study/pairs/real__principled/scene_00002.json"));
}

}  // namespace
}  // namespace ipd
