// Review marks (core/session/review_state.h): a scene marked reviewed, a suspect pair checked as correct,
// both undoable, saved in review/<A>__<B>.json by their rocks' boxes and read back against the pairs now.
#include <gtest/gtest.h>

#include <filesystem>

#include "core/report/provenance.h"
#include "core/session/scene_filter.h"
#include "core/session/session.h"
#include "core/util/atomic_file.h"
#include "tests/support/test_support.h"

namespace fs = std::filesystem;

namespace ipd {
namespace {

const std::string kCheckedFile =
    "{\"reviewed\":[\"s2\"],\"checked\":[{\"scene\":\"s1\",\"rock_a\":[0.3,0.8,0.12,0.1],\"rock_b\":[0.75,0.7,0.08,0."
    "12]}]}"
    "\n";

// Opened with every scene registered: a hand-paired scene is otherwise registered (and audited) only when the
// studio first shows it, and these tests count its suspect pairs.
Session open_audited(const std::string& root) {
  Session s = Session::open(root);
  for (int p = 0; p < static_cast<int>(s.domain_pairs().size()); ++p)
    for (int k = 0; k < static_cast<int>(s.scenes().size()); ++k) s.register_scene(p, k);
  return s;
}

std::vector<int> suspect_rows(const Session& s, int scene) {
  std::vector<int> out;
  for (const PairAudit& p : s.audit(scene).pairs)
    if (p.suspect) out.push_back(p.a);
  return out;
}

TEST(SessionReview, CheckingASuspectPairStopsItCountingAndUndoRedoTogglesIt) {
  test::TempDir d;
  test::write_review_study(d);
  Session s = open_audited(d.path());
  ASSERT_EQ(s.scenes().size(), 2u);
  EXPECT_EQ(s.summary(0).suspects, 2);
  EXPECT_EQ(suspect_rows(s, 0), (std::vector<int>{2, 3}));
  EXPECT_FALSE(s.toggle_checked(0, 2, 2).has_value());  // not a pair: nothing to check
  EXPECT_FALSE(s.can_undo());
  const std::optional<SaveJob> job = s.toggle_checked(0, 2, 3);
  ASSERT_TRUE(job.has_value());
  EXPECT_TRUE(s.checked(0, 2, 3));
  EXPECT_EQ(s.summary(0).suspects, 1);
  EXPECT_EQ(suspect_rows(s, 0), (std::vector<int>{3}));  // what `N` visits and the pictures colour
  EXPECT_EQ(s.suspect_rocks(Side::kA, 0), (std::vector<char>{0, 0, 0, 1}));
  EXPECT_TRUE(s.audit(0).pairs[2].checked);
  EXPECT_EQ(s.audit(0).pairs[2].why, "no overlap");  // still says what looked wrong
  EXPECT_EQ(job->path, d / "review/real__synth.json");
  EXPECT_EQ(*job->contents,
            "{\"reviewed\":[],\"checked\":[{\"scene\":\"s1\",\"rock_a\":[0.3,0.8,0.12,0.1],\"rock_b\":[0.75,0.7,0.08,"
            "0.12]}]}\n");
  EXPECT_EQ(s.review_progress().suspects_left, 1);
  // Undo takes the check back and the job removes the file (nothing left to keep); redo checks it again.
  const std::optional<SaveJob> undone = s.undo();
  ASSERT_TRUE(undone.has_value());
  EXPECT_FALSE(undone->contents.has_value());
  EXPECT_FALSE(s.checked(0, 2, 3));
  EXPECT_EQ(s.summary(0).suspects, 2);
  EXPECT_EQ(s.redo()->contents, job->contents);
  EXPECT_EQ(s.summary(0).suspects, 1);
  // Swapped view (synth on the left): the same pair is (3, 2) in view indices.
  ASSERT_TRUE(s.select_domains("synth", "real"));
  EXPECT_TRUE(s.checked(0, 3, 2));
  EXPECT_FALSE(s.checked(0, 2, 3));
  EXPECT_FALSE(s.toggle_checked(0, 3, 2)->contents.has_value());  // unchecked: nothing left to keep
  EXPECT_EQ(s.summary(0).suspects, 2);
}

// Unpairing a checked pair leaves its check in memory (undo brings the pair and the check back) and in the
// file: it is the user's record, and applies again if the pair comes back.
TEST(SessionReview, ACheckOfAPairEditedAwayIsKeptAndComesBackWithUndo) {
  test::TempDir d;
  test::write_review_study(d);
  Session s = open_audited(d.path());
  s.toggle_checked(0, 2, 3);
  s.apply(0, Edit::unpair(Side::kA, 2));
  EXPECT_EQ(s.summary(0).suspects, 1);  // [3, 2] is left, and not checked
  EXPECT_EQ(*s.toggle_reviewed(1).contents,
            "{\"reviewed\":[\"s2\"],\"checked\":[{\"scene\":\"s1\",\"rock_a\":[0.3,"
            "0.8,0.12,0.1],\"rock_b\":[0.75,0.7,0.08,0.12]}]}\n");
  s.undo();
  s.undo();  // the pair [2, 3] is back, checked
  EXPECT_EQ(s.summary(0).suspects, 1);
  EXPECT_TRUE(s.audit(0).pairs[2].checked);
}

// A scene whose name is not UTF-8 can't be written into the review file (JSON): marking it fails and changes
// nothing, and the other scenes' marks are still saved (a failed mark kept in memory would make every later
// save of the domain pair fail).
TEST(SessionReview, AMarkTheFileCannotHoldChangesNothing) {
  test::TempDir d;
  test::write_review_study(d);
  const std::string bad =
      "s\xff"
      "3";  // not UTF-8: 0xff alone
  for (const char* domain : {"real", "synth"})
    fs::copy_file(d / (std::string(domain) + "/labels/s2.txt"), d / (std::string(domain) + "/labels/" + bad + ".txt"));
  Session s = open_audited(d.path());
  int bad_scene = -1;
  for (int k = 0; k < static_cast<int>(s.scenes().size()); ++k)
    if (s.scenes()[k].stem == bad) bad_scene = k;
  ASSERT_GE(bad_scene, 0);
  EXPECT_THROW(s.toggle_reviewed(bad_scene), std::exception);
  EXPECT_FALSE(s.reviewed(bad_scene));
  EXPECT_EQ(s.review_progress().reviewed, 0);
  EXPECT_FALSE(s.can_undo());
  EXPECT_EQ(*s.toggle_reviewed(1).contents, "{\"reviewed\":[\"s2\"],\"checked\":[]}\n");
}

TEST(SessionReview, ReviewedScenesToggleCountAndFilter) {
  test::TempDir d;
  test::write_review_study(d);
  Session s = open_audited(d.path());
  EXPECT_EQ(s.review_progress().reviewed, 0);
  EXPECT_EQ(*s.toggle_reviewed(1).contents, "{\"reviewed\":[\"s2\"],\"checked\":[]}\n");
  EXPECT_TRUE(s.reviewed(1));
  EXPECT_TRUE(s.summary(1).reviewed);
  EXPECT_FALSE(s.summary(0).reviewed);
  const Session::ReviewProgress p = s.review_progress();
  EXPECT_EQ(p.scenes, 2);
  EXPECT_EQ(p.reviewed, 1);
  EXPECT_EQ(p.suspects_left, 2);
  const SceneFilter reviewed = SceneFilter::parse("reviewed"), unreviewed = SceneFilter::parse("unreviewed");
  EXPECT_TRUE(reviewed.error.empty());
  EXPECT_FALSE(reviewed.matches(s.summary(0)));
  EXPECT_TRUE(reviewed.matches(s.summary(1)));
  EXPECT_TRUE(unreviewed.matches(s.summary(0)));
  EXPECT_FALSE(unreviewed.matches(s.summary(1)));
  EXPECT_TRUE(SceneFilter::parse("s1 unreviewed suspect").matches(s.summary(0)));
  // Toggling again un-marks it; undo brings the mark back.
  EXPECT_FALSE(s.toggle_reviewed(1).contents.has_value());
  EXPECT_FALSE(s.reviewed(1));
  s.undo();
  EXPECT_TRUE(s.reviewed(1));
  EXPECT_EQ(s.review_progress().reviewed, 1);
}

TEST(SessionReview, TheFileRoundTripsByBoxesWhenLabelRowsAreReordered) {
  test::TempDir d;
  test::write_review_study(d);
  {
    Session s = open_audited(d.path());
    run_save_job(s.toggle_reviewed(1));
    run_save_job(*s.toggle_checked(0, 2, 3));
    EXPECT_EQ(read_file(d / "review/real__synth.json"), kCheckedFile);
  }
  Session again = open_audited(d.path());
  EXPECT_TRUE(again.problems().empty());
  EXPECT_TRUE(again.reviewed(1));
  EXPECT_TRUE(again.checked(0, 2, 3));
  EXPECT_EQ(again.summary(0).suspects, 1);
  // The real label file re-exported with rows 0 and 2 swapped: the pairs file finds its rocks again by box, and
  // so does the check ([2, 3] is now [0, 3]).
  test::write_text(d / "real/labels/s1.txt",
                   "0 0.3 0.8 0.12 0.1\n0 0.8 0.25 0.06 0.06\n0 0.2 0.2 0.1 0.08\n0 0.75 0.7 0.08 0.12\n");
  Session moved = open_audited(d.path());
  EXPECT_TRUE(moved.checked(0, 0, 3));
  EXPECT_FALSE(moved.checked(0, 2, 3));
  EXPECT_EQ(moved.summary(0).suspects, 1);
}

// A check whose rocks are not a pair now (another registration method, a label file being fixed) does not
// apply and says so, but it is the user's record: the next save of another mark writes it back, and it
// applies again when the pair is back, on opening or after an edit.
TEST(SessionReview, ACheckWhosePairIsGoneIsKeptAndAppliesAgainWhenThePairComesBack) {
  test::TempDir d;
  test::write_review_study(d);
  test::write_text(d / "review/real__synth.json", kCheckedFile);
  const std::string hand = read_file(d / "pairs/real__synth/s1.json");
  // The hand pairs are gone: registration pairs 2 with 2, so the checked pair [2, 3] is not a pair now.
  fs::remove(d / "pairs/real__synth/s1.json");
  {
    Session s = open_audited(d.path());
    EXPECT_FALSE(s.checked(0, 2, 3));
    EXPECT_TRUE(s.reviewed(1));
    ASSERT_EQ(s.problems().size(), 1u);
    EXPECT_EQ(s.problems()[0].to_string(),
              d / "review/real__synth.json" +
                  ": the check of the pair real rock 3 | synth rock 4 in scene \"s1\" does not apply now: those rocks "
                  "are not a pair now (kept in the file: it applies again when they are)");
    EXPECT_EQ(s.problems()[0].scene, "s1");
    EXPECT_EQ(s.review_of(0).kept_checks.size(), 1u);
    // Another scene's mark is saved: the check is written back as read.
    run_save_job(s.toggle_reviewed(0));
    EXPECT_EQ(read_file(d / "review/real__synth.json"),
              "{\"reviewed\":[\"s1\",\"s2\"],\"checked\":[{\"scene\":\"s1\",\"rock_a\":[0.3,0.8,0.12,0.1],"
              "\"rock_b\":[0.75,0.7,0.08,0.12]}]}\n");
    // Pairing the two rocks by hand brings the check back at once.
    s.apply(0, Edit::pair(2, 3));
    EXPECT_TRUE(s.checked(0, 2, 3));
    EXPECT_TRUE(s.review_of(0).kept_checks.empty());
  }
  test::write_text(d / "pairs/real__synth/s1.json", hand);
  const Session back = open_audited(d.path());
  EXPECT_TRUE(back.checked(0, 2, 3));
  EXPECT_TRUE(back.problems().empty());
}

// A check whose box left its label file (a typo being fixed, a rock deleted) says which box is gone rather
// than "not a pair now", and is kept the same way.
TEST(SessionReview, ACheckWhoseBoxLeftItsLabelFileSaysWhichBox) {
  test::TempDir d;
  test::write_review_study(d);
  test::write_text(d / "review/real__synth.json", kCheckedFile);
  test::write_text(d / "synth/labels/s1.txt",
                   "0 0.2 0.2 0.1 0.08\n0 0.8 0.25 0.06 0.06\n0 0.3 0.8 0.12 0.1\n0 0.75 0.7 0.08 0.13\n");
  fs::remove(d / "pairs/real__synth/s1.json");
  const Session s = open_audited(d.path());
  ASSERT_EQ(s.problems().size(), 1u);
  EXPECT_EQ(s.problems()[0].message,
            "the check of the pair (0.3 0.8 0.12 0.1) | (0.75 0.7 0.08 0.12) in scene \"s1\" does not apply now: "
            "synth's box (0.75 0.7 0.08 0.12) is no longer in its label file (moved or deleted; kept in the file: it "
            "applies again if the box comes back)");
  EXPECT_EQ(s.review_of(0).kept_checks.size(), 1u);
}

// The studio's figures count a check only while its rocks are a pair: unpairing them takes it out of the count
// (the check stays in the file).
TEST(SessionReview, ProvenanceCountsAChecksOnlyWhileItsRocksAreAPair) {
  test::TempDir d;
  test::write_review_study(d);
  test::write_text(d / "review/real__synth.json", kCheckedFile);
  Session s = open_audited(d.path());
  ASSERT_TRUE(s.checked(0, 2, 3));
  EXPECT_EQ(session_provenance(s).pairs_checked, 1);
  s.apply(0, Edit::unpair(Side::kA, 2));
  EXPECT_EQ(session_provenance(s).pairs_checked, 0);
  s.undo();
  EXPECT_EQ(session_provenance(s).pairs_checked, 1);
}

// Marks of a scene the domain pair does not have now (its label file moved away for a while) are kept too.
TEST(SessionReview, MarksOfAMissingSceneAreKeptInTheFile) {
  test::TempDir d;
  test::write_review_study(d);
  test::write_text(d / "review/real__synth.json",
                   "{\"reviewed\":[\"s3\"],\"checked\":[{\"scene\":\"s3\",\"rock_a\":[0.3,0.8,0.12,0.1],"
                   "\"rock_b\":[0.75,0.7,0.08,0.12]}]}\n");
  Session s = open_audited(d.path());
  ASSERT_EQ(s.problems().size(), 2u);
  EXPECT_EQ(s.problems()[0].message,
            "the review mark of scene \"s3\" does not apply now: real - synth has no such scene (kept in the file)");
  EXPECT_EQ(s.problems()[1].message,
            "the check of a pair in scene \"s3\" does not apply now: real - synth has no such scene (kept in the "
            "file)");
  EXPECT_EQ(s.review_progress().reviewed, 0);
  EXPECT_EQ(*s.toggle_reviewed(1).contents,
            "{\"reviewed\":[\"s2\",\"s3\"],\"checked\":[{\"scene\":\"s3\",\"rock_a\":[0.3,0.8,0.12,0.1],"
            "\"rock_b\":[0.75,0.7,0.08,0.12]}]}\n");
  // Un-marking the one scene that applies leaves the kept marks: the file stays.
  EXPECT_TRUE(s.toggle_reviewed(1).contents.has_value());
}

TEST(SessionReview, ANewerReviewFileOnDiskIsNotOverwritten) {
  test::TempDir d;
  test::write_review_study(d);
  Session first = open_audited(d.path()), second = open_audited(d.path());
  run_save_job(first.toggle_reviewed(0));
  const SaveJob theirs = second.toggle_reviewed(1);
  EXPECT_THROW(run_save_job(theirs), SaveConflict);
  EXPECT_EQ(read_file(d / "review/real__synth.json"), "{\"reviewed\":[\"s1\"],\"checked\":[]}\n");
  // Keeping the disk's version reads the file again.
  second.reload_scene(0, "");
  EXPECT_TRUE(second.reviewed(0));
  EXPECT_FALSE(second.reviewed(1));
}

TEST(SessionReview, BadReviewFilesNameTheFileAndWhatWasExpected) {
  test::TempDir d;
  test::write_review_study(d);
  const std::string f = d / "review/real__synth.json";
  auto error_of = [&](const std::string& text) {
    test::write_text(f, text);
    try {
      open_audited(d.path());
    } catch (const StudyError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_EQ(error_of("{\"reviewed\": [\"s1\"], \"reviewed\": []}"),
            f + ": duplicate key \"reviewed\" in one object (a JSON reader keeps only one of them); expected "
                "{\"reviewed\": [scene, ...], \"checked\": [{\"scene\": s, \"rock_a\": [cx, cy, w, h], \"rock_b\": "
                "[...]}]}");
  EXPECT_EQ(error_of("{\"reviewed\": 3}"), f + ": \"reviewed\" must be an array of scene names");
  EXPECT_EQ(error_of("{\"seen\": []}"), f + ": unknown key \"seen\" (expected reviewed, checked)");
  EXPECT_EQ(error_of("{\"checked\": [{\"scene\": \"s1\", \"rock_a\": [0.2, 0.8], \"rock_b\": [0, 0, 0, 0]}]}"),
            f + ": \"rock_a\" holds [0.2,0.8], expected a box [cx, cy, w, h]");
  EXPECT_EQ(error_of("{\"reviewed\": [1]}"), f + ": \"reviewed\" holds 1, expected a scene name");
}

TEST(SessionReview, ReadOnlyMarksAreWrittenBySaveAllTo) {
  test::TempDir d, other;
  test::write_review_study(d);
  Session s = open_audited(d.path());
  s.set_read_only("test");
  s.toggle_reviewed(1);
  s.toggle_checked(0, 2, 3);
  const std::vector<SaveJob> jobs = s.save_all_to(other.path());
  ASSERT_EQ(jobs.size(), 2u);  // s1's hand pairs and the review file
  EXPECT_EQ(jobs[1].path, other / "review/real__synth.json");
  EXPECT_EQ(jobs[1].contents, kCheckedFile);
  EXPECT_TRUE(jobs[1].expected.empty());
}

}  // namespace
}  // namespace ipd
