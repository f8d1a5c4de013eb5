// Two windows (or a window and an editor) on one study never lose an edit: ipd-studio holds a one-writer
// lock (checked with two processes), and every save first checks that the file on disk is still the one
// this window read or wrote; if not, nothing is overwritten and the user keeps one version.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <functional>

#include "app/studio/studio_saver.h"
#include "core/session/session.h"
#include "core/session/study_lock.h"
#include "core/util/atomic_file.h"
#include "tests/support/test_support.h"

namespace fs = std::filesystem;

namespace ipd {
namespace {

void write_study_save_conflict(const test::TempDir& d) { test::write_two_rock_study(d); }

std::string conflict_message(const std::string& file) {
  return file +
         ": changed on disk since this window read it (another window or program saved it); not overwritten: "
         "keep one version";
}

TEST(SaveConflict, ASecondWindowsSaveDoesNotOverwriteTheFirstOnesEdit) {
  test::TempDir d;
  write_study_save_conflict(d);
  Session first = Session::open(d.path()), second = Session::open(d.path());
  const std::string f = d / "pairs/real__synth/s1.json";
  const SaveJob mine = first.apply(0, Edit::pair(0, 0));
  run_save_job(mine);
  // Further edits of the same window save over its own file.
  const SaveJob again = first.apply(0, Edit::toggle_exclude(Side::kA, 1));
  run_save_job(again);
  EXPECT_EQ(read_file(f), *again.contents);
  const SaveJob theirs = second.apply(0, Edit::pair(1, 1));
  try {
    run_save_job(theirs);
    FAIL() << "expected a conflict";
  } catch (const SaveConflict& e) {
    EXPECT_EQ(std::string(e.what()), conflict_message(f));
    EXPECT_EQ(e.file, f);
    EXPECT_EQ(e.on_disk, again.contents);
    ASSERT_EQ(e.observed.size(), 2u);
    EXPECT_EQ(e.observed[0], version_of(again.contents));
    EXPECT_FALSE(e.observed[1].present);
    EXPECT_EQ(read_file(f), *again.contents);  // the first window's edit is still there
    // The user keeps the second window's version: written over exactly what the conflict found.
    run_save_job(Session::overwrite(theirs, e));
    EXPECT_EQ(read_file(f), *theirs.contents);
  }
  // The first window now finds a file it did not write: a conflict again, never a silent overwrite.
  EXPECT_THROW(run_save_job(first.apply(0, Edit::reset())), SaveConflict);
  EXPECT_EQ(read_file(f), *theirs.contents);
}

TEST(SaveConflict, KeepingTheDiskVersionReloadsTheScene) {
  test::TempDir d;
  write_study_save_conflict(d);
  Session first = Session::open(d.path()), second = Session::open(d.path());
  const SaveJob mine = first.apply(0, Edit::pair(0, 0));
  run_save_job(mine);
  EXPECT_THROW(run_save_job(second.apply(0, Edit::unpair(Side::kA, 0))), SaveConflict);
  second.reload_scene(0, "s1");
  EXPECT_EQ(second.scenes()[0].current.pairs, (RockPairs{{0, 0}}));
  EXPECT_TRUE(second.scenes()[0].edited);
  // Undo goes back to the second window's own edit; saving it is checked against the reloaded file.
  ASSERT_TRUE(second.can_undo());
  const SaveJob next = second.apply(0, Edit::pair(1, 1));
  run_save_job(next);
  EXPECT_EQ(read_file(d / "pairs/real__synth/s1.json"), *next.contents);
}

TEST(SaveConflict, AHandEditOfTheFileOrTheOtherNameOrderIsNotLost) {
  test::TempDir d;
  write_study_save_conflict(d);
  Session s = Session::open(d.path());
  // An editor writes the other name order while the window is open: the window's removal of it would lose it.
  test::write_text(d / "pairs/synth__real/s1.json", "{\"pairs\": [[1, 0]]}\n");
  try {
    run_save_job(s.apply(0, Edit::pair(0, 0)));
    FAIL() << "expected a conflict";
  } catch (const SaveConflict& e) {
    EXPECT_EQ(std::string(e.what()), conflict_message(d / "pairs/synth__real/s1.json"));
  }
  EXPECT_FALSE(fs::exists(d / "pairs/real__synth/s1.json"));  // nothing written
  EXPECT_EQ(read_file(d / "pairs/synth__real/s1.json"), "{\"pairs\": [[1, 0]]}\n");
}

// A hand edit that lands while the save writes and syncs its temp file (seconds on a slow or network disk) is
// found by the check made right before the rename: a conflict, the hand edit kept.
TEST(SaveConflict, AHandEditLandingWhileTheSaveIsWrittenIsNotLost) {
  test::TempDir d;
  write_study_save_conflict(d);
  Session s = Session::open(d.path());
  const std::string hand = "{\"pairs\": [[1, 1]]}\n";
  try {
    run_save_job(s.apply(0, Edit::pair(0, 0)), [&](const char* step) {
      if (std::string(step) == "temp written") test::write_text(d / "pairs/real__synth/s1.json", hand);
    });
    FAIL() << "expected a conflict";
  } catch (const SaveConflict& e) {
    EXPECT_EQ(std::string(e.what()), conflict_message(d / "pairs/real__synth/s1.json"));
  }
  EXPECT_EQ(read_file(d / "pairs/real__synth/s1.json"), hand);
  // No temp file is left beside it.
  int files = 0;
  for (const auto& e : fs::directory_iterator(d / "pairs/real__synth")) files += e.is_regular_file() ? 1 : 0;
  EXPECT_EQ(files, 1);
}

// The same for the review marks' file.
TEST(SaveConflict, AHandEditOfTheReviewFileLandingWhileTheSaveIsWrittenIsNotLost) {
  test::TempDir d;
  write_study_save_conflict(d);
  Session s = Session::open(d.path());
  const std::string hand = "{\"reviewed\": [\"s1\"]}\n";
  const SaveJob job = s.toggle_reviewed(0);
  try {
    run_save_job(job, [&](const char* step) {
      if (std::string(step) == "temp written") test::write_text(job.path, hand);
    });
    FAIL() << "expected a conflict";
  } catch (const SaveConflict& e) {
    EXPECT_EQ(std::string(e.what()), conflict_message(job.path));
  }
  EXPECT_EQ(read_file(job.path), hand);
}

TEST(SaveConflict, TheSaverKeepsConflictsForTheUserAndQueuedJobsKeepTheirExpectations) {
  test::TempDir d;
  write_study_save_conflict(d);
  Session first = Session::open(d.path()), second = Session::open(d.path());
  const std::string f = d / "pairs/real__synth/s1.json";
  {
    studio::Saver saver;
    // Three quick edits of one scene: however many the saver merges, none conflicts with the one before.
    saver.submit(first.apply(0, Edit::pair(0, 0)));
    saver.submit(first.apply(0, Edit::pair(1, 1)));
    const SaveJob last = first.apply(0, Edit::toggle_exclude(Side::kB, 1));
    saver.submit(last);
    saver.wait_idle();
    EXPECT_TRUE(saver.failures().empty()) << saver.failures().front();
    EXPECT_EQ(read_file(f), *last.contents);
    const SaveJob theirs = second.apply(0, Edit::unpair(Side::kA, 0));
    saver.submit(theirs);
    saver.wait_idle();
    ASSERT_EQ(saver.conflicts().size(), 1u);
    EXPECT_EQ(saver.conflicts()[0].message, conflict_message(f));
    EXPECT_EQ(saver.conflicts()[0].on_disk, last.contents);
    EXPECT_EQ(saver.failures(), std::vector<std::string>{conflict_message(f)});
    EXPECT_EQ(read_file(f), *last.contents);
    saver.keep_mine(f);
    saver.wait_idle();
    EXPECT_TRUE(saver.conflicts().empty());
    EXPECT_TRUE(saver.failures().empty());
    EXPECT_EQ(read_file(f), *theirs.contents);
  }
}

// Runs `child` in a forked process; its return value is the exit status.
int in_child(const std::function<int()>& child) {
  const pid_t pid = ::fork();
  if (pid == 0) ::_exit(child());
  int status = 0;
  ::waitpid(pid, &status, 0);
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

TEST(StudyLock, ASecondProcessIsToldWhoHoldsTheStudy) {
  test::TempDir d;
  write_study_save_conflict(d);
  std::string why;
  auto lock = StudyLock::try_acquire(d.path(), &why);
  ASSERT_TRUE(lock) << why;
  char host[256] = {};
  ::gethostname(host, sizeof host - 1);
  const std::string holder = "pid " + std::to_string(::getpid()) + " on " + host;
  EXPECT_EQ(read_file(d / ".ipd-cache/lock"), holder + "\n");
  // 0: refused with the holder named; 1: got the lock; 2: refused with another message.
  auto other = [&] {
    std::string held_by;
    if (StudyLock::try_acquire(d.path(), &held_by)) return 1;
    return held_by == holder ? 0 : 2;
  };
  EXPECT_EQ(in_child(other), 0);
  lock.reset();  // the first window closes
  EXPECT_EQ(in_child(other), 1);
  // A holder that died releases the lock with it (the kernel's lock, not the file, counts).
  EXPECT_EQ(in_child([&] {
              std::string held_by;
              auto mine = StudyLock::try_acquire(d.path(), &held_by);
              ::_exit(mine ? 0 : 3);  // exits holding it
              return 3;
            }),
            0);
  EXPECT_TRUE(StudyLock::try_acquire(d.path(), &why)) << why;
}

TEST(StudyLock, ALinkedCacheFolderGetsNoLockThroughIt) {
  test::TempDir d, x;
  write_study_save_conflict(d);
  fs::create_symlink(x.path(), d / ".ipd-cache");
  std::string why;
  EXPECT_FALSE(StudyLock::try_acquire(d.path(), &why));
  EXPECT_EQ(why, d / ".ipd-cache: is a symbolic link or not a folder; no lock is taken through it");
  EXPECT_TRUE(fs::is_empty(x.path()));
}

}  // namespace
}  // namespace ipd
