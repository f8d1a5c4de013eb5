// Headless figures: golden images (with a tolerance), boxes where the labels put them, clear errors,
// atomic output. Set IPD_UPDATE_GOLDEN=1 to rewrite tests/golden/*.png after an intended change.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "figures.h"
#include "test_support.h"

namespace fs = std::filesystem;

namespace ipd {
namespace {

// Two domains, one scene with a small drawn picture each, one rock each, one prediction each.
//   GT (both):        0 0.30 0.40 0.20 0.25      prediction real: 0 0.35 0.40 0.20 0.25 0.87
//   second rock real: 0 0.75 0.70 0.10 0.12      prediction synth: 0 0.32 0.40 0.20 0.25 0.93
void write_figure_study(const test::TempDir& d, bool pictures) {
  test::write_text(d / "study.yaml", "domains: [real, synth]\nimage_size: [640, 400]\nmodels: {det: {trained_on: real}}\n");
  test::write_text(d / "real/labels/s1.txt", "0 0.30 0.40 0.20 0.25\n0 0.75 0.70 0.10 0.12\n");
  test::write_text(d / "synth/labels/s1.txt", "0 0.30 0.40 0.20 0.25\n");
  test::write_text(d / "real/predictions/det/s1.txt", "0 0.35 0.40 0.20 0.25 0.87\n");
  test::write_text(d / "synth/predictions/det/s1.txt", "0 0.32 0.40 0.20 0.25 0.93\n");
  if (!pictures) return;
  for (const std::string dom : {"real", "synth"}) {
    cv::Mat img(400, 640, CV_8UC3, cv::Scalar(90, 95, 100));
    cv::circle(img, {192, 160}, 50, cv::Scalar(170, 175, 180), cv::FILLED, cv::LINE_AA);
    fs::create_directories(d / (dom + "/images"));
    cv::imwrite(d / (dom + "/images/s1.png"), img);
  }
}

// Mean absolute difference per channel, and the share of pixels differing by more than 64 somewhere.
void expect_like_golden(const std::string& produced, const std::string& name) {
  const std::string golden = std::string(IPD_GOLDEN_DIR) + "/" + name;
  const cv::Mat got = cv::imread(produced, cv::IMREAD_COLOR);
  ASSERT_FALSE(got.empty()) << produced;
  if (const char* u = std::getenv("IPD_UPDATE_GOLDEN"); u && std::string(u) == "1") {
    fs::copy_file(produced, golden, fs::copy_options::overwrite_existing);
    GTEST_SKIP() << "golden image rewritten: " << golden;
  }
  const cv::Mat want = cv::imread(golden, cv::IMREAD_COLOR);
  ASSERT_FALSE(want.empty()) << "no golden image " << golden << " (run with IPD_UPDATE_GOLDEN=1 to create it)";
  ASSERT_EQ(got.size(), want.size()) << name;
  cv::Mat diff;
  cv::absdiff(got, want, diff);
  const cv::Scalar mean = cv::mean(diff);
  EXPECT_LT((mean[0] + mean[1] + mean[2]) / 3, 1.5) << name;
  cv::Mat big;
  cv::cvtColor(diff, big, cv::COLOR_BGR2GRAY);
  EXPECT_LT(cv::countNonZero(big > 64), static_cast<int>(0.01 * big.total())) << name;
}

TEST(Figures, PairsRegistrationAndTableMatchTheirGoldenImages) {
  test::TempDir d;
  write_figure_study(d, true);
  for (const std::string kind : {"pairs", "registration", "table"}) {
    const std::string out = d / (kind + ".png");
    const auto r = test::run_ipd("figure " + kind + " " + d.path() + " --width 800 --out " + out);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(r.out, out + "\n");
    expect_like_golden(out, "figure_" + kind + ".png");
  }
}

bool near(const cv::Vec3b& bgr, int r, int g, int b) {
  return std::abs(bgr[2] - r) < 40 && std::abs(bgr[1] - g) < 40 && std::abs(bgr[0] - b) < 40;
}

TEST(Figures, BoxesStandWhereTheLabelsSay) {
  test::TempDir d;
  write_figure_study(d, false);  // grey placeholders: only boxes carry colour
  const std::string out = d / "pairs.png";
  const int width = 1200;
  const auto r = test::run_ipd("figure pairs " + d.path() + " --scene s1 --width 1200 --out " + out);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const cv::Mat img = cv::imread(out, cv::IMREAD_COLOR);
  ASSERT_FALSE(img.empty());
  const float px = std::max(13.0f, width / 75.0f);
  const ui::PairsLayout l = ui::pairs_layout({float(img.cols), float(img.rows)}, px);
  // Whether a colour appears within 2 pixels of where the label puts an edge (lines sit on half pixels).
  auto colour_near = [&](ImVec2 area_min, double x, double y, int r, int g, int b) {
    const ui::Placement p = ui::place(area_min, l.side_size, 640, 400, ui::CanvasView{});
    const ImVec2 q = p.to_screen(x, y);
    for (int dy = -2; dy <= 2; ++dy)
      for (int dx = -2; dx <= 2; ++dx)
        if (near(img.at<cv::Vec3b>(static_cast<int>(std::lround(q.y)) + dy, static_cast<int>(std::lround(q.x)) + dx), r, g, b))
          return true;
    return false;
  };
  // Left GT box: left edge x = 0.20 (pink); its prediction's right edge x = 0.45 (red); inside, neither.
  EXPECT_TRUE(colour_near(l.left_min, 0.20, 0.40, 255, 105, 200));
  EXPECT_TRUE(colour_near(l.left_min, 0.45, 0.45, 235, 40, 40));
  EXPECT_FALSE(colour_near(l.left_min, 0.33, 0.45, 255, 105, 200));
  EXPECT_FALSE(colour_near(l.left_min, 0.33, 0.45, 235, 40, 40));
  // The unpaired second rock is grey (left edge x = 0.70), and there is no box there on the right.
  EXPECT_TRUE(colour_near(l.left_min, 0.70, 0.70, 160, 160, 160));
  EXPECT_FALSE(colour_near(l.right_min, 0.70, 0.70, 160, 160, 160));
  // Right: GT left edge x = 0.20 (pink), prediction right edge x = 0.42 (red).
  EXPECT_TRUE(colour_near(l.right_min, 0.20, 0.40, 255, 105, 200));
  EXPECT_TRUE(colour_near(l.right_min, 0.42, 0.45, 235, 40, 40));
}

TEST(Figures, ClearMessagesAndNoFileOnError) {
  test::TempDir d, empty;
  write_figure_study(d, false);
  auto r = test::run_ipd("figure pairs " + d.path() + " --scene nope --out " + d / "x.png");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_EQ(r.err, "error: " + d.path() + ": no scene 'nope' in both 'real' and 'synth'\n");
  EXPECT_FALSE(fs::exists(d / "x.png"));
  test::write_text(empty / "real/labels/a.txt", "");
  test::write_text(empty / "synth/labels/b.txt", "");
  r = test::run_ipd("figure registration " + empty.path() + " --out " + empty / "x.png");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_EQ(r.err, "error: " + empty.path() + ": no scene is present in both 'real' and 'synth'\n");
  r = test::run_ipd("figure table " + empty / "missing" + " --out " + empty / "x.png");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_EQ(r.err, "error: " + empty / "missing" + ": no such study directory\n");
  // A successful run leaves the figure and nothing else (no temp files).
  r = test::run_ipd("figure table " + d.path() + " --out " + d / "figs/t.png");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  int files = 0;
  for (const auto& e : fs::directory_iterator(d / "figs")) files += e.is_regular_file();
  EXPECT_EQ(files, 1);
}

TEST(Figures, DefaultSceneIsTheLargestContribution) {
  test::TempDir d;
  write_figure_study(d, false);
  // A second scene where both sides agree (contributes 0).
  test::write_text(d / "real/labels/s0.txt", "0 0.5 0.5 0.2 0.2\n");
  test::write_text(d / "synth/labels/s0.txt", "0 0.5 0.5 0.2 0.2\n");
  test::write_text(d / "real/predictions/det/s0.txt", "0 0.5 0.5 0.2 0.2 0.9\n");
  test::write_text(d / "synth/predictions/det/s0.txt", "0 0.5 0.5 0.2 0.2 0.9\n");
  const auto r = test::run_ipd("figure pairs " + d.path() + " --width 400 --out " + d / "p.png");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err, "scene s1: it contributes most to IPD(real, synth) for det\n");
}

}  // namespace
}  // namespace ipd
