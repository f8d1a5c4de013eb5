// A study is untrusted: a symbolic link in pairs/ (the folder, a pairs/<A>__<B> folder or a pairs file) is
// never written through, deleted through or read through, even when it is swapped in between the check
// and the write (the write step hook makes that moment deterministic).
#include <gtest/gtest.h>

#include <filesystem>
#include <stdexcept>

#include "core/ipd/ipd.h"
#include "core/session/session.h"
#include "core/util/atomic_file.h"
#include "core/util/contained_file.h"
#include "tests/support/test_support.h"

namespace fs = std::filesystem;

namespace ipd {
namespace {

void write_study_pairs_symlinks(const test::TempDir& d) { test::write_two_rock_study(d); }

const char* kPairs = "{\"pairs\": [[0, 1]]}\n";

std::string refused(const std::string& path, const char* action) {
  return path + ": is a symbolic link; " + action + " through it is refused (links inside a study are never followed)";
}

std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const std::exception& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(PairsSymlinks, ReadingRefusesEveryLinkInPairs) {
  test::TempDir d, x;
  write_study_pairs_symlinks(d);
  test::write_text(x / "real__synth/s1.json", kPairs);
  test::write_text(x / "s1.json", kPairs);
  // pairs -> x
  fs::create_symlink(x.path(), d / "pairs");
  EXPECT_EQ(error_of([&] { Session::open(d.path()); }), refused(d / "pairs", "reading"));
  EXPECT_EQ(error_of([&] { compute_cross_table(load_labels(open_study(d.path())), {}); }),
            refused(d / "pairs", "reading"));
  // pairs/real__synth -> x/real__synth
  fs::remove(d / "pairs");
  fs::create_directories(d / "pairs");
  fs::create_symlink(x / "real__synth", d / "pairs/real__synth");
  EXPECT_EQ(error_of([&] { Session::open(d.path()); }), refused(d / "pairs/real__synth", "reading"));
  // pairs/real__synth/s1.json -> x/s1.json
  fs::remove(d / "pairs/real__synth");
  fs::create_directories(d / "pairs/real__synth");
  fs::create_symlink(x / "s1.json", d / "pairs/real__synth/s1.json");
  EXPECT_EQ(error_of([&] { Session::open(d.path()); }), refused(d / "pairs/real__synth/s1.json", "reading"));
}

TEST(PairsSymlinks, AValidFileBesideALinkedOtherOrderIsNotOpenedThroughIt) {
  // The attack: a valid pairs/real__synth/s1.json and pairs/synth__real -> /victim. The study does not open
  // (nothing is read through the link), and so no edit can delete victim/s1.json.
  test::TempDir d, victim;
  write_study_pairs_symlinks(d);
  test::write_text(d / "pairs/real__synth/s1.json", kPairs);
  test::write_text(victim / "s1.json", "precious");
  fs::create_symlink(victim.path(), d / "pairs/synth__real");
  EXPECT_EQ(error_of([&] { Session::open(d.path()); }), refused(d / "pairs/synth__real", "reading"));
  EXPECT_EQ(read_file(victim / "s1.json"), "precious");
}

TEST(PairsSymlinks, ASaveRefusesALinkedPairsFolder) {
  test::TempDir d, x;
  write_study_pairs_symlinks(d);
  Session s = Session::open(d.path());
  fs::create_symlink(x.path(), d / "pairs");  // swapped in while the study is open
  const SaveJob job = s.apply(0, Edit::pair(0, 0));
  EXPECT_EQ(error_of([&] { run_save_job(job); }), refused(d / "pairs", "saving"));
  EXPECT_TRUE(fs::is_empty(x.path()));
}

TEST(PairsSymlinks, ASaveRefusesToDeleteThroughALinkedOtherOrderAndWritesNothing) {
  test::TempDir d, victim;
  write_study_pairs_symlinks(d);
  test::write_text(d / "pairs/real__synth/s1.json", kPairs);
  Session s = Session::open(d.path());
  test::write_text(victim / "s1.json", "precious");
  fs::create_symlink(victim.path(), d / "pairs/synth__real");
  const SaveJob job = s.apply(0, Edit::pair(1, 0));
  ASSERT_EQ(job.also_remove, std::vector<std::string>{d / "pairs/synth__real/s1.json"});
  EXPECT_EQ(error_of([&] { run_save_job(job); }), refused(d / "pairs/synth__real", "saving"));
  EXPECT_EQ(read_file(victim / "s1.json"), "precious");
  EXPECT_EQ(read_file(d / "pairs/real__synth/s1.json"), kPairs);  // checked before anything was written
  // Back to automatic removes both orders: refused the same way.
  EXPECT_EQ(error_of([&] { run_save_job(s.apply(0, Edit::reset())); }), refused(d / "pairs/synth__real", "saving"));
  EXPECT_EQ(read_file(victim / "s1.json"), "precious");
}

TEST(PairsSymlinks, ASaveRefusesALinkedPairsFile) {
  test::TempDir d, elsewhere;
  write_study_pairs_symlinks(d);
  Session s = Session::open(d.path());
  test::write_text(elsewhere / "kept.json", kPairs);
  fs::create_directories(d / "pairs/real__synth");
  fs::create_symlink(elsewhere / "kept.json", d / "pairs/real__synth/s1.json");
  EXPECT_EQ(error_of([&] { run_save_job(s.apply(0, Edit::pair(0, 0))); }),
            refused(d / "pairs/real__synth/s1.json", "saving"));
  EXPECT_EQ(read_file(elsewhere / "kept.json"), kPairs);
  EXPECT_TRUE(fs::is_symlink(d / "pairs/real__synth/s1.json"));
}

TEST(PairsSymlinks, ALinkSwappedInAfterTheCheckIsReplacedNotFollowed) {
  test::TempDir d, victim;
  write_study_pairs_symlinks(d);
  test::write_text(d / "pairs/real__synth/s1.json", kPairs);
  Session s = Session::open(d.path());
  test::write_text(victim / "s1.json", "precious");
  const SaveJob job = s.apply(0, Edit::pair(0, 0));
  run_save_job(job, [&](const char* step) {
    if (std::string(step) != "checked") return;
    fs::remove(d / "pairs/real__synth/s1.json");
    fs::create_symlink(victim / "s1.json", d / "pairs/real__synth/s1.json");
  });
  EXPECT_EQ(read_file(victim / "s1.json"), "precious");
  EXPECT_FALSE(fs::is_symlink(d / "pairs/real__synth/s1.json"));
  EXPECT_EQ(read_file(d / "pairs/real__synth/s1.json"), *job.contents);
}

TEST(PairsSymlinks, AFolderSwappedForALinkAfterItWasOpenedIsNotFollowed) {
  test::TempDir d, victim;
  write_study_pairs_symlinks(d);
  fs::create_directories(d / "pairs/real__synth");
  Session s = Session::open(d.path());
  const SaveJob job = s.apply(0, Edit::pair(0, 0));
  run_save_job(job, [&](const char* step) {
    if (std::string(step) != "folder opened") return;
    fs::rename(d / "pairs/real__synth", d / "pairs/moved");
    fs::create_symlink(victim.path(), d / "pairs/real__synth");
  });
  EXPECT_TRUE(fs::is_empty(victim.path()));
  EXPECT_EQ(read_file(d / "pairs/moved/s1.json"), *job.contents);  // written into the folder it opened
}

TEST(PairsSymlinks, ARemovalWhoseFileBecomesALinkRemovesTheLinkOnly) {
  test::TempDir d, victim;
  write_study_pairs_symlinks(d);
  test::write_text(victim / "s1.json", "precious");
  test::write_text(d / "pairs/real__synth/s1.json", kPairs);
  EXPECT_TRUE(remove_file_beneath(d.path(), "pairs/real__synth/s1.json", [&](const char* step) {
    if (std::string(step) != "checked") return;
    fs::remove(d / "pairs/real__synth/s1.json");
    fs::create_symlink(victim / "s1.json", d / "pairs/real__synth/s1.json");
  }));
  EXPECT_EQ(read_file(victim / "s1.json"), "precious");
  EXPECT_FALSE(fs::exists(fs::symlink_status(d / "pairs/real__synth/s1.json")));
}

// Read straight through the file layer, with no scan before it: a linked folder on the way is refused by the
// one-call open (openat2, RESOLVE_NO_SYMLINKS) as by the folder-by-folder walk, which names it, whether it is
// the last folder or one in the middle.
TEST(PairsSymlinks, AFileReadBelowALinkedFolderIsRefusedNamingTheLink) {
  test::TempDir d, x;
  test::write_text(x / "real__synth/s1.json", kPairs);
  test::write_text(x / "real__synth/deeper/s1.json", kPairs);
  fs::create_directories(d / "pairs");
  fs::create_symlink(x / "real__synth", d / "pairs/real__synth");
  EXPECT_EQ(error_of([&] { read_file_beneath(d.path(), "pairs/real__synth/s1.json", 1 << 20); }),
            refused(d / "pairs/real__synth", "reading"));
  EXPECT_EQ(error_of([&] { read_file_beneath(d.path(), "pairs/real__synth/deeper/s1.json", 1 << 20); }),
            refused(d / "pairs/real__synth", "reading"));
}

TEST(PairsSymlinks, PathsThatClimbOutOfTheStudyAreRefused) {
  test::TempDir d;
  EXPECT_EQ(error_of([&] { write_file_beneath(d.path(), "pairs/../../x.json", "{}"); }),
            d.path() + "/pairs/../../x.json: expected a plain path inside the folder");
  EXPECT_EQ(error_of([&] { read_file_beneath(d.path(), "/etc/passwd"); }),
            d.path() + "//etc/passwd: expected a plain path inside the folder");
}

TEST(PairsSymlinks, StaleTempFilesAreTidiedOnlyInRealFolders) {
  test::TempDir d, x;
  write_study_pairs_symlinks(d);
  const std::string dead = "s1.json.tmp-4194305-77";  // pid above Linux's pid_max: no such process
  test::write_text(d / ("pairs/real__synth/" + dead), "{");
  test::write_text(x / dead, "someone else's");
  fs::create_symlink(x.path(), d / "pairs/synth__real");
  EXPECT_THROW(Session::open(d.path()), StudyError);            // the link refuses the study ...
  EXPECT_FALSE(fs::exists(d / ("pairs/real__synth/" + dead)));  // ... after its own leftovers were tidied
  EXPECT_TRUE(fs::exists(x / dead));                            // but nothing behind the link
}

}  // namespace
}  // namespace ipd
