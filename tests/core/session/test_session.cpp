// The GUI's state and edit logic, without a display: pairing, unpairing, excluding, undo/redo, saving
// (read back by the engine) and live IPD.
#include <gtest/gtest.h>
#include <sched.h>
#include <sys/mount.h>
#include <sys/wait.h>
#include <unistd.h>

#include <fmt/format.h>
#include <cmath>
#include <filesystem>
#include <functional>
#include <random>

#include "core/session/session.h"
#include "tests/support/test_support.h"

namespace fs = std::filesystem;

namespace ipd {
namespace {

// The tiny study of test_ipd.cpp: IPD 1/2 with pairs (0,1), (1,0); perf real = {1, 1/3}, synth = {0, 1/3}.
void write_tiny_study_session(const test::TempDir& d) {
  test::write_text(d / "real/labels/s1.txt", "0 0.2 0.2 0.1 0.1\n0 0.6 0.6 0.1 0.1\n");
  test::write_text(d / "synth/labels/s1.txt", "0 0.6 0.6 0.1 0.1\n0 0.2 0.2 0.1 0.1\n");
  test::write_text(d / "real/predictions/det/s1.txt", "0 0.2 0.2 0.1 0.1 0.9\n0 0.65 0.6 0.1 0.1 0.4\n");
  test::write_text(d / "synth/predictions/det/s1.txt", "0 0.25 0.2 0.1 0.1 0.8\n");
}

double table_ipd_from_disk(const std::string& root) {
  return compute_cross_table(load_labels(open_study(root)), {}).cells[0].ipd;
}

TEST(Session, OpensWithTheEngineFigures) {
  test::TempDir d;
  write_tiny_study_session(d);
  const Session s = Session::open(d.path());
  ASSERT_EQ(s.scenes().size(), 1u);
  EXPECT_EQ(s.left_domain(), "real");
  EXPECT_EQ(s.model(), "det");
  EXPECT_NEAR(s.cell().ipd, 0.5, 1e-12);
  EXPECT_EQ(s.view_pairs(0), (RockPairs{{0, 1}, {1, 0}}));
  const SceneSummary sum = s.summary(0);
  EXPECT_NEAR(sum.ipd, 0.5, 1e-12);
  EXPECT_EQ(sum.pairs, 2);
  EXPECT_FALSE(sum.edited);
}

TEST(Session, PairUnpairUndoRedoAndSaveAreSeenByTheEngine) {
  test::TempDir d;
  write_tiny_study_session(d);
  Session s = Session::open(d.path());
  // Unpair real rock 1: only (0,1) is left, |1 - 1/3| = 2/3.
  SaveJob job = s.apply(0, Edit::unpair(Side::kA, 1));
  EXPECT_NEAR(s.cell().ipd, 2.0 / 3, 1e-12);
  EXPECT_EQ(s.summary(0).unpaired_a, 1);
  EXPECT_TRUE(s.summary(0).edited);
  EXPECT_EQ(job.path, d / "pairs/real__synth/s1.json");
  ASSERT_TRUE(job.contents.has_value());
  EXPECT_EQ(*job.contents, "{\"pairs\":[[0,1]],\"rocks_a\":[[0,0.2,0.2,0.1,0.1]],\"rocks_b\":[[1,0.2,0.2,0.1,0.1]]}\n");
  run_save_job(job);
  EXPECT_NEAR(table_ipd_from_disk(d.path()), 2.0 / 3, 1e-12);
  // Pair real 0 with synth 0: replaces real 0's old partner. perf 1 vs 0 -> IPD 1.
  run_save_job(s.apply(0, Edit::pair(0, 0)));
  EXPECT_EQ(s.view_pairs(0), (RockPairs{{0, 0}}));
  EXPECT_NEAR(s.cell().ipd, 1.0, 1e-12);
  EXPECT_NEAR(table_ipd_from_disk(d.path()), 1.0, 1e-12);
  // Undo twice: back to automatic, and the file is removed.
  run_save_job(*s.undo());
  EXPECT_NEAR(s.cell().ipd, 2.0 / 3, 1e-12);
  const auto back = s.undo();
  ASSERT_TRUE(back.has_value());
  EXPECT_FALSE(back->contents.has_value());
  run_save_job(*back);
  EXPECT_FALSE(std::filesystem::exists(d / "pairs/real__synth/s1.json"));
  EXPECT_NEAR(s.cell().ipd, 0.5, 1e-12);
  EXPECT_FALSE(s.undo().has_value());
  // Redo re-applies the unpair.
  run_save_job(*s.redo());
  EXPECT_NEAR(s.cell().ipd, 2.0 / 3, 1e-12);
  EXPECT_NEAR(table_ipd_from_disk(d.path()), 2.0 / 3, 1e-12);
  // A new edit drops the redo branch.
  s.apply(0, Edit::reset());
  EXPECT_FALSE(s.can_redo());
  EXPECT_NEAR(s.cell().ipd, 0.5, 1e-12);
}

// Re-making registration's pairs by hand makes the scene automatic again: its pairs file goes, the engine
// counts registration's pairs, and undo still walks back through the steps.
TEST(Session, HandPairsEqualToRegistrationsMakeTheSceneAutomatic) {
  test::TempDir d;
  write_tiny_study_session(d);
  Session s = Session::open(d.path());
  const fs::path file = d / "pairs/real__synth/s1.json";
  run_save_job(s.apply(0, Edit::unpair(Side::kA, 1)));  // (0,1) alone: hand-edited, IPD 2/3
  ASSERT_TRUE(fs::exists(file));
  EXPECT_TRUE(s.summary(0).edited);
  EXPECT_NEAR(s.cell().ipd, 2.0 / 3, 1e-12);
  // Pairing real 1 with synth 0 again gives registration's {(0,1), (1,0)}.
  const SaveJob job = s.apply(0, Edit::pair(1, 0));
  EXPECT_FALSE(job.contents.has_value());  // the job removes the file
  run_save_job(job);
  EXPECT_FALSE(fs::exists(file));
  EXPECT_FALSE(s.summary(0).edited);
  EXPECT_EQ(s.view_pairs(0), (RockPairs{{0, 1}, {1, 0}}));
  EXPECT_NEAR(s.cell().ipd, 0.5, 1e-12);
  EXPECT_NEAR(table_ipd_from_disk(d.path()), 0.5, 1e-12);
  // The history keeps both steps: undo brings the hand pairs (and their file) back.
  run_save_job(*s.undo());
  EXPECT_TRUE(fs::exists(file));
  EXPECT_TRUE(s.summary(0).edited);
  EXPECT_NEAR(table_ipd_from_disk(d.path()), 2.0 / 3, 1e-12);
  // Registration's pairs with a rock excluded are still hand-made: the exclusion is saved.
  run_save_job(*s.redo());
  run_save_job(s.apply(0, Edit::toggle_exclude(Side::kA, 0)));
  EXPECT_TRUE(s.summary(0).edited);
  EXPECT_TRUE(fs::exists(file));
}

// 300 copies of the tiny study's scene (s001 ... s300): scenes 0 and 200 in different chunks of CowVector's 128 scenes.
void write_300_scene_study(const test::TempDir& d) {
  for (int k = 1; k <= 300; ++k) {
    const std::string stem = fmt::format("s{:03d}", k);
    test::write_text(d / ("real/labels/" + stem + ".txt"), "0 0.2 0.2 0.1 0.1\n0 0.6 0.6 0.1 0.1\n");
    test::write_text(d / ("synth/labels/" + stem + ".txt"), "0 0.6 0.6 0.1 0.1\n0 0.2 0.2 0.1 0.1\n");
    test::write_text(d / ("real/predictions/det/" + stem + ".txt"), "0 0.2 0.2 0.1 0.1 0.9\n0 0.65 0.6 0.1 0.1 0.4\n");
    test::write_text(d / ("synth/predictions/det/" + stem + ".txt"), "0 0.25 0.2 0.1 0.1 0.8\n");
  }
}

// The studio publishes copies of its Session after every edit: an edit, undo or redo made after a copy never
// shows in the copy, and the copy shares the scenes the edit did not touch.
TEST(Session, ACopyIsASnapshotThatLaterEditsLeaveAlone) {
  test::TempDir d;
  write_300_scene_study(d);
  Session s = Session::open(d.path());
  ASSERT_EQ(s.scenes().size(), 300u);
  const Session before = s;
  // Unpair real rock 1 of s201: its (1, 0) pair goes, |1/3 - 0| with it. Each scene's sum is 1 over 2 pairs;
  // s201's is 2/3 over 1 pair: (299 + 2/3) / 599 = 899 / 1797.
  s.apply(200, Edit::unpair(Side::kA, 1));
  EXPECT_NEAR(s.cell().ipd, 899.0 / 1797, 1e-12);
  EXPECT_EQ(s.view_pairs(200), (RockPairs{{0, 1}}));
  EXPECT_EQ(s.audit(200).pairs.size(), 1u);
  EXPECT_TRUE(s.summary(200).edited);
  EXPECT_NEAR(before.cell().ipd, 0.5, 1e-12);
  EXPECT_EQ(before.cell().pairs, 600);
  EXPECT_EQ(before.view_pairs(200), (RockPairs{{0, 1}, {1, 0}}));
  EXPECT_EQ(before.audit(200).pairs.size(), 2u);
  EXPECT_FALSE(before.summary(200).edited);
  EXPECT_NEAR(before.summary(200).ipd, 0.5, 1e-12);
  EXPECT_EQ(before.contributions_for("det", 0)[200].pairs, 2);
  EXPECT_FALSE(before.can_undo());
  EXPECT_TRUE(s.scenes().shares_element(before.scenes(), 0));     // another chunk: shared
  EXPECT_FALSE(s.scenes().shares_element(before.scenes(), 200));  // the edited scene's chunk: copied

  const Session edited = s;
  ASSERT_TRUE(s.undo().has_value());
  EXPECT_NEAR(s.cell().ipd, 0.5, 1e-12);
  EXPECT_EQ(edited.view_pairs(200), (RockPairs{{0, 1}}));
  EXPECT_NEAR(edited.cell().ipd, 899.0 / 1797, 1e-12);
  EXPECT_TRUE(edited.can_undo());
  EXPECT_FALSE(edited.can_redo());
  ASSERT_TRUE(s.redo().has_value());
  s.apply(5, Edit::toggle_exclude(Side::kA, 0));  // a new edit drops the redo history of s, not of `edited`
  EXPECT_FALSE(s.can_redo());
  EXPECT_TRUE(s.excluded(Side::kA, 5, 0));
  EXPECT_FALSE(edited.excluded(Side::kA, 5, 0));
  EXPECT_EQ(edited.contributions_for("det", 0)[5].pairs, 2);
}

// A hand-paired scene opens with its pairs file only: no registration until it is needed, and meanwhile its
// audit says it waits for one instead of measuring residuals against a made-up affine.
TEST(Session, AHandPairedSceneIsRegisteredOnlyWhenNeeded) {
  test::TempDir d;
  write_tiny_study_session(d);
  test::write_text(d / "pairs/real__synth/s1.json",
                   "{\"pairs\":[[0,1]],\"rocks_a\":[[0,0.2,0.2,0.1,0.1]],\"rocks_b\":[[1,0.2,0.2,0.1,0.1]]}\n");
  Session s = Session::open(d.path());
  ASSERT_EQ(s.scenes().size(), 1u);
  EXPECT_FALSE(s.scenes()[0].registered);
  EXPECT_TRUE(s.scenes()[0].edited);
  EXPECT_TRUE(s.audit(0).waits_for_registration);
  EXPECT_TRUE(s.audit(0).pairs.empty());
  EXPECT_EQ(s.audit(0).suspects, 0);
  EXPECT_NEAR(s.cell().ipd, 2.0 / 3, 1e-12);  // the hand pair (0, 1) counts: |1 - 1/3|
  const Session before = s;
  EXPECT_TRUE(s.register_scene(0, 0));
  EXPECT_FALSE(s.register_scene(0, 0));  // once
  EXPECT_TRUE(s.scenes()[0].registered);
  EXPECT_EQ(s.scenes()[0].automatic.pairs, (RockPairs{{0, 1}, {1, 0}}));
  EXPECT_FALSE(s.audit(0).waits_for_registration);
  ASSERT_EQ(s.audit(0).pairs.size(), 1u);  // the audit of the hand pair against the found affine
  EXPECT_NEAR(s.audit(0).pairs[0].residual_px, 0, 1e-6);
  EXPECT_EQ(s.view_pairs(0), (RockPairs{{0, 1}}));  // still the hand pairs
  EXPECT_NEAR(s.cell().ipd, 2.0 / 3, 1e-12);
  EXPECT_FALSE(before.scenes()[0].registered);  // a snapshot taken before keeps waiting

  // Going back to automatic pairs on a scene not registered yet registers it first.
  Session fresh = Session::open(d.path());
  ASSERT_FALSE(fresh.scenes()[0].registered);
  fresh.apply(0, Edit::reset());
  EXPECT_TRUE(fresh.scenes()[0].registered);
  EXPECT_EQ(fresh.view_pairs(0), (RockPairs{{0, 1}, {1, 0}}));
  EXPECT_NEAR(fresh.cell().ipd, 0.5, 1e-12);
}

TEST(Session, ExcludeAndSwappedView) {
  test::TempDir d;
  write_tiny_study_session(d);
  Session s = Session::open(d.path());
  ASSERT_TRUE(s.select_domains("synth", "real"));
  EXPECT_TRUE(s.swapped());
  EXPECT_EQ(s.left_domain(), "synth");
  EXPECT_EQ(s.view_pairs(0), (RockPairs{{0, 1}, {1, 0}}));  // (synth, real)
  // Exclude synth rock 0 (left): its pair (real 1, synth 0) leaves the IPD: only |1 - 1/3| remains.
  const SaveJob job = s.apply(0, Edit::toggle_exclude(Side::kA, 0));
  EXPECT_NEAR(s.cell().ipd, 2.0 / 3, 1e-12);
  EXPECT_TRUE(s.excluded(Side::kA, 0, 0));
  EXPECT_EQ(*job.contents,
            "{\"excluded_b\":[0],\"pairs\":[[0,1],[1,0]],\"rocks_a\":[[0,0.2,0.2,0.1,0.1],[1,0.6,0.6,0.1,0.1]],"
            "\"rocks_b\":[[0,0.6,0.6,0.1,0.1],[1,0.2,0.2,0.1,0.1]]}\n");
  // The header: one pair counted; the excluded rock's partner (real 1, on the right) is not unpaired.
  EXPECT_EQ(s.summary(0).pairs, 1);
  EXPECT_EQ(s.summary(0).unpaired_a, 0);
  EXPECT_EQ(s.summary(0).unpaired_b, 0);
  // Pair left (synth) 1 with right (real) 1: stored as real 1 <-> synth 1.
  s.apply(0, Edit::pair(1, 1));
  EXPECT_EQ(s.view_pairs(0), (RockPairs{{1, 1}}));
  ASSERT_TRUE(s.select_domains("real", "synth"));
  EXPECT_EQ(s.view_pairs(0), (RockPairs{{1, 1}}));
}

TEST(Session, ConfidenceThresholdMovesTheIpd) {
  test::TempDir d;
  write_tiny_study_session(d);
  Session s = Session::open(d.path());
  s.set_conf_threshold(0.5);  // real rock 1's prediction (0.4) is dropped: diffs 2/3 and 0
  EXPECT_NEAR(s.cell().ipd, 1.0 / 3, 1e-12);
  EXPECT_EQ(s.predictions(Side::kA, 0).size(), 1u);
}

TEST(Session, IncrementalTotalsMatchAFullRecompute) {
  test::TempDir d;
  // A bigger study: the demo-like layout of 3 scenes, 8 rocks each, two models.
  std::mt19937 g(3);
  auto u = [&](double lo, double hi) { return lo + (hi - lo) * (g() / 4294967296.0); };
  for (int sc = 0; sc < 3; ++sc) {
    std::string real, synth, pr[2], ps[2];
    for (int k = 0; k < 8; ++k) {
      const double x = 0.1 + 0.1 * k, y = u(0.2, 0.8);
      real += fmt::format("0 {} {} 0.05 0.05\n", x, y);
      synth += fmt::format("0 {} {} 0.05 0.05\n", x + 0.005, y);
      for (int m = 0; m < 2; ++m) {
        pr[m] += fmt::format("0 {} {} 0.05 0.05 0.9\n", x + u(-0.02, 0.02), y);
        ps[m] += fmt::format("0 {} {} 0.05 0.05 0.9\n", x + u(-0.02, 0.02), y);
      }
    }
    const std::string stem = "s" + std::to_string(sc);
    test::write_text(d / ("real/labels/" + stem + ".txt"), real);
    test::write_text(d / ("synth/labels/" + stem + ".txt"), synth);
    for (int m = 0; m < 2; ++m) {
      test::write_text(d / ("real/predictions/m" + std::to_string(m) + "/" + stem + ".txt"), pr[m]);
      test::write_text(d / ("synth/predictions/m" + std::to_string(m) + "/" + stem + ".txt"), ps[m]);
    }
  }
  Session s = Session::open(d.path());
  for (int step = 0; step < 40; ++step) {
    const int scene = static_cast<int>(g() % 3);
    const int kind = static_cast<int>(g() % 4);
    Edit e{static_cast<Edit::Kind>(kind),
           static_cast<int>(g() % 8),
           static_cast<int>(g() % 8),
           g() % 2 ? Side::kA : Side::kB,
           {}};
    run_save_job(s.apply(scene, e));
    if (step % 7 == 3) run_save_job(*s.undo());
  }
  for (const std::string m : {"m0", "m1"}) {
    TableOptions o;
    o.models = {m};
    const double from_disk = compute_cross_table(load_labels(open_study(d.path())), o).cells[0].ipd;
    EXPECT_NEAR(s.cell_for(m, 0).ipd, from_disk, 1e-12) << m;
  }
}

// Runs `check` in a child process where `dir` is a read-only bind mount (a private mount namespace: root
// ignores permissions but not a read-only mount). Returns its exit code; -1 when no namespace can be made.
int in_read_only_mount(const std::string& dir, const std::function<int()>& check) {
  const pid_t pid = ::fork();
  if (pid == 0) {
    if (::unshare(CLONE_NEWNS) != 0 && ::unshare(CLONE_NEWUSER | CLONE_NEWNS) != 0) ::_exit(100);
    if (::mount(nullptr, "/", nullptr, MS_REC | MS_PRIVATE, nullptr) != 0 ||
        ::mount(dir.c_str(), dir.c_str(), nullptr, MS_BIND, nullptr) != 0 ||
        ::mount(nullptr, dir.c_str(), nullptr, MS_REMOUNT | MS_BIND | MS_RDONLY, nullptr) != 0)
      ::_exit(100);
    ::_exit(check());
  }
  int status = 0;
  ::waitpid(pid, &status, 0);
  return WIFEXITED(status) && WEXITSTATUS(status) != 100 ? WEXITSTATUS(status) : -1;
}

TEST(Session, ReadOnlyStudyIsDetectedAndSaveAsWritesElsewhere) {
  test::TempDir d, other;
  write_tiny_study_session(d);
  {
    Session s = Session::open(d.path());
    EXPECT_FALSE(s.read_only());
    s.apply(0, Edit::unpair(Side::kA, 1));
    const auto jobs = s.save_all_to(other.path());
    ASSERT_EQ(jobs.size(), 1u);
    EXPECT_EQ(jobs[0].path, other / "pairs/real__synth/s1.json");
  }
  const int code = in_read_only_mount(d.path(), [&] {
    const Session s = Session::open(d.path());
    return s.read_only() ? 0 : 1;
  });
  if (code >= 0) {
    EXPECT_EQ(code, 0) << "a study on a read-only mount was not detected as read-only";
    return;
  }
  // No mount namespace here (a restricted container): permissions, which bind everyone but root.
  ASSERT_NE(::geteuid(), 0u) << "root without a mount namespace: read-only can't be simulated";
  std::filesystem::permissions(d.path(), std::filesystem::perms::owner_write, std::filesystem::perm_options::remove);
  const bool read_only = Session::open(d.path()).read_only();
  std::filesystem::permissions(d.path(), std::filesystem::perms::owner_write, std::filesystem::perm_options::add);
  EXPECT_TRUE(read_only);
}

// Null and empty mean "none" and any scene count is a cut: nothing in the session options can be wrong.
TEST(Session, OptionsAreAlwaysUsable) {
  SessionOptions o;
  EXPECT_EQ(o.validate(), "");
  o.first_scenes = 3;
  o.cache_dir = "cache";
  EXPECT_EQ(o.validate(), "");
}

}  // namespace
}  // namespace ipd
