// Hand pairs are the one thing that must never be lost: the save order (write + rename the new file, fsync,
// only then remove the other name order) is checked by failing at every step.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <stdexcept>

#include "core/session/session.h"
#include "core/util/atomic_file.h"
#include "tests/support/test_support.h"

namespace fs = std::filesystem;

namespace ipd {
namespace {

// real: perf {1, 1/3}; synth: perf {0, 1/3}. Automatic pairs (0,1), (1,0): IPD 1/2.
void write_study_with_hand_pairs(const test::TempDir& d) {
  test::write_text(d / "real/labels/s1.txt", "0 0.2 0.2 0.1 0.1\n0 0.6 0.6 0.1 0.1\n");
  test::write_text(d / "synth/labels/s1.txt", "0 0.6 0.6 0.1 0.1\n0 0.2 0.2 0.1 0.1\n");
  test::write_text(d / "real/predictions/det/s1.txt", "0 0.2 0.2 0.1 0.1 0.9\n0 0.65 0.6 0.1 0.1 0.4\n");
  test::write_text(d / "synth/predictions/det/s1.txt", "0 0.25 0.2 0.1 0.1 0.8\n");
  // Hand pairs saved in the other name order: synth 1 <-> real 0 only: IPD |1 - 1/3| = 2/3.
  test::write_text(d / "pairs/synth__real/s1.json", "{\"pairs\": [[1, 0]]}\n");
}

double ipd_on_disk(const std::string& root) {
  return compute_cross_table(load_labels(open_study(root)), {}).cells[0].ipd;
}

constexpr double kHand = 2.0 / 3, kEdited = 1.0, kAutomatic = 0.5;

TEST(SaveOrder, AFailedWriteKeepsTheOtherNameOrderFile) {
  test::TempDir d;
  write_study_with_hand_pairs(d);
  Session s = Session::open(d.path());
  ASSERT_NEAR(s.cell().ipd, kHand, 1e-12);
  const SaveJob job = s.apply(0, Edit::pair(0, 0));  // real 0 <-> synth 0 only: IPD 1
  ASSERT_EQ(job.path, d / "pairs/real__synth/s1.json");
  // The new file's directory can't be made (a file is in the way): the write fails, as on a full disk.
  test::write_text(d / "pairs/real__synth", "in the way");
  EXPECT_THROW(run_save_job(job), IoError);
  EXPECT_TRUE(fs::exists(d / "pairs/synth__real/s1.json"));
  fs::remove(d / "pairs/real__synth");               // (a file where a pairs folder belongs is itself an error to read)
  EXPECT_NEAR(ipd_on_disk(d.path()), kHand, 1e-12);  // not the automatic 1/2
}

struct Crash : std::runtime_error {
  using std::runtime_error::runtime_error;
};

TEST(SaveOrder, ACrashBetweenAnyTwoStepsLeavesTheOldOrTheNewPairs) {
  // step -> the state a crash right after it must leave (the new one once the rename happened)
  const std::vector<std::pair<std::string, double>> write_steps = {
      {"temp written", kHand}, {"renamed", kEdited}, {"directory synced", kEdited}, {"other removed", kEdited}};
  for (const auto& [step, expected] : write_steps) {
    test::TempDir d;
    write_study_with_hand_pairs(d);
    Session s = Session::open(d.path());
    const SaveJob job = s.apply(0, Edit::pair(0, 0));
    bool crashed = false;
    try {
      run_save_job(job, [&, step = step](const char* at) {
        if (at == step) throw Crash(at);
      });
    } catch (const Crash&) {
      crashed = true;
    }
    EXPECT_TRUE(crashed) << step;
    EXPECT_NEAR(ipd_on_disk(d.path()), expected, 1e-12) << "crash after " << step;
    EXPECT_NEAR(Session::open(d.path()).cell().ipd, expected, 1e-12) << "crash after " << step;
  }
  // Back to automatic: the other name order goes first, so the file read first still holds the old pairs.
  for (const auto& [step, expected] :
       std::vector<std::pair<std::string, double>>{{"other removed", kEdited}, {"removed", kAutomatic}}) {
    test::TempDir d;
    write_study_with_hand_pairs(d);
    test::write_text(d / "pairs/real__synth/s1.json", "{\"pairs\": [[0, 0]]}\n");  // both orders present
    Session s = Session::open(d.path());
    ASSERT_NEAR(s.cell().ipd, kEdited, 1e-12);
    const SaveJob job = s.apply(0, Edit::reset());
    ASSERT_FALSE(job.contents.has_value());
    try {
      run_save_job(job, [&, step = step](const char* at) {
        if (at == step) throw Crash(at);
      });
    } catch (const Crash&) {
    }
    EXPECT_NEAR(ipd_on_disk(d.path()), expected, 1e-12) << "crash after " << step;
  }
}

TEST(SaveOrder, StaleTempFilesOfDeadWritersAreRemoved) {
  test::TempDir d;
  // pid 2^22 + 1 is above Linux's pid_max limit: no such process.
  test::write_text(d / "s1.json.tmp-4194305-77", "{\"pairs\": [");
  test::write_text(d / ("s2.json.tmp-" + std::to_string(::getpid()) + "-5"), "a live writer's");
  test::write_text(d / "s3.json", "{}");
  EXPECT_EQ(remove_stale_temp_files(d.path()), 1);
  EXPECT_FALSE(fs::exists(d / "s1.json.tmp-4194305-77"));
  EXPECT_TRUE(fs::exists(d / ("s2.json.tmp-" + std::to_string(::getpid()) + "-5")));
  EXPECT_TRUE(fs::exists(d / "s3.json"));
}

// The review marks' temp files of an interrupted save were never removed (only the pairs folders were
// tidied). Opening the study removes ours whose writer is gone, in review/ and pairs/<A>__<B>/; a live
// writer's stays, and so does a link of such a name (not ours), its target untouched.
TEST(SaveOrder, OpeningAStudyRemovesStaleTempFilesOfReviewMarksAndPairs) {
  test::TempDir d, elsewhere;
  test::write_two_rock_study(d);
  const std::string live = "real__synth.json.tmp-" + std::to_string(::getpid()) + "-2";
  test::write_text(d / "review/real__synth.json.tmp-4194305-1", "{\"reviewed\": [");
  test::write_text(d / ("review/" + live), "a live writer's");
  test::write_text(elsewhere / "precious.json", "keep\n");
  fs::create_symlink(elsewhere / "precious.json", d / "review/other.json.tmp-4194305-3");
  test::write_text(d / "pairs/real__synth/s1.json.tmp-4194305-4", "{\"pairs\": [");
  const Session s = Session::open(d.path());
  EXPECT_FALSE(fs::exists(d / "review/real__synth.json.tmp-4194305-1"));
  EXPECT_FALSE(fs::exists(d / "pairs/real__synth/s1.json.tmp-4194305-4"));
  EXPECT_TRUE(fs::exists(d / ("review/" + live)));
  EXPECT_TRUE(fs::is_symlink(d / "review/other.json.tmp-4194305-3"));
  EXPECT_EQ(read_file(elsewhere / "precious.json"), "keep\n");
}

}  // namespace
}  // namespace ipd
