// The studio's worker and saver without a window: commands go in from one thread, immutable snapshots come
// out, and hand edits reach the pairs files. Run under ThreadSanitizer too (preset "tsan").
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <thread>

#include "app/studio/studio_worker.h"
#include "core/demo/demo_study.h"
#include "tests/support/test_support.h"

namespace fs = std::filesystem;
using namespace ipd;
using namespace ipd::studio;
using ipd::test::TempDir;

namespace {

// Waits until the worker has run everything queued and the saver has written it (a minute at most).
void wait_done(StudyWorker& w) {
  const auto until = std::chrono::steady_clock::now() + std::chrono::minutes(1);
  while (!w.idle() && std::chrono::steady_clock::now() < until)
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  ASSERT_TRUE(w.idle()) << "the worker is still busy after a minute";
  w.saver().wait_idle();
}

std::string open_small_study(const TempDir& d, StudyWorker& w) {
  DemoStudyOptions o;
  o.scenes = 3;
  o.labels_only = true;
  const std::string dir = d / "study";
  write_demo_study(dir, o);
  w.submit(command::OpenStudy{dir, false, {}});
  wait_done(w);
  return dir;
}

}  // namespace

TEST(StudyWorker, OpensAStudyAndPublishesItsScenes) {
  TempDir d;
  StudyWorker w;
  open_small_study(d, w);
  const auto snap = w.snapshot();
  ASSERT_TRUE(snap) << w.open_error();
  EXPECT_EQ(snap->session->scenes().size(), 3u);
  EXPECT_EQ(snap->summaries->size(), 3u);
  EXPECT_EQ(w.open_error(), "");
}

TEST(StudyWorker, AStudyThatCannotBeOpenedLeavesTheReason) {
  TempDir d;
  StudyWorker w;
  w.submit(command::OpenStudy{d / "nowhere", false, {}});
  wait_done(w);
  EXPECT_FALSE(w.snapshot());
  EXPECT_NE(w.open_error().find("nowhere"), std::string::npos) << w.open_error();
}

TEST(StudyWorker, AnEditIsPublishedSavedAndUndone) {
  TempDir d;
  StudyWorker w;
  const std::string dir = open_small_study(d, w);
  const auto before = w.snapshot();
  ASSERT_TRUE(before);
  const std::string stem = before->session->scenes()[0].stem;
  const auto& [a, b] = before->session->domain_pairs()[before->session->pair_index()];
  const fs::path pairs_file = fs::path(dir) / "pairs" / (a + "__" + b) / (stem + ".json");
  ASSERT_FALSE(before->session->excluded(Side::kA, 0, 0));

  w.submit(command::ApplyEdit{0, Edit::toggle_exclude(Side::kA, 0)});
  wait_done(w);
  const auto after = w.snapshot();
  EXPECT_GT(after->version, before->version);
  EXPECT_TRUE(after->session->excluded(Side::kA, 0, 0));
  EXPECT_FALSE(before->session->excluded(Side::kA, 0, 0)) << "a published snapshot never changes";
  EXPECT_TRUE((*after->summaries)[0].edited);
  EXPECT_FALSE((*before->summaries)[0].edited) << "nor do its summaries";
  EXPECT_GE(after->edit_ms, 0);
  EXPECT_GE(after->edit_cpu_ms, 0);
  EXPECT_LE(after->edit_cpu_ms, after->edit_ms + 1) << "the worker's CPU time in the edit is within its wall time";
  EXPECT_EQ(before->edit_ms, -1);  // made by opening, not by an edit
  EXPECT_EQ(before->edit_cpu_ms, -1);
  EXPECT_TRUE(fs::exists(pairs_file)) << pairs_file;

  w.submit(command::Undo{});
  wait_done(w);
  EXPECT_FALSE(w.snapshot()->session->excluded(Side::kA, 0, 0));
  EXPECT_FALSE(fs::exists(pairs_file)) << "undone back to automatic pairing: the file goes";
  EXPECT_EQ(w.snapshot()->jump_to_scene, 0);

  w.submit(command::Redo{});
  wait_done(w);
  EXPECT_TRUE(w.snapshot()->session->excluded(Side::kA, 0, 0));
  EXPECT_TRUE(fs::exists(pairs_file));
}

// After an edit only the edited scene's summary is made again: the published list equals a full one.
TEST(StudyWorker, SummariesAfterEditsEqualThoseOfTheWholeSession) {
  TempDir d;
  StudyWorker w;
  open_small_study(d, w);
  const auto opened = w.snapshot();
  ASSERT_TRUE(opened);
  const SceneSummary untouched = (*opened->summaries)[1];
  w.submit(command::ApplyEdit{1, Edit::unpair(Side::kA, 0)});
  w.submit(command::ApplyEdit{2, Edit::toggle_exclude(Side::kA, 1)});
  w.submit(command::Undo{});
  wait_done(w);
  const auto snap = w.snapshot();
  const std::vector<SceneSummary> full = snap->session->summaries();
  ASSERT_EQ(snap->summaries->size(), full.size());
  for (size_t k = 0; k < full.size(); ++k) {
    const SceneSummary& p = (*snap->summaries)[k];
    EXPECT_EQ(p.stem, full[k].stem);
    EXPECT_EQ(p.pairs, full[k].pairs) << k;
    EXPECT_EQ(p.unpaired_a, full[k].unpaired_a) << k;
    EXPECT_EQ(p.edited, full[k].edited) << k;
    EXPECT_EQ(p.suspects, full[k].suspects) << k;
    EXPECT_TRUE(p.ipd == full[k].ipd || (std::isnan(p.ipd) && std::isnan(full[k].ipd))) << k;
  }
  EXPECT_TRUE((*snap->summaries)[1].edited);
  EXPECT_FALSE((*snap->summaries)[2].edited);  // undone
  EXPECT_EQ((*snap->summaries)[1].pairs, untouched.pairs - 1);
  EXPECT_EQ((*opened->summaries)[1].pairs, untouched.pairs);
}

// A review mark changes one scene's summary: the worker redoes that one (timed as an edit, edit_ms) instead of
// every summary of the study, and the result equals the whole session's.
TEST(StudyWorker, ReviewMarksRedoOnlyTheirScenesSummary) {
  TempDir d;
  StudyWorker w;
  open_small_study(d, w);
  const auto opened = w.snapshot();
  ASSERT_TRUE(opened);
  const std::pair<int, int> first_pair = opened->session->scenes()[0].current.pairs.at(0);
  w.submit(command::ToggleReviewed{1});
  wait_done(w);
  const auto reviewed = w.snapshot();
  EXPECT_GE(reviewed->edit_ms, 0) << "a review mark is timed as an edit";
  EXPECT_TRUE((*reviewed->summaries)[1].reviewed);
  EXPECT_FALSE((*opened->summaries)[1].reviewed) << "an earlier snapshot does not change";
  w.submit(command::ToggleChecked{0, first_pair.first, first_pair.second});
  w.submit(command::ToggleReviewed{2});
  w.submit(command::Undo{});
  wait_done(w);
  const auto snap = w.snapshot();
  EXPECT_GE(snap->edit_ms, 0);
  const std::vector<SceneSummary> full = snap->session->summaries();
  ASSERT_EQ(snap->summaries->size(), full.size());
  for (size_t k = 0; k < full.size(); ++k) {
    EXPECT_EQ((*snap->summaries)[k].reviewed, full[k].reviewed) << k;
    EXPECT_EQ((*snap->summaries)[k].suspects, full[k].suspects) << k;
  }
  EXPECT_TRUE((*snap->summaries)[1].reviewed);
  EXPECT_FALSE((*snap->summaries)[2].reviewed) << "undone";
  EXPECT_EQ(snap->session->review_of(0).checked_pairs(), 1);
}

TEST(StudyWorker, ARerunIsPublishedWithoutChangingTheSession) {
  TempDir d;
  StudyWorker w;
  open_small_study(d, w);
  const auto before = w.snapshot();
  command::RerunRegistration r;
  r.scene = 1;
  r.automatic = true;
  w.submit(r);
  wait_done(w);
  const auto after = w.snapshot();
  ASSERT_TRUE(after->rerun);
  EXPECT_EQ(after->rerun_stem, before->session->scenes()[1].stem);
  EXPECT_TRUE(after->rerun_is_automatic);
  EXPECT_EQ(after->session, before->session) << "a re-run reuses the published session";
  EXPECT_FALSE(after->rerun->trace.steps.empty()) << "re-runs record their trace for the replay panel";
}

TEST(StudyWorker, ThresholdsFromManyThreadsEndOnTheLastOne) {
  TempDir d;
  StudyWorker w;
  open_small_study(d, w);
  // The view thread and a replay may submit at once; the worker serialises them, and a queued threshold
  // is replaced by a newer one, so the last submitted wins.
  std::vector<std::thread> threads;
  for (int t = 0; t < 4; ++t)
    threads.emplace_back([&w, t] {
      for (int k = 0; k < 20; ++k) w.submit(command::SetConfThreshold{0.01 * (t * 20 + k) / 80.0});
    });
  for (auto& t : threads) t.join();
  w.submit(command::SetConfThreshold{0.5});
  wait_done(w);
  EXPECT_DOUBLE_EQ(w.snapshot()->session->conf_threshold(), 0.5);
}

TEST(StudyWorker, ExportJobsReportTheirStatusLine) {
  TempDir d;
  StudyWorker w;
  open_small_study(d, w);
  w.submit(command::ExportFigure{[] { return std::string("wrote x.pdf"); }});
  w.submit(command::ExportFigure{});
  wait_done(w);
  const auto messages = w.take_messages();
  ASSERT_EQ(messages.size(), 2u);
  EXPECT_EQ(messages[0], "wrote x.pdf");
  EXPECT_EQ(messages[1], "export failed: nothing to export");
}
