// Letters typed into a dialog or a text field belong to it: in a real window (Xvfb, --replay's `type`, which
// presses each key as a keyboard does), the shortcut letters R (review), X (exclude), U (unpair) and C (check)
// typed after a rejected entry or with no field active never reach the scene behind, and no pairs or review file
// is written. Run by ctest (StudioKeyboardOwnership, which sets IPD_STUDIO); skipped otherwise.
#include <gtest/gtest.h>

#include <fmt/format.h>
#include <cstdlib>
#include <filesystem>
#include <string>

#include "core/session/study_lock.h"
#include "core/util/atomic_file.h"
#include "tests/support/test_support.h"

namespace fs = std::filesystem;

namespace ipd {
namespace {

int run(const std::string& cmd) {
  const int status = std::system(cmd.c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

// The files below `dir` (none when it does not exist), one per line.
std::string files_below(const fs::path& dir) {
  std::string out;
  std::error_code ec;
  if (!fs::exists(dir, ec)) return out;
  for (const auto& e : fs::recursive_directory_iterator(dir))
    if (e.is_regular_file()) out += e.path().lexically_relative(dir).string() + "\n";
  return out;
}

struct StudioRun {
  int exit_code = -1;
  std::string log;
};

// The demo study (3 scenes of 12 rocks) with scene_00002 shown and its left rock 3 selected, so that each
// shortcut letter would edit something, then `actions`, then the scene list written to list.txt.
StudioRun replay_with_rock_selected(const test::TempDir& d, const std::string& actions) {
  test::write_text(d / "actions.txt",
                   "scene scene_00002\nclick 3\n" + actions + "wait 10\nlist " + d / "list.txt" + "\n");
  const fs::path status_file = d / "exit-status.txt";
  const std::string cmd = fmt::format("XDG_CACHE_HOME={} {} {} --replay {}", d / "cache", std::getenv("IPD_STUDIO"),
                                      d / "study", d / "actions.txt");
  run(fmt::format("xvfb-run -a -s '-screen 0 1280x800x24' sh -c '{}; echo $? >{}' >{} 2>&1", cmd, status_file.string(),
                  d / "log.txt"));
  StudioRun r;
  r.log = read_file(d / "log.txt");
  if (fs::exists(status_file)) r.exit_code = std::stoi(read_file(status_file));
  return r;
}

class StudioKeyboard : public ::testing::Test {
 protected:
  void SetUp() override {
    const char* studio = std::getenv("IPD_STUDIO");
    if (!studio || !*studio) GTEST_SKIP() << "set IPD_STUDIO to the ipd-studio binary (ctest does)";
    ASSERT_EQ(test::run_ipd(fmt::format("demo {} --labels-only --scenes 3 --rocks 12", d / "study")).exit_code, 0);
  }
  // Nothing the letters could have done reached the disk.
  void expect_study_untouched(const StudioRun& r) {
    EXPECT_EQ(r.exit_code, 0) << r.log;
    EXPECT_EQ(files_below(d / "study/pairs"), "") << r.log;
    EXPECT_EQ(files_below(d / "study/review"), "") << r.log;
  }
  test::TempDir d;
};

// The Open dialog's path is rejected ("no such folder"); the field keeps the keyboard, and the dialog owns it.
TEST_F(StudioKeyboard, LettersAfterARejectedPathInOpenStudyEditNothing) {
  const StudioRun r =
      replay_with_rock_selected(d, "dialog open\ntype /no-such-folder\nkey enter\ntype rxuc\nkey escape\n");
  expect_study_untouched(r);
}

// Go to scene with a name that matches nothing, Enter, then letters.
TEST_F(StudioKeyboard, LettersAfterAnUnmatchedNameInGoToSceneEditNothing) {
  const StudioRun r = replay_with_rock_selected(d, "dialog goto\ntype nosuchscene\nkey enter\ntype rxuc\nkey escape\n");
  expect_study_untouched(r);
}

// The Export dialog opens with no field active: its letters must still not reach the shortcuts.
TEST_F(StudioKeyboard, LettersInTheExportDialogWithNoFieldActiveEditNothing) {
  const StudioRun r = replay_with_rock_selected(d, "dialog export\ntype rxuc\nkey escape\n");
  expect_study_untouched(r);
  EXPECT_EQ(files_below(d.path()).find(".pdf"), std::string::npos);  // Esc cancelled it: nothing exported
}

// The Shortcuts window is a dialog too: its letters do nothing but Esc closes it.
TEST_F(StudioKeyboard, LettersOverTheShortcutsListEditNothing) {
  const StudioRun r = replay_with_rock_selected(d, "dialog help\ntype rxuc\nkey escape\n");
  expect_study_untouched(r);
}

// The scene list's filter: a filter that matches no scene, Enter, then letters: they go on into the filter
// (which then still matches nothing), not to the scene in view.
TEST_F(StudioKeyboard, LettersAfterEnterInTheSceneFilterStayInTheFilter) {
  const StudioRun r = replay_with_rock_selected(d, "dialog search\ntype zzz\nkey enter\ntype rxuc\n");
  expect_study_untouched(r);
  EXPECT_EQ(read_file(d / "list.txt"), "\n");  // no chip, no scene: the filter reads zzzrxuc
}

// The same filter, left with Esc: the shortcuts are the keyboard's again (the test's own control: the replay's
// letters do reach them when nothing else holds the keyboard).
TEST_F(StudioKeyboard, AfterEscLeavesTheFilterTheLettersAreShortcutsAgain) {
  const StudioRun r = replay_with_rock_selected(d, "dialog search\ntype zzz\nkey escape\ntype r\n");
  EXPECT_EQ(r.exit_code, 0) << r.log;
  EXPECT_EQ(files_below(d / "study/review"), "real__principled.json\n") << r.log;
}

// A read-only study's 'save as' field: Enter saves (nothing was edited), then letters stay in the field. A
// letter that reached a shortcut would leave an edit in memory, which fails the replay.
TEST_F(StudioKeyboard, LettersAfterEnterInSaveAsEditNothing) {
  std::string why;
  const auto first_window = StudyLock::try_acquire(d / "study", &why);  // this window is read-only
  ASSERT_TRUE(first_window) << why;
  const StudioRun r = replay_with_rock_selected(d, "dialog saveas\ntype " + d / "copy" + "\nkey enter\ntype rxuc\n");
  EXPECT_EQ(r.exit_code, 0) << r.log;
  EXPECT_EQ(r.log.find("only in memory"), std::string::npos) << r.log;
  EXPECT_EQ(files_below(d / "copy"), "");
  EXPECT_EQ(files_below(d / "study/pairs"), "");
}

}  // namespace
}  // namespace ipd
