// ipd-studio driven by --replay in a real window (Xvfb): the edits it makes reach the pairs files exactly
// as the Session API makes them. Run by ctest (StudioReplayEdits, which sets IPD_STUDIO); skipped otherwise.
#include <gtest/gtest.h>

#include <fmt/format.h>
#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <sstream>

#include "core/session/session.h"
#include "core/util/atomic_file.h"
#include "tests/support/pdf_text.h"
#include "tests/support/test_support.h"

namespace fs = std::filesystem;

namespace ipd {
namespace {

int run_studio_replay(const std::string& cmd) {
  const int status = std::system(cmd.c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

// `command` in a fresh Xvfb, its output redirected by `redirections`; returns the command's own exit status.
// xvfb-run's cleanup can fail after the command has finished ("problem while cleaning up temporary directory",
// status 5, seen under load with other Xvfb runs), so the status is taken from a file the command leaves.
int run_in_xvfb(const std::string& command, const std::string& redirections, const fs::path& dir) {
  const fs::path status_file = dir / "exit-status.txt";
  fs::remove(status_file);
  const int xvfb = run_studio_replay(fmt::format("xvfb-run -a -s '-screen 0 1280x800x24' sh -c '{}; echo $? >{}' {}",
                                                 command, status_file.string(), redirections));
  if (!fs::exists(status_file)) return xvfb;
  return std::stoi(read_file(status_file));
}

TEST(StudioReplay, EditsReachThePairsFiles) {
  const char* studio = std::getenv("IPD_STUDIO");
  if (!studio || !*studio) GTEST_SKIP() << "set IPD_STUDIO to the ipd-studio binary (ctest does)";
  test::TempDir d;
  ASSERT_EQ(test::run_ipd(fmt::format("demo {} --labels-only --scenes 3 --rocks 12", d / "study")).exit_code, 0);
  test::write_text(d / "actions.txt",
                   "# audit fixes\n"
                   "scene scene_00002\n"
                   "unpair 1\n"
                   "pair 2 3\n"
                   "exclude 4\n"
                   "undo\n"
                   "redo\n"
                   "scene scene_00003\n"
                   "pair 1 1\n"
                   "undo\n"
                   "export " +
                       d / "fig.pdf\n"
                           "export table " +
                       d / "table.pdf\n"
                           "export breakdown-confidence " +
                       d / "breakdown.svg\n"
                           "screenshot " +
                       d / "shot.png\n");
  // The same edits through the Session API, opened before the GUI writes anything.
  Session s = Session::open(d / "study");
  const std::string cmd =
      fmt::format("XDG_CACHE_HOME={} {} {} --replay {}", d / "cache", studio, d / "study", d / "actions.txt");
  ASSERT_EQ(run_in_xvfb(cmd, fmt::format(">{} 2>&1", d / "log.txt"), d.path()), 0) << read_file(d / "log.txt");
  EXPECT_TRUE(fs::exists(d / "shot.png"));
  ASSERT_TRUE(fs::exists(d / "fig.pdf")) << read_file(d / "log.txt");  // exported in-process, on the worker
  EXPECT_EQ(read_file(d / "fig.pdf").substr(0, 5), "%PDF-");
  EXPECT_NE(test::pdf_words(d / "table.pdf").find("Instance Performance Difference"), std::string::npos);
  EXPECT_NE(read_file(d / "breakdown.svg").find(">IPD(real, principled) of "), std::string::npos);

  const int two = s.scene_index("scene_00002");
  s.apply(two, Edit::unpair(Side::kA, 0));
  s.apply(two, Edit::pair(1, 2));
  const SaveJob expected = s.apply(two, Edit::toggle_exclude(Side::kA, 3));
  ASSERT_TRUE(expected.contents.has_value());
  EXPECT_EQ(read_file(d / "study/pairs/real__principled/scene_00002.json"), *expected.contents);
  EXPECT_FALSE(fs::exists(d / "study/pairs/real__principled/scene_00003.json"));  // paired, then undone
}

TEST(StudioReplay, BadActionsNameTheFileAndLine) {
  const char* studio = std::getenv("IPD_STUDIO");
  if (!studio || !*studio) GTEST_SKIP() << "set IPD_STUDIO to the ipd-studio binary (ctest does)";
  test::TempDir d;
  test::write_text(d / "actions.txt", "wait 2\npair 1\n");
  const std::string cmd = fmt::format("{} --replay {} >{} 2>&1", studio, d / "actions.txt", d / "log.txt");
  EXPECT_EQ(run_studio_replay(cmd), 2);
  EXPECT_EQ(read_file(d / "log.txt"),
            "error: " + d / "actions.txt" + ":2: 'pair' takes two rock numbers (left, right), got 1 argument(s)\n");
  test::write_text(d / "actions.txt", "export histogram x.pdf\n");
  EXPECT_EQ(run_studio_replay(cmd), 2);
  EXPECT_EQ(read_file(d / "log.txt"),
            "error: " + d / "actions.txt" +
                ":1: 'export': expected a figure kind (pairs, registration, table, compare, distribution, breakdown, "
                "breakdown-size, breakdown-region, breakdown-confidence or gallery), got 'histogram'\n");
  // A number is the whole word: "5\0" (a zero-filled block) is not 5, and it must fit the studio's int.
  test::write_text(d / "actions.txt", std::string("wait 5\0\n", 8));
  EXPECT_EQ(run_studio_replay(cmd), 2);
  EXPECT_EQ(read_file(d / "log.txt"),
            "error: " + d / "actions.txt" + ":1: 'wait': expected a number >= 1, got '5\\x00'\n");
  test::write_text(d / "actions.txt", "wait 1\nwait 99999999999\n");
  EXPECT_EQ(run_studio_replay(cmd), 2);
  EXPECT_EQ(read_file(d / "log.txt"),
            "error: " + d / "actions.txt" + ":2: 'wait': expected a number >= 1, got '99999999999'\n");
  test::write_text(d / "actions.txt", std::string("conf 0.5\0\n", 10));
  EXPECT_EQ(run_studio_replay(cmd), 2);
  EXPECT_EQ(read_file(d / "log.txt"),
            "error: " + d / "actions.txt" + ":1: 'conf': expected a threshold in [0, 1], got '0.5\\x00'\n");
  // The methods come from the one table (registration_methods()), the default first.
  test::write_text(d / "actions.txt", "rerun cpd\nrerun ransac\n");
  EXPECT_EQ(run_studio_replay(cmd), 2);
  EXPECT_EQ(read_file(d / "log.txt"),
            "error: " + d / "actions.txt" + ":2: 'rerun': expected consensus, paper or cpd, got 'ransac'\n");
  // One domain against itself has no gap: the replay says so instead of keeping the domains on screen.
  test::write_text(d / "actions.txt", "domains real real\n");
  EXPECT_EQ(run_studio_replay(cmd), 2);
  EXPECT_EQ(read_file(d / "log.txt"),
            "error: " + d / "actions.txt" + ":1: 'domains': expected two different domains, got 'real' twice\n");
  test::write_text(d / "actions.txt", "check 2\n");
  EXPECT_EQ(run_studio_replay(cmd), 2);
  EXPECT_EQ(read_file(d / "log.txt"),
            "error: " + d / "actions.txt" +
                ":1: 'check' takes two rock numbers of a pair (left, right), or nothing for the selected pair, got 1 "
                "argument(s)\n");
  test::write_text(d / "actions.txt", "focus yes\n");
  EXPECT_EQ(run_studio_replay(cmd), 2);
  EXPECT_EQ(read_file(d / "log.txt"), "error: " + d / "actions.txt" + ":1: 'focus': expected on or off, got 'yes'\n");
}

TEST(StudioReplay, DomainsTheStudyLacksFailTheReplay) {
  const char* studio = std::getenv("IPD_STUDIO");
  if (!studio || !*studio) GTEST_SKIP() << "set IPD_STUDIO to the ipd-studio binary (ctest does)";
  test::TempDir d;
  ASSERT_EQ(test::run_ipd(fmt::format("demo {} --labels-only --scenes 2 --rocks 8", d / "study")).exit_code, 0);
  test::write_text(d / "actions.txt", "focus on\nscreenshot " + d / "focus.png\n" + "domains real synthetic\n");
  const std::string cmd =
      fmt::format("XDG_CACHE_HOME={} {} {} --replay {}", d / "cache", studio, d / "study", d / "actions.txt");
  EXPECT_EQ(run_in_xvfb(cmd, fmt::format(">{} 2>&1", d / "log.txt"), d.path()), 1);
  EXPECT_TRUE(fs::exists(d / "focus.png"));
  EXPECT_NE(read_file(d / "log.txt").find(d / "actions.txt" + ":3: 'domains': the study has no domain 'synthetic'\n"),
            std::string::npos)
      << read_file(d / "log.txt");
}

// A model the study lacks was accepted (exit 0) and figures were exported for it; it fails as a domain does.
TEST(StudioReplay, AModelTheStudyLacksFailsTheReplay) {
  const char* studio = std::getenv("IPD_STUDIO");
  if (!studio || !*studio) GTEST_SKIP() << "set IPD_STUDIO to the ipd-studio binary (ctest does)";
  test::TempDir d;
  ASSERT_EQ(test::run_ipd(fmt::format("demo {} --scenes 2 --rocks 8", d / "study")).exit_code, 0);
  test::write_text(d / "actions.txt", "model det-real\nmodel nothere\nexport table " + d / "table.svg\n");
  const std::string cmd =
      fmt::format("XDG_CACHE_HOME={} {} {} --replay {}", d / "cache", studio, d / "study", d / "actions.txt");
  EXPECT_EQ(run_in_xvfb(cmd, fmt::format(">{} 2>&1", d / "log.txt"), d.path()), 1);
  EXPECT_FALSE(fs::exists(d / "table.svg"));
  EXPECT_NE(read_file(d / "log.txt").find(d / "actions.txt" + ":2: 'model': the study has no model 'nothere'\n"),
            std::string::npos)
      << read_file(d / "log.txt");
}

TEST(StudioReplay, AStudyThatCannotBeOpenedSaysWhyOnStderr) {
  const char* studio = std::getenv("IPD_STUDIO");
  if (!studio || !*studio) GTEST_SKIP() << "set IPD_STUDIO to the ipd-studio binary (ctest does)";
  test::TempDir d;
  const std::string cmd = fmt::format("XDG_CACHE_HOME={} {} {} --screenshot {} --frames 3", d / "cache", studio,
                                      d / "missing", d / "shot.png");
  EXPECT_EQ(run_in_xvfb(cmd, fmt::format(">/dev/null 2>{}", d / "err.txt"), d.path()), 1);
  // Contains, not equals: Xvfb and the GL driver may add their own lines to stderr.
  const std::string err = read_file(d / "err.txt");
  EXPECT_NE(err.find("error: could not open the study: " + d / "missing" + ": no such study directory\n"),
            std::string::npos)
      << err;
}

// Scripted runs must end and say what went wrong: a replay on a study that can't be opened exits 1, it does not
// wait for the study forever (`timeout` turns a hang into 124, not 1).
TEST(StudioReplay, AReplayOnAStudyThatCannotBeOpenedExits1) {
  const char* studio = std::getenv("IPD_STUDIO");
  if (!studio || !*studio) GTEST_SKIP() << "set IPD_STUDIO to the ipd-studio binary (ctest does)";
  test::TempDir d;
  test::write_text(d / "actions.txt", "scene next\nunpair 1\n");
  const std::string cmd = fmt::format("XDG_CACHE_HOME={} timeout 120 {} {} --replay {}", d / "cache", studio,
                                      d / "missing", d / "actions.txt");
  EXPECT_EQ(run_in_xvfb(cmd, fmt::format(">/dev/null 2>{}", d / "err.txt"), d.path()), 1);
  const std::string err = read_file(d / "err.txt");
  EXPECT_NE(err.find("error: could not open the study: " + d / "missing" + ": no such study directory\n"),
            std::string::npos)
      << err;
}

// An edit that could not be saved and an export that could not be written fail the run, each named.
TEST(StudioReplay, FailedSavesAndExportsMakeTheReplayFail) {
  const char* studio = std::getenv("IPD_STUDIO");
  if (!studio || !*studio) GTEST_SKIP() << "set IPD_STUDIO to the ipd-studio binary (ctest does)";
  test::TempDir d;
  ASSERT_EQ(test::run_ipd(fmt::format("demo {} --labels-only --scenes 3 --rocks 12", d / "study")).exit_code, 0);
  test::write_text(d / "study/pairs", "a file where the pairs folder should be\n");
  test::write_text(d / "blocker", "a file where the figure's folder should be\n");
  test::write_text(d / "actions.txt", "scene scene_00002\nunpair 1\nexport " + d / "blocker/fig.pdf" + "\n");
  const std::string cmd = fmt::format("XDG_CACHE_HOME={} timeout 120 {} {} --replay {}", d / "cache", studio,
                                      d / "study", d / "actions.txt");
  EXPECT_EQ(run_in_xvfb(cmd, fmt::format(">/dev/null 2>{}", d / "err.txt"), d.path()), 1);
  const std::string err = read_file(d / "err.txt");
  const std::string prefix = "error: replay " + d / "actions.txt" + ": ";
  EXPECT_NE(err.find(prefix + "edit not saved: " + d / "study/pairs" + ": is a file, expected a folder\n"),
            std::string::npos)
      << err;
  EXPECT_NE(err.find(prefix + d / "blocker/fig.pdf" + ": export failed: "), std::string::npos) << err;
  EXPECT_EQ(err.find("could not open the study"), std::string::npos) << err;
}

// Adds `by` to every box's cx in a label file (written with 6 decimals, as the demo writes them).
void shift_boxes(const std::string& file, double by) {
  std::istringstream in(read_file(file));
  std::string out;
  int cls = 0;
  double cx = 0, cy = 0, w = 0, h = 0;
  while (in >> cls >> cx >> cy >> w >> h)
    out += fmt::format("{} {:.6f} {:.6f} {:.6f} {:.6f}\n", cls, cx + by, cy, w, h);
  test::write_text(file, out);
}

// A pairs file is the user's work. A box moved by 1e-6 (a re-export) is the same rock: the next edit keeps
// every hand decision. A rock really moved makes the file stale: an edit of the scene is refused, the replay
// exits 1 naming the file, and the file is untouched until `automatic` discards it.
TEST(StudioReplay, AStalePairsFileIsNeverOverwrittenByAnEdit) {
  const char* studio = std::getenv("IPD_STUDIO");
  if (!studio || !*studio) GTEST_SKIP() << "set IPD_STUDIO to the ipd-studio binary (ctest does)";
  test::TempDir d;
  ASSERT_EQ(test::run_ipd(fmt::format("demo {} --labels-only --scenes 2 --rocks 8", d / "study")).exit_code, 0);
  auto replay = [&](const std::string& actions) {
    test::write_text(d / "actions.txt", actions);
    const std::string cmd = fmt::format("XDG_CACHE_HOME={} timeout 120 {} {} --replay {}", d / "cache", studio,
                                        d / "study", d / "actions.txt");
    return run_in_xvfb(cmd, fmt::format(">/dev/null 2>{}", d / "err.txt"), d.path());
  };
  const std::string pairs = d / "study/pairs/real__principled/scene_00001.json";
  const std::string labels = d / "study/principled/labels/scene_00001.txt";
  ASSERT_EQ(replay("scene scene_00001\nunpair 1\nexclude 2\n"), 0) << read_file(d / "err.txt");
  shift_boxes(labels, 1e-6);
  ASSERT_EQ(replay("scene scene_00001\nexclude 3\n"), 0) << read_file(d / "err.txt");
  {
    Session s = Session::open(d / "study");
    ASSERT_TRUE(s.select_domains("real", "principled"));
    const SceneState& scene = s.scenes()[s.scene_index("scene_00001")];
    EXPECT_TRUE(scene.edited);
    EXPECT_EQ(scene.current.excluded_a, (std::vector<int>{1, 2}));
    for (const auto& p : scene.current.pairs) EXPECT_NE(p.first, 0);  // left rock 1 still unpaired
  }
  shift_boxes(labels, 0.01);
  const std::string before = read_file(pairs);
  EXPECT_EQ(replay("scene scene_00001\npair 1 1\n"), 1);
  EXPECT_EQ(read_file(pairs), before);
  const std::string err = read_file(d / "err.txt");
  EXPECT_NE(err.find("error: replay " + d / "actions.txt" + ": failed: " + pairs + ": edit refused: "),
            std::string::npos)
      << err;
  EXPECT_EQ(replay("scene scene_00001\nautomatic\n"), 0) << read_file(d / "err.txt");
  EXPECT_FALSE(fs::exists(pairs));
}

TEST(StudioReplay, ProblemsTheCliReportsArePrintedOnStderr) {
  const char* studio = std::getenv("IPD_STUDIO");
  if (!studio || !*studio) GTEST_SKIP() << "set IPD_STUDIO to the ipd-studio binary (ctest does)";
  test::TempDir d;
  ASSERT_EQ(test::run_ipd(fmt::format("demo {} --labels-only --scenes 3 --rocks 5", d / "study")).exit_code, 0);
  // A file name pasted into a label line, and a scene missing in one domain: `ipd table` exits 1 naming the
  // line; the studio opens the study (the line skipped) and must say so too.
  const std::string labels = d / "study/real/labels/scene_00001.txt";
  const std::string text = read_file(labels);
  const int lines = static_cast<int>(std::count(text.begin(), text.end(), '\n'));
  test::write_text(labels, text + "0 0.5 0.5 0.1 0.1 scene_00001.png\n");
  fs::remove(d / "study/principled/labels/scene_00003.txt");
  // The Problems window open, its first row clicked (the bad line's scene), then a screenshot.
  test::write_text(d / "actions.txt", "problems\nproblem 1\nwait 3\nscreenshot " + d / "problems.png\n");
  const std::string cmd =
      fmt::format("XDG_CACHE_HOME={} {} {} --replay {}", d / "cache", studio, d / "study", d / "actions.txt");
  EXPECT_EQ(run_in_xvfb(cmd, fmt::format(">/dev/null 2>{}", d / "err.txt"), d.path()), 0);
  EXPECT_TRUE(fs::exists(d / "problems.png"));
  const std::string err = read_file(d / "err.txt");
  EXPECT_NE(err.find(fmt::format("warning: {}:{}: expected 5 columns (class cx cy w h), found 6\n", labels, lines + 1)),
            std::string::npos)
      << err;
  EXPECT_NE(err.find("warning: 1 scene(s) of 'real' and 'hapke' have no counterpart in 'principled' and are skipped: "
                     "scene_00003\n"),
            std::string::npos)
      << err;
}

// A prediction whose confidence is exactly the threshold is kept, in the studio as by `ipd --conf`: "conf 0.3"
// is 0.3, not the float 0.30000001 that dropped synth's prediction (IPD 0.5 instead of 0).
TEST(StudioReplay, AThresholdKeepsAPredictionAtExactlyThatConfidenceAsTheCliDoes) {
  const char* studio = std::getenv("IPD_STUDIO");
  if (!studio || !*studio) GTEST_SKIP() << "set IPD_STUDIO to the ipd-studio binary (ctest does)";
  test::TempDir d;
  const fs::path study = d / "study";
  for (const std::string domain : {"real", "synth"})
    test::write_text(study / domain / "labels/s1.txt", "0 0.2 0.2 0.1 0.1\n0 0.6 0.6 0.1 0.1\n");
  test::write_text(study / "real/predictions/det/s1.txt", "0 0.2 0.2 0.1 0.1 0.9\n");
  test::write_text(study / "synth/predictions/det/s1.txt", "0 0.2 0.2 0.1 0.1 0.3\n");
  test::write_text(d / "actions.txt", "conf 0.3\nwait 3\nexport table " + d / "gui.svg\n");
  const std::string cmd =
      fmt::format("XDG_CACHE_HOME={} {} {} --replay {}", d / "cache", studio, study.string(), d / "actions.txt");
  ASSERT_EQ(run_in_xvfb(cmd, fmt::format(">{} 2>&1", d / "log.txt"), d.path()), 0) << read_file(d / "log.txt");
  const auto cli = test::run_ipd("figure table " + study.string() + " --conf 0.3 --out " + d / "cli.svg");
  ASSERT_EQ(cli.exit_code, 0) << cli.err;
  // The cell's number in both: 0.0000 (both rocks score alike); 0.5000 had synth's prediction been dropped.
  for (const std::string file : {"gui.svg", "cli.svg"}) {
    const std::string svg = read_file(d / file);
    EXPECT_NE(svg.find(">0.0000</text>"), std::string::npos) << file;
    EXPECT_EQ(svg.find(">0.5000</text>"), std::string::npos) << file;
  }
}

// A rerun is watched where its replay is: the registration tab comes forward from behind the statistics.
TEST(StudioReplay, ARerunBringsTheRegistrationTabForward) {
  const char* studio = std::getenv("IPD_STUDIO");
  if (!studio || !*studio) GTEST_SKIP() << "set IPD_STUDIO to the ipd-studio binary (ctest does)";
  test::TempDir d;
  test::write_two_rock_study(d);
  test::write_text(d / "actions.txt", fmt::format("wait 2\nstate {}\nrerun paper\nwait 3\nstate {}\n",
                                                  d / "before.json", d / "after.json"));
  const std::string cmd =
      fmt::format("XDG_CACHE_HOME={} {} {} --replay {}", d / "cache", studio, d.path(), d / "actions.txt");
  ASSERT_EQ(run_in_xvfb(cmd, fmt::format(">/dev/null 2>{}", d / "err.txt"), d.path()), 0) << read_file(d / "err.txt");
  EXPECT_EQ(nlohmann::json::parse(read_file(d / "before.json"))["registration_tab"], false);
  EXPECT_EQ(nlohmann::json::parse(read_file(d / "after.json"))["registration_tab"], true);
}

// Two scenes: s1 as write_two_rock_study (pairs with |diff| 2/3 and 0), s2 with both sides' predictions on
// their rocks (|diff| 0 twice). A drag box over |diff| >= 0.5, perf A >= 0.5 holds one pair, in s1: the scene
// list then shows s1 alone, under the selection's label. The selected pair stays highlighted when the scatter
// shows other axes (size x perf B), where the box means nothing.
TEST(StudioReplay, ARockViewBoxBecomesASceneListFilter) {
  const char* studio = std::getenv("IPD_STUDIO");
  if (!studio || !*studio) GTEST_SKIP() << "set IPD_STUDIO to the ipd-studio binary (ctest does)";
  test::TempDir d;
  test::write_two_rock_study(d);
  for (const char* domain : {"real", "synth"}) {
    const std::string rocks = "0 0.3 0.3 0.1 0.1\n0 0.7 0.4 0.15 0.1\n";
    test::write_text(d / fmt::format("{}/labels/s2.txt", domain), rocks);
    test::write_text(d / fmt::format("{}/predictions/det/s2.txt", domain),
                     "0 0.3 0.3 0.1 0.1 0.9\n0 0.7 0.4 0.15 0.1 0.7\n");
  }
  test::write_text(
      d / "actions.txt",
      fmt::format("list {}\nrocks diff perf-a\nwait 2\nselect 0.5 0.5 1 1\nwait 2\nstate {}\n"
                  "rocks size perf-b\nwait 2\nstate {}\nlist {}\ngallery page 2 sort size\nwait 2\n"
                  "screenshot {}\n",
                  d / "before.txt", d / "boxed.json", d / "other-axes.json", d / "after.txt", d / "rocks.png"));
  const std::string cmd =
      fmt::format("XDG_CACHE_HOME={} {} {} --replay {}", d / "cache", studio, d.path(), d / "actions.txt");
  ASSERT_EQ(run_in_xvfb(cmd, fmt::format(">/dev/null 2>{}", d / "err.txt"), d.path()), 0) << read_file(d / "err.txt");
  EXPECT_EQ(read_file(d / "before.txt"), "\ns1\ns2\n");
  EXPECT_EQ(read_file(d / "after.txt"), "selection: 1 pair in 1 scene\ns1\n");
  const auto boxed = nlohmann::json::parse(read_file(d / "boxed.json"))["rock_view"];
  EXPECT_EQ(boxed["x"], "|diff|");
  EXPECT_EQ(boxed["points"], 4);
  EXPECT_EQ(boxed["highlighted"], 1);
  const auto other = nlohmann::json::parse(read_file(d / "other-axes.json"))["rock_view"];
  EXPECT_EQ(other["x"], "size (px\u00b2)");
  EXPECT_EQ(other["y"], "perf B");
  EXPECT_EQ(other["highlighted"], 1);
  EXPECT_TRUE(fs::exists(d / "rocks.png"));
}

// An audit driven through the review verbs: `suspect` selects the next suspect pair (N), `check` marks it
// correct (C), `review` marks the scene (R), undo takes the last toggle back. The second `suspect` in s1 must
// skip the pair checked before (else `check` would uncheck it). The review file then holds exactly what the
// same toggles make through the Session API.
TEST(StudioReplay, AReviewMarksScenesAndChecksSuspectPairs) {
  const char* studio = std::getenv("IPD_STUDIO");
  if (!studio || !*studio) GTEST_SKIP() << "set IPD_STUDIO to the ipd-studio binary (ctest does)";
  test::TempDir d;
  test::write_review_study(d);
  test::write_text(d / "actions.txt",
                   "scene s1\nsuspect\ncheck\nscene s2\nreview\nreview\nundo\nscene s1\nsuspect\ncheck\n"
                   "check 4 3\nundo\nreview\n");
  Session s = Session::open(d.path());
  const std::string cmd =
      fmt::format("XDG_CACHE_HOME={} {} {} --replay {}", d / "cache", studio, d.path(), d / "actions.txt");
  ASSERT_EQ(run_in_xvfb(cmd, fmt::format(">/dev/null 2>{}", d / "err.txt"), d.path()), 0) << read_file(d / "err.txt");
  s.toggle_checked(0, 2, 3);
  s.toggle_reviewed(1);
  s.toggle_checked(0, 3, 2);
  const SaveJob expected = s.toggle_reviewed(0);
  ASSERT_TRUE(expected.contents.has_value());
  EXPECT_EQ(*expected.contents,
            "{\"reviewed\":[\"s1\",\"s2\"],\"checked\":[{\"scene\":\"s1\",\"rock_a\":[0.3,0.8,0.12,0.1],"
            "\"rock_b\":[0.75,0.7,0.08,0.12]},{\"scene\":\"s1\",\"rock_a\":[0.75,0.7,0.08,0.12],\"rock_b\":[0.3,"
            "0.8,0.12,0.1]}]}\n");
  EXPECT_EQ(read_file(d / "review/real__synth.json"), *expected.contents);
  EXPECT_EQ(s.summary(0).suspects, 0);
}

TEST(StudioReplay, RockViewActionsNameTheirArguments) {
  const char* studio = std::getenv("IPD_STUDIO");
  if (!studio || !*studio) GTEST_SKIP() << "set IPD_STUDIO to the ipd-studio binary (ctest does)";
  test::TempDir d;
  test::write_text(d / "actions.txt", "rocks perf-a width\n");
  const std::string cmd = fmt::format("{} --replay {} >{} 2>&1", studio, d / "actions.txt", d / "log.txt");
  EXPECT_EQ(run_studio_replay(cmd), 2);
  EXPECT_EQ(read_file(d / "log.txt"),
            "error: " + d / "actions.txt" +
                ":1: 'rocks': expected an axis (perf-a, perf-b, diff, size, x, y, conf-a or conf-b), got 'width'\n");
  test::write_text(d / "actions.txt", "select 0 0 1 one\n");
  EXPECT_EQ(run_studio_replay(cmd), 2);
  EXPECT_EQ(read_file(d / "log.txt"), "error: " + d / "actions.txt" + ":1: 'select': expected a number, got 'one'\n");
  test::write_text(d / "actions.txt", "gallery sort worst\n");
  EXPECT_EQ(run_studio_replay(cmd), 2);
  EXPECT_EQ(read_file(d / "log.txt"),
            "error: " + d / "actions.txt" +
                ":1: 'gallery': expected a sort key (diff, perf-a, perf-b or size), got 'worst'\n");
  test::write_text(d / "actions.txt", "gallery page 0\n");
  EXPECT_EQ(run_studio_replay(cmd), 2);
  EXPECT_EQ(read_file(d / "log.txt"),
            "error: " + d / "actions.txt" + ":1: 'gallery': expected a page number >= 1, got '0'\n");
  test::write_text(d / "actions.txt", "gallery page 2 page 3\n");
  EXPECT_EQ(run_studio_replay(cmd), 2);
  EXPECT_EQ(read_file(d / "log.txt"),
            "error: " + d / "actions.txt" + ":1: 'gallery': expected 'page N' or 'sort KEY' (each once), got 'page'\n");
  test::write_text(d / "actions.txt", "gallery page\n");
  EXPECT_EQ(run_studio_replay(cmd), 2);
  EXPECT_EQ(read_file(d / "log.txt"), "error: " + d / "actions.txt" +
                                          ":1: 'gallery' takes [page N] [sort diff|perf-a|perf-b|size], got 1 "
                                          "argument(s)\n");
}

}  // namespace
}  // namespace ipd

namespace ipd {
namespace {
// A study of rocks and shadows (classes.txt names both): the window shows the first named class and says which on
// stderr; the replay verb `class shadow` opens it again showing shadows.
TEST(StudioReplay, TheClassVerbSwitchesTheClassShown) {
  const char* studio = std::getenv("IPD_STUDIO");
  if (!studio || !*studio) GTEST_SKIP() << "set IPD_STUDIO to the ipd-studio binary (ctest does)";
  test::TempDir d;
  const std::string gt = "0 0.2 0.2 0.1 0.1\n1 0.25 0.2 0.1 0.1\n0 0.6 0.6 0.1 0.1\n0 0.4 0.8 0.1 0.1\n";
  for (const char* domain : {"real", "synth"}) {
    test::write_text(d / (std::string("study/") + domain + "/labels/s1.txt"), gt);
    test::write_text(d / (std::string("study/") + domain + "/predictions/det/s1.txt"), "0 0.2 0.2 0.1 0.1 0.9\n");
  }
  test::write_text(d / "study/real/labels/classes.txt", "rock\nshadow\n");
  test::write_text(d / "rocks.txt", "wait 3\n");
  test::write_text(d / "shadows.txt", "class shadow\nwait 3\n");
  for (const auto& [actions, expected] : {std::pair<std::string, std::string>{"rocks.txt", "class: rock (class 0)\n"},
                                          {"shadows.txt", "class: shadow (class 1)\n"}}) {
    const std::string cmd =
        fmt::format("XDG_CACHE_HOME={} {} {} --replay {}", d / "cache", studio, d / "study", d / actions);
    EXPECT_EQ(run_in_xvfb(cmd, fmt::format(">{} 2>&1", d / "log.txt"), d.path()), 0) << read_file(d / "log.txt");
    EXPECT_NE(read_file(d / "log.txt").find(expected), std::string::npos) << read_file(d / "log.txt");
  }
  // The scene in view stays in view across the switch, although the shadow class has no rock in s1 and the
  // scenes are listed in another order (s0 sorts first by IPD for rocks, s2 for shadows).
  test::write_text(d / "study/real/labels/s0.txt", "0 0.3 0.3 0.1 0.1\n0 0.7 0.3 0.1 0.1\n0 0.5 0.7 0.1 0.1\n");
  test::write_text(d / "study/synth/labels/s0.txt", "0 0.3 0.3 0.1 0.1\n0 0.7 0.3 0.1 0.1\n0 0.5 0.7 0.1 0.1\n");
  test::write_text(d / "study/real/labels/s2.txt", "1 0.3 0.3 0.1 0.1\n1 0.7 0.3 0.1 0.1\n1 0.5 0.7 0.1 0.1\n");
  test::write_text(d / "study/synth/labels/s2.txt", "1 0.3 0.3 0.1 0.1\n1 0.7 0.3 0.1 0.1\n1 0.5 0.7 0.1 0.1\n");
  for (const char* domain : {"real", "synth"})
    for (const char* stem : {"s0", "s2"})
      test::write_text(d / (std::string("study/") + domain + "/predictions/det/" + stem + ".txt"), "");
  test::write_text(d / "stay.txt", fmt::format("scene s2\nwait 3\nstate {0}/a.json\nclass shadow\nwait 3\nstate "
                                               "{0}/b.json\nclass rock\nwait 3\nstate {0}/c.json\n",
                                               d.path()));
  const std::string cmd =
      fmt::format("XDG_CACHE_HOME={} {} {} --replay {}", d / "cache", studio, d / "study", d / "stay.txt");
  EXPECT_EQ(run_in_xvfb(cmd, fmt::format(">{} 2>&1", d / "log.txt"), d.path()), 0) << read_file(d / "log.txt");
  for (const char* state : {"a.json", "b.json", "c.json"})
    EXPECT_EQ(nlohmann::json::parse(read_file(d / state))["scene"], "s2") << state << ": " << read_file(d / state);
}
}  // namespace
}  // namespace ipd
