// The audit's views in a real window (Xvfb), driven by --replay and read back through its `state` dump and
// --frame-stats: the blink view draws both domains' boxes through the registration, flips and blends the
// pictures; sync zoom follows the selected rock to its new partner; hand pairs that equal registration's leave
// the scene automatic (no pairs file); the Rank window lists `ipd rank`'s order and a click shows a setting on
// the right. Run by ctest (StudioAuditViews, which sets IPD_STUDIO); skipped otherwise.
#include <gtest/gtest.h>

#include <fmt/format.h>
#include <cstdlib>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <regex>
#include <string>

#include "core/session/session.h"
#include "core/util/atomic_file.h"
#include "tests/support/pdf_text.h"
#include "tests/support/test_support.h"

namespace fs = std::filesystem;

namespace ipd {
namespace {

const char* studio() {
  const char* s = std::getenv("IPD_STUDIO");
  return s && *s ? s : nullptr;
}

// ipd-studio on `study` with the replay `actions`; returns its exit status, its output in *log.
int replay(const test::TempDir& d, const std::string& study, const std::string& actions, std::string* log,
           const std::string& extra = "") {
  test::write_text(d / "actions.txt", actions);
  const std::string cmd =
      fmt::format("XDG_CACHE_HOME={} sh {} 1600x900x24 {} {} --size 1600x900 --replay {} {} >{} 2>&1", d / "cache",
                  IPD_TESTS_DIR "/e2e/run_in_xvfb.sh", studio(), study, d / "actions.txt", extra, d / "log.txt");
  const int status = std::system(cmd.c_str());
  *log = read_file(d / "log.txt");
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

nlohmann::json state(const test::TempDir& d, const std::string& name) {
  return nlohmann::json::parse(read_file(d / name));
}

int lines_of(const fs::path& file) {
  const std::string text = read_file(file);
  return static_cast<int>(std::count(text.begin(), text.end(), '\n'));
}

TEST(StudioAudit, BlinkViewDrawsBothDomainsFlipsAndBlends) {
  if (!studio()) GTEST_SKIP() << "set IPD_STUDIO to the ipd-studio binary (ctest does)";
  test::TempDir d;
  ASSERT_EQ(test::run_ipd(fmt::format("demo {}", d / "study")).exit_code, 0);
  // scene_02 of the demo: 17 GT boxes a side and 32 predictions of det-real a side (the label files' lines).
  const int gt_l = lines_of(d / "study/real/labels/scene_02.txt");
  const int gt_r = lines_of(d / "study/principled/labels/scene_02.txt");
  const int pred_l = lines_of(d / "study/real/predictions/det-real/scene_02.txt");
  const int pred_r = lines_of(d / "study/principled/predictions/det-real/scene_02.txt");
  ASSERT_EQ(gt_l, 17);
  ASSERT_EQ(pred_r, 32);
  std::string log;
  ASSERT_EQ(replay(d, d / "study",
                   fmt::format("scene scene_02\nstate {0}/s0.json\nblink on\nstate {0}/s1.json\nblink flip\n"
                               "state {0}/s2.json\nblink overlay 0.25\nstate {0}/s3.json\nblink rate 4\nwait 30\n"
                               "focus on\nwait 3\nstate {0}/s4.json\n",
                               d.path()),
                   &log, "--frame-stats"),
            0)
      << log;
  EXPECT_FALSE(state(d, "s0.json")["blink"]["drawn"].get<bool>());  // the two panes
  const nlohmann::json s1 = state(d, "s1.json")["blink"];
  EXPECT_TRUE(s1["drawn"].get<bool>());
  EXPECT_TRUE(s1["pictures"].get<bool>());
  EXPECT_EQ(s1["mode"], "blink");
  EXPECT_EQ(s1["right_opacity"].get<double>(), 0.0);  // the left picture first
  EXPECT_EQ(s1["gt"], nlohmann::json({gt_l, gt_r}));
  EXPECT_EQ(s1["predictions"], nlohmann::json({pred_l, pred_r}));
  EXPECT_EQ(s1["hand_pairs"], 0);
  EXPECT_EQ(state(d, "s2.json")["blink"]["right_opacity"].get<double>(), 1.0);  // flipped: the right one
  const nlohmann::json s3 = state(d, "s3.json")["blink"];
  EXPECT_EQ(s3["mode"], "overlay");
  EXPECT_NEAR(s3["right_opacity"].get<double>(), 0.25, 1e-6);
  // The focus view gives the blink pane at least 80% of the 1600 x 900 window.
  const nlohmann::json s4 = state(d, "s4.json")["blink"];
  EXPECT_GE(s4["pane"][0].get<double>() * s4["pane"][1].get<double>() / (1600.0 * 900.0), 0.8) << s4.dump();
  // --frame-stats times the blink frames and says what the last one drew.
  std::smatch m;
  ASSERT_TRUE(
      std::regex_search(log, m, std::regex(R"(blink_frame_ms median=([0-9.]+) p95=[0-9.]+ max=[0-9.]+ n=(\d+))")))
      << log;
  EXPECT_GT(std::stoi(m[2]), 20) << log;
  // Flipping 4 times a second, the last frame showed one picture whole, either one.
  const std::string drawn = fmt::format(R"(pictures=yes right_opacity=(0|1)\.00 gt={}\+{} pred={}\+{} hand_pairs=0)",
                                        gt_l, gt_r, pred_l, pred_r);
  EXPECT_TRUE(std::regex_search(log, std::regex(drawn))) << log;
}

TEST(StudioAudit, BlinkViewOfALabelsOnlyStudyDrawsBoxesAndAHandPair) {
  if (!studio()) GTEST_SKIP() << "set IPD_STUDIO to the ipd-studio binary (ctest does)";
  test::TempDir d;
  ASSERT_EQ(test::run_ipd(fmt::format("demo {} --labels-only --scenes 3 --rocks 12", d / "study")).exit_code, 0);
  std::string log;
  ASSERT_EQ(replay(d, d / "study",
                   fmt::format("scene scene_00002\nblink on\npair 2 3\nwait 2\nstate {0}/s1.json\n", d.path()), &log),
            0)
      << log;
  const nlohmann::json s1 = state(d, "s1.json");
  EXPECT_FALSE(s1["blink"]["pictures"].get<bool>());  // boxes only, and the window says so
  EXPECT_EQ(s1["blink"]["gt"], nlohmann::json({lines_of(d / "study/real/labels/scene_00002.txt"),
                                               lines_of(d / "study/principled/labels/scene_00002.txt")}));
  EXPECT_EQ(s1["blink"]["predictions"][0], lines_of(d / "study/real/predictions/det-real/scene_00002.txt"));
  EXPECT_TRUE(s1["edited"].get<bool>());
  // Left rock 2 with right rock 3 is no pair of registration's: one hand pair, highlighted.
  EXPECT_EQ(s1["blink"]["hand_pairs"], 1);
}

TEST(StudioAudit, BadBlinkActionsAreNamed) {
  if (!studio()) GTEST_SKIP() << "set IPD_STUDIO to the ipd-studio binary (ctest does)";
  test::TempDir d;
  test::write_text(d / "actions.txt", "blink overlay 2\n");
  const std::string cmd = fmt::format("{} --replay {} >{} 2>&1", studio(), d / "actions.txt", d / "log.txt");
  const int status = std::system(cmd.c_str());
  EXPECT_EQ(WEXITSTATUS(status), 2);
  EXPECT_EQ(read_file(d / "log.txt"),
            "error: " + d / "actions.txt" +
                ":1: 'blink': expected on, off, flip, overlay X (X in [0, 1]) or rate N (N in "
                "[0, 8] flips a second), got 'overlay 2'\n");
}

TEST(StudioAudit, SyncZoomFollowsTheNewPartnerAndRegistrationsPairsLeaveTheSceneAutomatic) {
  if (!studio()) GTEST_SKIP() << "set IPD_STUDIO to the ipd-studio binary (ctest does)";
  test::TempDir d;
  ASSERT_EQ(test::run_ipd(fmt::format("demo {}", d / "study")).exit_code, 0);
  // Registration's partner of left rock 1 in scene_02, a right rock that is not it and that rock's partner.
  int partner = -1, wrong = -1, wrong_partner = -1;
  double left_cx = 0, left_cy = 0, partner_cx = 0, partner_cy = 0, wrong_cx = 0, wrong_cy = 0;
  {
    const Session s = Session::open(d / "study");
    const int scene = s.scene_index("scene_02");
    for (const auto& [l, r] : s.view_pairs(scene))
      if (l == 0) partner = r;
    ASSERT_GE(partner, 0);
    wrong = partner == 0 ? 1 : 0;
    for (const auto& [l, r] : s.view_pairs(scene))
      if (r == wrong) wrong_partner = l;
    ASSERT_GT(wrong_partner, 0);
    left_cx = s.gt(Side::kA, scene)[0].cx, left_cy = s.gt(Side::kA, scene)[0].cy;
    partner_cx = s.gt(Side::kB, scene)[partner].cx, partner_cy = s.gt(Side::kB, scene)[partner].cy;
    wrong_cx = s.gt(Side::kB, scene)[wrong].cx, wrong_cy = s.gt(Side::kB, scene)[wrong].cy;
  }
  const fs::path file = d / "study/pairs/real__principled/scene_02.json";
  std::string log;
  // Left rock 1 paired with a wrong rock: a suspect pair, N selects it (zoom 2.5 on it); then rock 1 is paired
  // with its partner again and the wrong rock with its own: registration's pairs.
  ASSERT_EQ(replay(d, d / "study",
                   fmt::format("scene scene_02\npair 1 {1}\nsuspect\nstate {0}/s1.json\npair 1 {2}\nwait 2\n"
                               "state {0}/s2.json\npair {3} {1}\nwait 2\nstate {0}/s3.json\n",
                               d.path(), wrong + 1, partner + 1, wrong_partner + 1),
                   &log),
            0)
      << log;
  const nlohmann::json s1 = state(d, "s1.json"), s2 = state(d, "s2.json"), s3 = state(d, "s3.json");
  EXPECT_EQ(s1["selected_left"], 1) << log;
  EXPECT_TRUE(s1["edited"].get<bool>());
  // The right picture shows the wrong partner where the left shows rock 1: pan = rock's pan + (partner - rock).
  const double pan_x = s1["left_view"]["pan"][0].get<double>(), pan_y = s1["left_view"]["pan"][1].get<double>();
  EXPECT_NEAR(pan_x, left_cx - 0.5, 1e-5);
  EXPECT_NEAR(s1["right_view"]["pan"][0].get<double>(), wrong_cx - 0.5, 1e-5);
  EXPECT_NEAR(s1["right_view"]["pan"][1].get<double>(), wrong_cy - 0.5, 1e-5);
  // After the re-pairing the right picture follows the new partner, at the same zoom.
  EXPECT_EQ(s2["right_view"]["zoom"], s2["left_view"]["zoom"]);
  EXPECT_NEAR(s2["right_view"]["pan"][0].get<double>(), pan_x + partner_cx - left_cx, 1e-5);
  EXPECT_NEAR(s2["right_view"]["pan"][1].get<double>(), pan_y + partner_cy - left_cy, 1e-5);
  EXPECT_TRUE(s2["edited"].get<bool>());  // the wrong rock's partner is still unpaired
  // Registration's pairs again: the scene is automatic and its pairs file is gone.
  EXPECT_FALSE(s3["edited"].get<bool>());
  EXPECT_FALSE(fs::exists(file));
  // and `ipd table` reads no hand pairs.
  const test::CommandResult table = test::run_ipd(fmt::format("table {}", d / "study"));
  EXPECT_NE(table.out.find("no hand pairs (every pair from registration)"), std::string::npos) << table.out;
}

TEST(StudioAudit, RankWindowListsTheRankingAndAClickShowsTheSettingOnTheRight) {
  if (!studio()) GTEST_SKIP() << "set IPD_STUDIO to the ipd-studio binary (ctest does)";
  test::TempDir d;
  ASSERT_EQ(test::run_ipd(fmt::format("demo {} --variants 4", d / "study")).exit_code, 0);
  const test::CommandResult cli =
      test::run_ipd(fmt::format("rank {} --ref real --model det-real --format json", d / "study"));
  ASSERT_EQ(cli.exit_code, 0) << cli.err;
  const nlohmann::json ranked = nlohmann::json::parse(cli.out)["ranked"];
  ASSERT_EQ(ranked.size(), 4u) << cli.out;
  const std::string third = ranked[2]["domain"];
  std::string log;
  ASSERT_EQ(
      replay(d, d / "study",
             fmt::format("model det-real\nrank\nstate {0}/s1.json\nrank {1}\nstate {0}/s2.json\n", d.path(), third),
             &log),
      0)
      << log;
  const nlohmann::json s1 = state(d, "s1.json");
  ASSERT_EQ(s1["rank"]["ranked"].size(), 4u) << s1.dump();
  EXPECT_EQ(s1["rank"]["ref"], "real");
  for (size_t k = 0; k < 4; ++k) {
    EXPECT_EQ(s1["rank"]["ranked"][k]["domain"], ranked[k]["domain"]) << k;
    EXPECT_NEAR(s1["rank"]["ranked"][k]["ipd"].get<double>(), ranked[k]["ipd"].get<double>(), 1e-12) << k;
    EXPECT_EQ(s1["rank"]["ranked"][k]["in_best_group"], ranked[k]["in_best_group"]) << k;
  }
  const nlohmann::json s2 = state(d, "s2.json");
  EXPECT_EQ(s2["left"], "real");
  EXPECT_EQ(s2["right"], third);
}

TEST(StudioAudit, GalleryExportFollowsTheSortOnScreen) {
  if (!studio()) GTEST_SKIP() << "set IPD_STUDIO to the ipd-studio binary (ctest does)";
  test::TempDir d;
  ASSERT_EQ(test::run_ipd(fmt::format("demo {}", d / "study")).exit_code, 0);
  std::string log;
  ASSERT_EQ(replay(d, d / "study",
                   fmt::format("model det-real\ngallery sort size\nexport gallery {}/studio.pdf\n", d.path()), &log),
            0)
      << log;
  for (const char* sort : {"size", "diff"})
    ASSERT_EQ(test::run_ipd(fmt::format("figure gallery {} --model det-real --sort {} --count 8 --out {}/{}.pdf",
                                        d / "study", sort, d.path(), sort))
                  .exit_code,
              0);
  // The same pairs in the same order as `ipd figure gallery --sort size`, not the default |diff| order.
  const std::string studio_words = test::pdf_words(d / "studio.pdf");
  EXPECT_EQ(studio_words, test::pdf_words(d / "size.pdf"));
  EXPECT_NE(studio_words, test::pdf_words(d / "diff.pdf"));
}

}  // namespace
}  // namespace ipd
