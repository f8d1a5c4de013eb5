// Every number is about one class: a rock is scored by rock predictions and paired with rocks, a study whose
// labels hold two classes never yields a class-mixed number unasked, and class numbers from two tools are read by
// name (or refused) rather than mixed in silence.
#include <gtest/gtest.h>

#include <fmt/format.h>

#include "core/ipd/ipd.h"
#include "core/registration/pairing.h"
#include "core/report/provenance.h"
#include "core/session/session.h"
#include "core/study/study.h"
#include "core/util/errors.h"
#include "tests/support/pdf_text.h"
#include "tests/support/test_support.h"

namespace ipd {
namespace {

Box of_class(int cls, double cx, double cy, double w, double h, double conf = 1.0) {
  return Box{cls, cx, cy, w, h, conf};
}

// A rock (class 0) overlapped by a shadow prediction (class 1) with IoU 0.9 and a rock prediction with IoU 0.5:
// its performance value is 0.5 (pycocotools matches within a category), and the best prediction is the rock one.
TEST(Classes, ARockIsScoredOnlyByPredictionsOfItsClass) {
  const Box rock = of_class(0, 0.5, 0.5, 0.2, 0.2);
  // 0.9: the same centre and height, width 0.2 * 0.9 inside the rock.
  const Box shadow_pred = of_class(1, 0.5, 0.5, 0.18, 0.2, 0.9);
  // 0.5: shifted right by a third of the width: overlap 2/3 of the area, IoU (2/3) / (4/3) = 0.5.
  const Box rock_pred = of_class(0, 0.5 + 0.2 / 3, 0.5, 0.2, 0.2, 0.6);
  ASSERT_NEAR(iou(rock, shadow_pred), 0.9, 1e-12);
  ASSERT_NEAR(iou(rock, rock_pred), 0.5, 1e-12);
  const PerformanceValues pv = performance_values({rock}, {shadow_pred, rock_pred});
  EXPECT_NEAR(pv.value[0], 0.5, 1e-12);
  EXPECT_EQ(pv.best_prediction[0], 1);
  // With no prediction of its class the rock is missed, however well a shadow prediction covers it.
  EXPECT_EQ(performance_values({rock}, {shadow_pred}).value[0], 0.0);
  EXPECT_EQ(performance_values({rock}, {shadow_pred}).best_prediction[0], -1);
}

TEST(Classes, BoxesOfTwoClassesAreNeverAPair) {
  const PairingRule rule;
  EXPECT_NEAR(pair_weight(of_class(0, 0.5, 0.5, 0.1, 0.1), of_class(0, 0.5, 0.5, 0.1, 0.1), rule), 1.0, 1e-12);
  EXPECT_EQ(pair_weight(of_class(0, 0.5, 0.5, 0.1, 0.1), of_class(1, 0.5, 0.5, 0.1, 0.1), rule), 0.0);
}

// The paper's mutual nearest centres know no class: a shadow at a rock's place is still no pair.
TEST(Classes, ThePaperMethodPairsNoTwoClasses) {
  const std::vector<Box> a = {of_class(0, 0.2, 0.2, 0.05, 0.05), of_class(0, 0.5, 0.7, 0.05, 0.05),
                              of_class(0, 0.8, 0.3, 0.05, 0.05), of_class(1, 0.4, 0.4, 0.05, 0.05)};
  std::vector<Box> b = a;
  b[3] = of_class(0, 0.401, 0.4, 0.05, 0.05);  // a rock where A has a shadow (not the same layout)
  RegistrationOptions o;
  o.method = RegistrationMethod::kPaper;
  const RegistrationReport r = register_rocks(a, b, o);
  EXPECT_EQ(r.pairs, (RockPairs{{0, 0}, {1, 1}, {2, 2}}));
}

// Real and synth have the same layout: rocks R1 (0.2, 0.2) and R2 (0.6, 0.6), shadow S1 (0.25, 0.2) beside R1.
// det in real: a shadow box exactly on R1 (IoU 1 with R1, 1/3 with S1) and a rock box 0.025 below R1 (IoU 0.6);
// R2 missed. det in synth finds all three exactly. Rock IPD (|0.6 - 1| + |0 - 1|) / 2 = 0.7; shadow IPD
// |1/3 - 1| = 2/3; class-blind (pairs within a class) (0.4 + 1 + 2/3) / 3.
void write_two_class_study(const test::TempDir& d, const std::string& yaml = "") {
  const std::string gt = "0 0.2 0.2 0.1 0.1\n1 0.25 0.2 0.1 0.1\n0 0.6 0.6 0.1 0.1\n";
  test::write_text(d / "real/labels/s1.txt", gt);
  test::write_text(d / "real/labels/classes.txt", "rock\nshadow\n");
  test::write_text(d / "synth/labels/s1.txt", gt);
  test::write_text(d / "real/predictions/det/s1.txt", "1 0.2 0.2 0.1 0.1 0.9\n0 0.2 0.225 0.1 0.1 0.8\n");
  test::write_text(d / "synth/predictions/det/s1.txt",
                   "0 0.2 0.2 0.1 0.1 0.9\n0 0.6 0.6 0.1 0.1 0.9\n1 0.25 0.2 0.1 0.1 0.9\n");
  test::write_text(d / "study.yaml", "domains: [real, synth]\nmodels: {det: {trained_on: real}}\n" + yaml);
}

double ipd_for(const test::TempDir& d, const std::string& word) {
  Study study = open_study(d.path());
  if (!word.empty()) study.config.rock_class = study.classes.resolve(word);
  const StudyLabels labels = load_labels(study);
  require_class_choice(labels);
  return compute_cross_table(labels, {}).cell("det", "real", "synth")->ipd;
}

TEST(Classes, EachClassHasItsOwnIpdWorkedByHand) {
  test::TempDir d;
  write_two_class_study(d);
  EXPECT_NEAR(ipd_for(d, "rock"), 0.7, 1e-12);
  EXPECT_NEAR(ipd_for(d, "0"), 0.7, 1e-12);
  EXPECT_NEAR(ipd_for(d, "shadow"), 2.0 / 3, 1e-12);
  EXPECT_NEAR(ipd_for(d, "all"), (0.4 + 1 + 2.0 / 3) / 3, 1e-12);
}

TEST(Classes, RockClassInStudyYamlTakesANameOrANumber) {
  test::TempDir d;
  write_two_class_study(d, "rock_class: 0\n");
  EXPECT_NEAR(ipd_for(d, ""), 0.7, 1e-12);
  test::TempDir n;
  write_two_class_study(n, "rock_class: shadow\n");
  EXPECT_NEAR(ipd_for(n, ""), 2.0 / 3, 1e-12);
}

TEST(Classes, TwoClassesWithoutAChoiceAreRefusedListingTheirBoxes) {
  test::TempDir d;
  write_two_class_study(d);
  const StudyLabels labels = load_labels(open_study(d.path()));
  EXPECT_EQ(labels.class_choice_needed,
            d.path() +
                ": the labels hold 2 classes (rock (class 0): 4 boxes, shadow (class 1): 2 boxes), and an IPD that "
                "mixed them would score and pair one class against another; choose one with --class rock (or "
                "rock_class: rock in study.yaml), or --class all for a class-blind number");
  EXPECT_THROW(require_class_choice(labels), StudyError);
}

// One class in the ground truth is the class: no choice needed, and a detector's other classes can't score it.
TEST(Classes, OneGroundTruthClassNeedsNoChoice) {
  test::TempDir d;
  test::write_text(d / "real/labels/s1.txt", "0 0.2 0.2 0.1 0.1\n");
  test::write_text(d / "synth/labels/s1.txt", "0 0.2 0.2 0.1 0.1\n");
  test::write_text(d / "real/predictions/det/s1.txt", "1 0.2 0.2 0.1 0.1 0.9\n0 0.2 0.225 0.1 0.1 0.8\n");
  test::write_text(d / "synth/predictions/det/s1.txt", "0 0.2 0.2 0.1 0.1 0.9\n");
  const StudyLabels labels = load_labels(open_study(d.path()));
  EXPECT_EQ(labels.class_choice_needed, "");
  EXPECT_EQ(labels.study.config.rock_class, 0);
  EXPECT_EQ(labels.predictions_of("real", "det", "s1").boxes.size(), 1u);
  EXPECT_NEAR(compute_cross_table(labels, {}).cell("det", "real", "synth")->ipd, 0.4, 1e-12);
}

// synth's classes.txt numbers the two classes the other way round: its labels are read by name, so the numbers are
// those of the study where every file uses one numbering.
TEST(Classes, ClassNumbersOfAnotherToolAreReadByName) {
  test::TempDir d;
  write_two_class_study(d);
  test::write_text(d / "synth/labels/classes.txt", "shadow\nrock\n");
  test::write_text(d / "synth/labels/s1.txt", "1 0.2 0.2 0.1 0.1\n0 0.25 0.2 0.1 0.1\n1 0.6 0.6 0.1 0.1\n");
  const Study study = open_study(d.path());
  ASSERT_EQ(study.classes.notes.size(), 1u);
  EXPECT_EQ(study.classes.notes[0],
            "synth/labels/classes.txt numbers its classes differently from real/labels/classes.txt (shadow 0 -> 1, "
            "rock 1 -> 0): read by name");
  EXPECT_NEAR(ipd_for(d, "rock"), 0.7, 1e-12);
  EXPECT_NEAR(ipd_for(d, "shadow"), 2.0 / 3, 1e-12);
}

TEST(Classes, APredictionSetNamingAClassTheStudyLacksIsRefusedNamingBothFiles) {
  test::TempDir d;
  write_two_class_study(d);
  test::write_text(d / "real/predictions/det/classes.txt", "rock\nboulder\n");
  EXPECT_EQ(test::open_study_error(d.path()),
            d / "real/predictions/det/classes.txt" + ":2: class 'boulder' is not among the study's classes (" +
                d / "real/labels/classes.txt" +
                ": 0 rock, 1 shadow); a class must have one name in every label set (rename it, or add it to "
                "real/labels/classes.txt)");
}

TEST(Classes, AClassNamedTwiceInOneFileIsRefusedWithItsLine) {
  test::TempDir d;
  write_two_class_study(d);
  test::write_text(d / "real/labels/classes.txt", "rock\nshadow\nrock\n");
  EXPECT_EQ(test::open_study_error(d.path()),
            d / "real/labels/classes.txt" +
                ":3: class 'rock' is named again (also line 1); each class once, on the line of its number");
}

// CVAT's COCO export numbers rock 1; YOLO predictions without a classes.txt number it 0. The prediction lines of
// class 0 are refused (that number has no name), never scored as the study's class 0.
TEST(Classes, AnUnnamedClassNumberBesideNamedOnesIsALabelError) {
  test::TempDir d;
  test::write_text(d / "real/labels/classes.txt", "\nrock\nshadow\n");
  test::write_text(d / "real/labels/s1.txt", "1 0.2 0.2 0.1 0.1\n");
  test::write_text(d / "synth/labels/s1.txt", "1 0.2 0.2 0.1 0.1\n");
  test::write_text(d / "real/predictions/det/s1.txt", "0 0.2 0.2 0.1 0.1 0.9\n");
  test::write_text(d / "synth/predictions/det/s1.txt", "1 0.2 0.2 0.1 0.1 0.9\n");
  const StudyLabels labels = load_labels(open_study(d.path()));
  ASSERT_EQ(labels.errors.size(), 1u);
  EXPECT_EQ(labels.errors[0].to_string(),
            d / "real/predictions/det/s1.txt" +
                ":1: class 0 is a number the study's classes leave unnamed (real/labels/classes.txt: 1 rock, 2 "
                "shadow); give this label set a classes.txt, or name the class there");
}

// --class-map 0:1 says the predictions' 0 is the study's 1 (rock): then they score the rocks.
TEST(Classes, AClassMapRenumbersPredictionsWithoutAClassesFile) {
  test::TempDir d;
  test::write_text(d / "real/labels/classes.txt", "\nrock\n");
  test::write_text(d / "real/labels/s1.txt", "1 0.2 0.2 0.1 0.1\n");
  test::write_text(d / "synth/labels/s1.txt", "1 0.2 0.2 0.1 0.1\n");
  test::write_text(d / "real/predictions/det/s1.txt", "0 0.2 0.225 0.1 0.1 0.9\n");
  test::write_text(d / "synth/predictions/det/s1.txt", "0 0.2 0.2 0.1 0.1 0.9\n");
  Study study = open_study(d.path());
  apply_prediction_class_map({{0, 1}}, study.domains, &study.classes);
  const StudyLabels labels = load_labels(study);
  EXPECT_TRUE(labels.errors.empty());
  EXPECT_NEAR(compute_cross_table(labels, {}).cell("det", "real", "synth")->ipd, 0.4, 1e-12);
}

// 25 rocks and 25 shadows; the detector numbers them the other way round and has no classes.txt: its "1" boxes
// detect rocks. The study refuses for want of a class, and says which map would undo the shift.
TEST(Classes, ShiftedPredictionNumbersAreNamedWithTheMapThatUndoesThem) {
  test::TempDir d;
  std::string gt, pred;
  for (int k = 0; k < 25; ++k) {
    const double x = 0.05 + 0.035 * k;
    gt += fmt::format("0 {} 0.3 0.02 0.02\n1 {} 0.7 0.02 0.02\n", x, x);
    pred += fmt::format("1 {} 0.3 0.02 0.02 0.9\n0 {} 0.7 0.02 0.02 0.9\n", x, x);
  }
  test::write_text(d / "real/labels/classes.txt", "rock\nshadow\n");
  test::write_text(d / "real/labels/s1.txt", gt);
  test::write_text(d / "synth/labels/s1.txt", gt);
  test::write_text(d / "real/predictions/det/s1.txt", pred);
  test::write_text(d / "synth/predictions/det/s1.txt", pred);
  const StudyLabels labels = load_labels(open_study(d.path()));
  ASSERT_EQ(labels.class_warnings.size(), 2u);
  EXPECT_EQ(labels.class_warnings[0],
            "real/predictions/det: the class numbers look shifted against the ground truth's (25 of its rock boxes "
            "detect shadow and 0 rock; 25 of its shadow boxes detect rock and 0 shadow at IoU >= 0.5); if this model "
            "numbers its classes differently, give it a classes.txt or --class-map 0:1,1:0");
  EXPECT_NE(labels.class_choice_needed.find(labels.class_warnings[0]), std::string::npos);
}

TEST(Classes, ProvenanceNamesTheClass) {
  test::TempDir d;
  write_two_class_study(d, "rock_class: shadow\n");
  const StudyLabels labels = load_labels(open_study(d.path()));
  const CrossTable t = compute_cross_table(labels, {});
  const Provenance p = table_provenance(t, labels);
  EXPECT_EQ(p.class_name, "shadow (class 1)");
  EXPECT_EQ(provenance_note(p).rfind("Class shadow (class 1). Label files ", 0), 0u) << provenance_note(p);
  EXPECT_EQ(provenance_json(p)["class"], "shadow (class 1)");
  Study all = open_study(d.path());
  all.config.rock_class = kAllClasses;
  const StudyLabels blind = load_labels(all);
  EXPECT_EQ(provenance_class(blind), "all, class-blind (--class all)");
}

// A figure of one class of several says which, in the figure itself: a shadow table must not pass for a rock one.
TEST(Classes, AFigureOfAChosenClassNamesItInTheFigure) {
  test::TempDir d;
  write_two_class_study(d);
  for (const char* kind : {"table", "pairs"}) {
    auto r = test::run_ipd(std::string("figure ") + kind + " " + d.path() + " --class shadow --out " + d / "f.pdf");
    ASSERT_EQ(r.exit_code, 0) << kind << ": " << r.err;
    const std::string words = test::pdf_words(d / "f.pdf");
    EXPECT_NE(words.find("Class shadow (class 1)."), std::string::npos) << kind << ": " << words;
    EXPECT_EQ(words.find("Label files"), std::string::npos) << kind << ": " << words;  // nothing set by hand
  }
}

TEST(Classes, AnUnknownClassWordListsTheClasses) {
  test::TempDir d;
  write_two_class_study(d);
  const Study study = open_study(d.path());
  try {
    study.classes.resolve("boulder");
    FAIL() << "accepted";
  } catch (const StudyError& e) {
    EXPECT_STREQ(e.what(),
                 "no class named 'boulder'; the study's classes are rock (0), shadow (1), by name or number; or 'all' "
                 "for a class-blind number");
  }
  // A number the study's names leave unnamed has no boxes: refused, not an empty table.
  try {
    study.classes.resolve("2");
    FAIL() << "accepted";
  } catch (const StudyError& e) {
    EXPECT_STREQ(e.what(),
                 "no class 2 among the study's classes rock (0), shadow (1) (real/labels/classes.txt); or 'all' for a "
                 "class-blind number");
  }
}

}  // namespace
}  // namespace ipd

namespace ipd {
namespace {

// Hand pairs are of the class they were made under: a rock scene's pairs file says "class": 0, counts for rocks,
// is no pairs (and no problem) for shadows, and an edit made while showing shadows is refused rather than
// overwrite the rocks' hand work.
TEST(Classes, HandPairsOfOneClassAreNotAnotherClasssPairs) {
  test::TempDir d;
  write_two_class_study(d);
  SessionOptions rocks;
  rocks.class_word = "rock";
  {
    Session s = Session::open(d.path(), rocks);
    const SaveJob job = s.apply(0, Edit::unpair(Side::kA, 0));  // R1 out: the rock IPD is R2's |0 - 1| = 1
    ASSERT_TRUE(job.contents.has_value());
    EXPECT_EQ(job.contents->rfind("{\"class\":0,\"pairs\":[[1,1]]", 0), 0u) << *job.contents;
    run_save_job(job);
  }
  EXPECT_NEAR(ipd_for(d, "rock"), 1.0, 1e-12);
  Study study = open_study(d.path());
  study.config.rock_class = study.classes.resolve("shadow");
  const StudyLabels labels = load_labels(study);
  const CrossTable shadows = compute_cross_table(labels, {});
  EXPECT_NEAR(shadows.cell("det", "real", "synth")->ipd, 2.0 / 3, 1e-12);
  EXPECT_EQ(shadows.fixed_scenes, 0);
  EXPECT_TRUE(shadows.pairs_problems.empty());
  SessionOptions shadow;
  shadow.class_word = "shadow";
  Session s = Session::open(d.path(), shadow);
  try {
    s.apply(0, Edit::reset());
    FAIL() << "an edit under shadows overwrote the rocks' hand pairs";
  } catch (const StudyError& e) {
    EXPECT_EQ(std::string(e.what()),
              d / "pairs/real__synth/s1.json" +
                  ": edit refused: this scene's hand pairs are of rock, and saving an edit made while showing "
                  "shadow (class 1) would overwrite them; choose rock in the class menu to edit them");
  }
}

}  // namespace
}  // namespace ipd

namespace ipd {
namespace {

// A pair joins two rocks of one class, also in a class-blind view where both are shown: an edit pairing real's
// rock R1 with synth's shadow S1 is refused, and so is a pairs file that holds such a pair.
TEST(Classes, AHandPairJoiningTwoClassesIsRefused) {
  test::TempDir d;
  write_two_class_study(d);
  SessionOptions all;
  all.class_word = "all";
  {
    Session s = Session::open(d.path(), all);
    try {
      s.apply(0, Edit::pair(0, 1));  // rows of real/labels/s1.txt: R1 S1 R2
      FAIL() << "a rock was paired with a shadow";
    } catch (const StudyError& e) {
      EXPECT_STREQ(e.what(),
                   "edit refused: pairs real rock 1 (rock) with synth rock 2 (shadow): a pair joins two rocks of one "
                   "class");
    }
    const SaveJob job = s.apply(0, Edit::pair(2, 0));  // R2 with R1: within a class, saved as class-blind work
    ASSERT_TRUE(job.contents.has_value());
    EXPECT_EQ(job.contents->rfind("{\"class\":\"all\",\"pairs\":[[1,1],[2,0]],", 0), 0u) << *job.contents;
  }
  test::write_text(d / "pairs/real__synth/s1.json", "{\"class\": \"all\", \"pairs\": [[0, 1]]}\n");
  try {
    ipd_for(d, "all");
    FAIL() << "a pairs file joining two classes was used";
  } catch (const StudyError& e) {
    EXPECT_EQ(std::string(e.what()), d / "pairs/real__synth/s1.json" +
                                         ": pairs real rock 1 (rock) with synth rock 2 (shadow): a pair joins two "
                                         "rocks of one class");
  }
}

// Review marks are of the class they were made under, as hand pairs are: the rocks' reviewed scene and checked
// pair are no marks (and no problem) while shadows are shown, a shadow review is added beside them, and both
// classes' marks are in the file and apply again under their own class.
TEST(Classes, ReviewMarksAreOfTheClassTheyWereMadeUnder) {
  test::TempDir d;
  write_two_class_study(d);
  SessionOptions rocks;
  rocks.class_word = "rock";
  SessionOptions shadow;
  shadow.class_word = "shadow";
  {
    Session s = Session::open(d.path(), rocks);
    run_save_job(s.toggle_reviewed(0));
    const auto job = s.toggle_checked(0, 1, 1);  // R2 | R2 (rows of the rock class)
    ASSERT_TRUE(job && job->contents);
    EXPECT_EQ(*job->contents,
              "{\"reviewed\":[{\"scene\":\"s1\",\"class\":0}],\"checked\":[{\"scene\":\"s1\",\"rock_a\":[0.6,0.6,0.1,"
              "0.1],\"rock_b\":[0.6,0.6,0.1,0.1],\"class\":0}]}\n");
    run_save_job(*job);
  }
  {
    Session s = Session::open(d.path(), shadow);
    EXPECT_EQ(s.review_of(0).reviewed_scenes, 0);
    EXPECT_EQ(s.review_of(0).checked_pairs(), 0);
    for (const Problem& p : s.problems())  // the rocks' marks are no problem of the shadows
      EXPECT_EQ(p.file.find("review"), std::string::npos) << p.file << ": " << p.message;
    const SaveJob job = s.toggle_reviewed(0);
    ASSERT_TRUE(job.contents);
    EXPECT_EQ(*job.contents,
              "{\"reviewed\":[{\"scene\":\"s1\",\"class\":1},{\"scene\":\"s1\",\"class\":0}],\"checked\":[{"
              "\"scene\":\"s1\",\"rock_a\":[0.6,0.6,0.1,0.1],\"rock_b\":[0.6,0.6,0.1,0.1],\"class\":0}]}\n");
    run_save_job(job);
  }
  Session s = Session::open(d.path(), rocks);
  EXPECT_EQ(s.review_of(0).reviewed_scenes, 1);
  EXPECT_EQ(s.review_of(0).checked_pairs(), 1);
  EXPECT_TRUE(s.review_of(0).is_checked(0, 1, 1));
}

// A class-blind check is class-blind work: shown under rocks it is kept aside, and stays aside when an edit makes
// the scene's pairs be looked at again (the moment kept checks of this class apply again).
TEST(Classes, AClassBlindCheckNeverAppliesToOneClasssPairs) {
  test::TempDir d;
  write_two_class_study(d);
  SessionOptions all;
  all.class_word = "all";
  {
    Session s = Session::open(d.path(), all);
    const auto job = s.toggle_checked(0, 2, 2);  // R2 | R2 (rows of every class: R1 S1 R2)
    ASSERT_TRUE(job && job->contents);
    EXPECT_NE(job->contents->find("\"class\":\"all\""), std::string::npos) << *job->contents;
    run_save_job(*job);
  }
  SessionOptions rocks;
  rocks.class_word = "rock";
  Session s = Session::open(d.path(), rocks);
  EXPECT_EQ(s.review_of(0).checked_pairs(), 0);
  ASSERT_EQ(s.review_of(0).kept_checks.size(), 1u);
  (void)s.apply(0, Edit::unpair(Side::kA, 0));  // R1 out; R2 | R2 stays a pair
  EXPECT_EQ(s.review_of(0).checked_pairs(), 0);
  EXPECT_EQ(s.review_of(0).kept_checks.size(), 1u);
}

}  // namespace
}  // namespace ipd
