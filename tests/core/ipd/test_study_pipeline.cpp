// The one study pipeline (study_pipeline.h): the table and the studio's Session pair scenes, read fixed
// pairs and report problems through it, so they can't disagree.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>

#include "core/ipd/study_pipeline.h"
#include "core/session/session.h"
#include "core/util/atomic_file.h"
#include "tests/support/test_support.h"

namespace ipd {
namespace {

namespace fs = std::filesystem;

// real and synth share s1 (two rocks, listed in the other order); only_real has no counterpart; s1's hand
// pairs, written as synth__real [synth 1, real 0], pair real 0 with synth 1 only.
void write_pipeline_study(const test::TempDir& d) {
  test::write_text(d / "real/labels/s1.txt", "0 0.2 0.2 0.1 0.1\n0 0.6 0.6 0.1 0.1\n");
  test::write_text(d / "synth/labels/s1.txt", "0 0.6 0.6 0.1 0.1\n0 0.2 0.2 0.1 0.1\n");
  test::write_text(d / "real/labels/only_real.txt", "0 0.5 0.5 0.1 0.1\n");
  test::write_text(d / "pairs/synth__real/s1.json", R"({"pairs": [[1, 0]]})");
  test::write_text(d / "study.yaml", "image_size: [1000, 1000]\n");  // square pictures, said so
}

TEST(StudyPipeline, FixedScenesAreRegisteredOnlyWhenAsked) {
  test::TempDir d;
  write_pipeline_study(d);
  const StudyLabels labels = load_labels(open_study(d.path()));
  PipelineOptions o;
  const PairedStudy table = pair_study(labels, {{"real", "synth"}}, o);
  ASSERT_EQ(table.pairs.size(), 1u);
  ASSERT_EQ(table.pairs[0].scenes.size(), 1u);
  const PipelineScene& s = table.pairs[0].scenes[0];
  EXPECT_EQ(s.automatic.stem, "s1");
  ASSERT_TRUE(s.fixed.has_value());
  EXPECT_EQ(s.fixed->pairs, (RockPairs{{0, 1}}));
  EXPECT_TRUE(s.automatic.pairs.empty());  // the table never needs the registration of a fixed scene
  EXPECT_EQ(table.registrations, 0);
  EXPECT_EQ(table.fixed_scenes, 1);
  const ScenePairing counted = s.counted();
  EXPECT_TRUE(counted.fixed);
  EXPECT_EQ(counted.pairs, (RockPairs{{0, 1}}));
  EXPECT_EQ(counted.count_a, 2);
  EXPECT_EQ(counted.count_b, 2);

  o.register_fixed_scenes = true;  // the studio: "reset to automatic" needs the registration's pairs
  const PairedStudy studio = pair_study(labels, {{"real", "synth"}}, o);
  EXPECT_EQ(studio.pairs[0].scenes[0].automatic.pairs, (RockPairs{{0, 1}, {1, 0}}));
  EXPECT_EQ(studio.registrations, 1);
  EXPECT_EQ(studio.fixed_scenes, 1);
}

// A scene that one of three domains lacks misses two domain pairs: it is one problem naming both domains
// that have it, not one per pair; a scene only one domain has is its own problem.
TEST(StudyPipeline, AMissingSceneIsOneProblemOverItsDomainPairs) {
  test::TempDir d;
  test::write_text(d / "study.yaml", "domains: [real, principled, hapke]\nimage_size: [1000, 1000]\n");
  for (const std::string dom : {"real", "principled", "hapke"})
    test::write_text(d / (dom + "/labels/s1.txt"), "0 0.2 0.2 0.1 0.1\n");
  test::write_text(d / "real/labels/s2.txt", "0 0.2 0.2 0.1 0.1\n");
  test::write_text(d / "principled/labels/s2.txt", "0 0.2 0.2 0.1 0.1\n");
  test::write_text(d / "real/labels/s3.txt", "0 0.2 0.2 0.1 0.1\n");
  const StudyLabels labels = load_labels(open_study(d.path()));
  const PairedStudy paired =
      pair_study(labels, {{"real", "principled"}, {"real", "hapke"}, {"principled", "hapke"}}, PipelineOptions{});
  std::vector<std::string> said;
  for (const Problem& p : paired.problems) said.push_back(p.to_string());
  EXPECT_EQ(said, (std::vector<std::string>{
                      "1 scene(s) of 'real' have no counterpart in 'principled' and are skipped: s3",
                      "2 scene(s) of 'real' have no counterpart in 'hapke' and are skipped: s2, s3",
                      "1 scene(s) of 'principled' have no counterpart in 'hapke' and are skipped: s2",
                  }));
  // Without s3 the same scene is missing from hapke for both domains that have it: one problem.
  fs::remove(d / "real/labels/s3.txt");
  const PairedStudy again = pair_study(load_labels(open_study(d.path())),
                                       {{"real", "principled"}, {"real", "hapke"}, {"principled", "hapke"}}, {});
  ASSERT_EQ(again.problems.size(), 1u);
  EXPECT_EQ(again.problems[0].to_string(),
            "1 scene(s) of 'real' and 'principled' have no counterpart in 'hapke' and are skipped: s2");
  EXPECT_EQ(again.problems[0].scene, "s2");
}

// study.yaml's registration.budget_ms reaches every registration, for the table (through the options the CLI
// builds from the study) and for the studio's Session. A budget of a nanosecond is spent at the first reading of
// the clock after the start, so each registration stops on it.
TEST(StudyPipeline, TheStudysTimeBudgetReachesEveryRegistration) {
  test::TempDir d;
  test::write_text(d / "study.yaml", "registration: {budget_ms: 0.000001}\n");
  test::write_text(d / "real/labels/s1.txt", "0 0.2 0.2 0.1 0.1\n0 0.6 0.6 0.1 0.1\n0 0.3 0.8 0.1 0.1\n");
  test::write_text(d / "synth/labels/s1.txt", "0 0.21 0.2 0.1 0.1\n0 0.61 0.6 0.1 0.1\n0 0.31 0.8 0.1 0.1\n");
  const Study study = open_study(d.path());
  EXPECT_EQ(study.config.registration.time_budget_ms, 0.000001);
  PipelineOptions o;
  o.registration = study.config.registration;  // what `ipd table` and `ipd metrics` pass (study_options.cpp)
  const PairedStudy table = pair_study(load_labels(study), {{"real", "synth"}}, o);
  ASSERT_EQ(table.pairs[0].scenes.size(), 1u);
  EXPECT_EQ(table.pairs[0].scenes[0].automatic.registration.stop, StopReason::kTimeBudget);
  const Session session = Session::open(d.path());
  EXPECT_EQ(session.scenes()[0].automatic.registration.stop, StopReason::kTimeBudget);
  // Without the setting the same scene is registered to the end, and pairs all three rocks.
  test::write_text(d / "study.yaml", "registration: {method: consensus}\n");
  const Session unbudgeted = Session::open(d.path());
  EXPECT_NE(unbudgeted.scenes()[0].automatic.registration.stop, StopReason::kTimeBudget);
  EXPECT_EQ(unbudgeted.scenes()[0].automatic.registration.pairs, (RockPairs{{0, 0}, {1, 1}, {2, 2}}));
}

TEST(StudyPipeline, TheSessionReportsWhatTheTableWarnsAbout) {
  test::TempDir d;
  write_pipeline_study(d);
  // Both name orders of s1's pairs file: the first one read counts, the other is ignored with a warning.
  test::write_text(d / "pairs/real__synth/s1.json", R"({"pairs": [[0, 1], [1, 0]]})");
  const StudyLabels labels = load_labels(open_study(d.path()));
  const PairedStudy paired = pair_study(labels, {{"real", "synth"}}, PipelineOptions{});
  ASSERT_EQ(paired.problems.size(), 2u);
  const Problem& missing = paired.problems[0];
  EXPECT_EQ(missing.to_string(), "1 scene(s) of 'real' have no counterpart in 'synth' and are skipped: only_real");
  EXPECT_EQ(missing.file, "");
  EXPECT_EQ(missing.domain, "real");
  EXPECT_EQ(missing.scene, "only_real");
  const Problem& ignored = paired.problems[1];
  EXPECT_EQ(ignored.file, d / "pairs/synth__real/s1.json");
  EXPECT_EQ(ignored.message, "ignored: " + d / "pairs/real__synth/s1.json" +
                                 " holds this scene's pairs too and is read first; remove one");
  EXPECT_EQ(ignored.scene, "s1");
  EXPECT_EQ(ignored.domain, "real");
  EXPECT_EQ(ignored.other_domain, "synth");

  const Session session(load_labels(open_study(d.path())));
  ASSERT_EQ(session.problems().size(), 2u);
  EXPECT_EQ(session.problems()[0].to_string(), missing.to_string());
  EXPECT_EQ(session.problems()[1].to_string(), ignored.to_string());
  // The file read first counts in both.
  EXPECT_EQ(session.scenes()[0].current.pairs, (RockPairs{{0, 1}, {1, 0}}));
}

TEST(StudyPipeline, ALabelFileMissingBesideItsTwinsIsAProblem) {
  test::TempDir d;
  write_pipeline_study(d);
  // s2 has a picture in both domains but GT only in synth: real's s2 reads as a picture without rocks.
  test::write_text(d / "real/images/s2.png", "");
  test::write_text(d / "synth/images/s2.png", "");
  test::write_text(d / "synth/labels/s2.txt", "0 0.3 0.3 0.1 0.1\n");
  const StudyLabels labels = load_labels(open_study(d.path()));
  const PairedStudy paired = pair_study(labels, {{"real", "synth"}}, PipelineOptions{});
  ASSERT_EQ(paired.problems.size(), 2u);  // only_real without a counterpart, then s2
  const Problem& p = paired.problems[1];
  EXPECT_EQ(p.to_string(),
            d / "real/labels/s2.txt" +
                ": no label file, while 'synth' has one for this scene: read as a picture without rocks");
  EXPECT_EQ(p.scene, "s2");
  EXPECT_EQ(p.domain, "real");
  const Session session(load_labels(open_study(d.path())));
  EXPECT_EQ(session.problems().at(1).to_string(), p.to_string());
}

TEST(StudyPipeline, TheSessionListsSkippedLinesAndMissingPredictions) {
  test::TempDir d;
  write_pipeline_study(d);
  // A file name pasted into a label line: the CLI refuses it (unless --skip-bad-lines); the studio skips it,
  // and its Problems list names the file and line.
  test::write_text(d / "synth/labels/s1.txt", "0 0.6 0.6 0.1 0.1\n0 0.2 0.2 0.1 0.1 s1.png\n0 0.2 0.2 0.1 0.1\n");
  test::write_text(d / "real/predictions/det/s1.txt", "0 0.2 0.2 0.1 0.1 0.9\n");
  const Session s(load_labels(open_study(d.path())));
  EXPECT_EQ(s.gt(Side::kB, 0).size(), 2u);  // the bad line is skipped, the others are kept
  const std::vector<Problem> problems = s.problems();
  ASSERT_EQ(problems.size(), 3u);
  EXPECT_EQ(problems[0].to_string(), d / "synth/labels/s1.txt" + ":2: expected 5 columns (class cx cy w h), found 6");
  EXPECT_EQ(problems[0].file, d / "synth/labels/s1.txt");
  EXPECT_EQ(problems[0].line, 2);
  EXPECT_EQ(problems[0].domain, "synth");
  EXPECT_EQ(problems[0].scene, "s1");
  EXPECT_EQ(problems[1].to_string(), "1 scene(s) of 'real' have no counterpart in 'synth' and are skipped: only_real");
  EXPECT_EQ(problems[2].to_string(), "model 'det' has no predictions for domain 'synth' (expected " +
                                         d / "synth/predictions/det" + "/): its cells are empty");
  EXPECT_EQ(problems[2].domain, "synth");
}

// A labels-only study whose study.yaml gives no image_size registers its scenes as square pictures, which can
// change its pairs: ipd table says so once (not once per scene or domain pair) and the studio lists it once.
TEST(StudyPipeline, ALabelsOnlyStudyWithoutImageSizeIsWarnedOnce) {
  test::TempDir d;
  ASSERT_EQ(test::run_ipd("demo " + d / "s" + " --labels-only --scenes 3 --rocks 8").exit_code, 0);
  const std::string with_size = read_file(d / "s/study.yaml");
  ASSERT_NE(with_size.find("image_size: [960, 600]\n"), std::string::npos) << with_size;
  std::string without = with_size;
  without.erase(without.find("image_size: [960, 600]\n"), std::string("image_size: [960, 600]\n").size());
  test::write_text(d / "s/study.yaml", without);
  const std::string warning = "warning: " + d / "s/study.yaml" +
                              ": no image_size and no pictures: registration takes the pictures as square (aspect "
                              "1), so its angles and distances are not the pictures' pixels and the pairs can "
                              "differ from those of the real aspect; add 'image_size: [WIDTH, HEIGHT]' (the "
                              "pictures' size in pixels), as ipd register --image-size takes it\n";
  const auto r = test::run_ipd("table " + d / "s" + " --bootstrap 0");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err, warning);  // once, for three domain pairs of three scenes
  const Session session(load_labels(open_study(d / "s")));
  const auto& problems = session.problems();
  EXPECT_EQ(std::count_if(problems.begin(), problems.end(),
                          [](const Problem& p) { return p.message.rfind("no image_size", 0) == 0; }),
            1);
  // With the size back, no word.
  test::write_text(d / "s/study.yaml", with_size);
  EXPECT_EQ(test::run_ipd("table " + d / "s" + " --bootstrap 0").err, "");
}

}  // namespace
}  // namespace ipd
