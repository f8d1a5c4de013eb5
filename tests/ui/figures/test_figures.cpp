// Headless figures, raster path (`ipd figure ... --out X.png`: OSMesa + ImGui's draw list): golden images
// (with a tolerance), boxes where the labels put them, clear errors, atomic output. Set IPD_UPDATE_GOLDEN=1
// to rewrite tests/golden/*.png after an intended change (and look at them before committing).
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "core/demo/demo_study.h"
#include "tests/support/figure_test_study.h"
#include "tests/support/test_support.h"
#include "ui/canvas/canvas_cairo.h"
#include "ui/figures/figure_input.h"
#include "ui/figures/figure_options.h"
#include "ui/figures/figure_scene.h"
#include "ui/figures/scene_panels.h"

namespace fs = std::filesystem;

namespace ipd {
namespace {

// Mean absolute difference per channel, and the share of pixels differing by more than 64 somewhere.
bool updating_golden() {
  const char* u = std::getenv("IPD_UPDATE_GOLDEN");
  return u && std::string(u) == "1";
}

void expect_like_golden(const std::string& produced, const std::string& name) {
  const std::string golden = std::string(IPD_GOLDEN_DIR) + "/" + name;
  const cv::Mat got = cv::imread(produced, cv::IMREAD_COLOR);
  ASSERT_FALSE(got.empty()) << produced;
  if (updating_golden()) {
    fs::copy_file(produced, golden, fs::copy_options::overwrite_existing);
    return;
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

// The figure options' sentences name the command-line option and its range; check() throws exactly that.
TEST(Figures, OptionsValidateNamesTheOptionAndItsRange) {
  ui::FigureOptions o;
  EXPECT_EQ(o.validate(), "");
  o.dpi = 20;
  EXPECT_EQ(o.validate(), "--dpi: 20 is outside 30..2400");
  o.dpi = 300;
  o.width_in = 0.5;
  EXPECT_EQ(o.validate(), "--width-in: 0.5 is not a figure width (1 to 40 inches)");
  o.width_in = 3.5;
  o.crop.x0 = 0.6;
  o.crop.x1 = 0.4;
  EXPECT_EQ(o.validate(), "--crop: the region must satisfy 0 <= X0 < X1 <= 1 and 0 <= Y0 < Y1 <= 1");
  o.crop = {};
  o.by = "area";
  EXPECT_EQ(o.validate(), "--by: expected size, region or confidence, found 'area'");
  try {
    o.check();
    FAIL() << "check() accepted --by area";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "--by: expected size, region or confidence, found 'area'");
  }
}

TEST(Figures, PairsRegistrationAndTableMatchTheirGoldenImages) {
  test::TempDir d;
  test::write_figure_study(d, true);
  for (const std::string kind : {"pairs", "registration", "table"}) {
    const std::string out = d / (kind + ".png");
    const auto r = test::run_ipd("figure " + kind + " " + d.path() + " --column single --dpi 200 --out " + out);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(r.out, out + "\n");
    expect_like_golden(out, "figure_" + kind + ".png");
  }
  if (updating_golden()) GTEST_SKIP() << "golden images rewritten in " << IPD_GOLDEN_DIR;
}

bool near(const cv::Vec3b& bgr, int r, int g, int b) {
  return std::abs(bgr[2] - r) < 40 && std::abs(bgr[1] - g) < 40 && std::abs(bgr[0] - b) < 40;
}

// --panels: side by side, each picture half the width less the 4 pt gap ((252 - 8 - 4) / 2 = 120 pt), or
// stacked, each the whole width between the margins (244 pt), the second under the first; auto keeps a
// sparse scene (every pair numbered) side by side. --crop auto on the study's two rocks (x 0.20..0.80,
// y 0.275..0.76): a square region (the picture's shape) 0.6 + 2 x 0.05 wide about their centre.
TEST(Figures, PanelsSideBySideOrStackedAndTheRocksCrop) {
  test::TempDir d;
  test::write_figure_study(d, false);
  const StudyLabels labels = load_labels(open_study(d.path()));
  const ui::SceneFigureInput in = ui::scene_input_from_study(labels, "real", "synth", "det", "s1", 0, {});
  const ui::FontMetrics metrics(ui::default_font_file());
  for (const auto panels :
       {ui::PanelArrangement::kAuto, ui::PanelArrangement::kSideBySide, ui::PanelArrangement::kStacked}) {
    ui::FigureOptions o;
    o.panels = panels;
    ui::DisplayList fig(metrics);
    const ui::PairsLayout l = ui::draw_pairs_figure(fig, in, o);
    const bool stacked = panels == ui::PanelArrangement::kStacked;
    EXPECT_EQ(l.stacked, stacked);
    EXPECT_NEAR(l.left.width(), stacked ? 244 : 120, 1e-9);
    EXPECT_NEAR(l.left.height(), l.left.width() / (640.0 / 400.0), 1e-9);
    if (stacked) {
      EXPECT_NEAR(l.right.x0, l.left.x0, 1e-9);
      EXPECT_GT(l.right.y0, l.left.y1);
    } else {
      EXPECT_NEAR(l.right.x0, l.left.x1 + 4, 1e-9);
      EXPECT_NEAR(l.right.y0, l.left.y0, 1e-9);
    }
  }
  EXPECT_THROW(ui::parse_panels("stack"), std::invalid_argument);
  const auto r = test::run_ipd("figure pairs " + d.path() + " --scene s1 --panels stack --out " + (d / "p.pdf"));
  EXPECT_EQ(r.exit_code, 2);
  // Rocks: real 0.30 +- 0.10 x 0.40 +- 0.125 and 0.75 +- 0.05 x 0.70 +- 0.06; synth the first only.
  // x 0.20..0.80, y 0.275..0.76: side max(0.6, 0.485) + 0.1 = 0.7, centred on (0.5, 0.5175).
  const ui::Crop c = ui::scene::rocks_crop(in, false);
  EXPECT_NEAR(c.x0, 0.15, 1e-9);
  EXPECT_NEAR(c.x1, 0.85, 1e-9);
  EXPECT_NEAR(c.y0, 0.5175 - 0.35, 1e-9);
  EXPECT_NEAR(c.y1, 0.5175 + 0.35, 1e-9);
}

TEST(Figures, BoxesStandWhereTheLabelsSay) {
  test::TempDir d;
  test::write_figure_study(d, false);  // grey placeholders: only boxes carry colour
  const std::string out = d / "pairs.png";
  const double dpi = 288;  // 4 px per point
  const auto r =
      test::run_ipd("figure pairs " + d.path() + " --scene s1 --layers gt,pred,pairs --dpi 288 --out " + out);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const cv::Mat img = cv::imread(out, cv::IMREAD_COLOR);
  ASSERT_FALSE(img.empty());
  EXPECT_EQ(img.cols, 1008);  // 3.5 in x 288 dpi
  // The same layout, computed in points.
  const StudyLabels labels = load_labels(open_study(d.path()));
  const ui::SceneFigureInput in = ui::scene_input_from_study(labels, "real", "synth", "det", "s1", 0, {});
  ui::FigureOptions o;
  o.layers = ui::parse_layers("gt,pred,pairs");
  const ui::FontMetrics metrics(ui::default_font_file());
  ui::DisplayList fig(metrics);
  const ui::PairsLayout l = ui::draw_pairs_figure(fig, in, o);
  EXPECT_EQ(img.rows, static_cast<int>(std::ceil(fig.height_pt * dpi / 72)));
  // Whether a colour appears within 2 pixels of where the label puts a (vertical) edge, or up to 8 pixels
  // along it: predictions are dashed (a dash and its gap: 3.6 pt, 14 pixels).
  auto colour_near = [&](const ui::PtRect& panel, double x, double y, int r, int g, int b) {
    const double px = (panel.x0 + x * panel.width()) * dpi / 72, py = (panel.y0 + y * panel.height()) * dpi / 72;
    for (int dy = -8; dy <= 8; ++dy)
      for (int dx = -2; dx <= 2; ++dx)
        if (near(img.at<cv::Vec3b>(static_cast<int>(py) + dy, static_cast<int>(px) + dx), r, g, b)) return true;
    return false;
  };
  // Left GT box: left edge x = 0.20 (yellow); its prediction's right edge x = 0.45 (blue); inside, neither.
  EXPECT_TRUE(colour_near(l.left, 0.20, 0.40, 240, 228, 66));
  EXPECT_TRUE(colour_near(l.left, 0.45, 0.45, 0, 114, 178));
  EXPECT_FALSE(colour_near(l.left, 0.33, 0.45, 240, 228, 66));
  EXPECT_FALSE(colour_near(l.left, 0.33, 0.45, 0, 114, 178));
  // The unpaired second rock is grey (left edge x = 0.70), and there is no box there on the right.
  EXPECT_TRUE(colour_near(l.left, 0.70, 0.70, 175, 175, 175));
  EXPECT_FALSE(colour_near(l.right, 0.70, 0.70, 175, 175, 175));
  // Right: GT left edge x = 0.20 (yellow), prediction right edge x = 0.42 (blue).
  EXPECT_TRUE(colour_near(l.right, 0.20, 0.40, 240, 228, 66));
  EXPECT_TRUE(colour_near(l.right, 0.42, 0.45, 0, 114, 178));
}

// Fig. 2 with a misalignment smaller than a GT ring (about 2 pt on the page): the green pair line must still
// show between the dot and the ring (drawn over the rings with a white halo, under small dots).
TEST(Figures, ShortPairLinesStayVisibleInTheRegistrationFigure) {
  ui::SceneFigureInput in;
  in.stem = "s", in.a = "real", in.b = "synth", in.method = "consensus";
  in.image_w = 1000, in.image_h = 1000;
  in.gt_a = {Box{0, 0.5, 0.5, 0.05, 0.05}};
  in.gt_b = {Box{0, 0.5125, 0.5, 0.05, 0.05}};  // 0.0125 of a ~118 pt panel: 1.5 pt to the right
  in.pairs = {{0, 0}};
  ui::FigureOptions o;
  o.layers = ui::parse_layers("gt,pairs");
  const ui::FontMetrics metrics(ui::default_font_file());
  ui::DisplayList fig(metrics);
  ui::draw_registration_figure(fig, in, o);
  const std::string png = ui::render_figure_file(fig, metrics, ui::FigureFormat::kPng, 288);  // 4 px per pt
  const cv::Mat img = cv::imdecode(std::vector<uchar>(png.begin(), png.end()), cv::IMREAD_COLOR);
  ASSERT_FALSE(img.empty());
  int green = 0;
  for (int y = 0; y < img.rows; ++y)
    for (int x = 0; x < img.cols; ++x) green += near(img.at<cv::Vec3b>(y, x), 40, 160, 80);
  // Two panels (identity affine: the same picture twice), each with ~0.6 pt x 0.9 pt of stroke between dot
  // and ring: 12 px at 4 px/pt. Lines drawn under the rings and the old 1.3 pt dots left 4 px.
  EXPECT_GT(green, 8);
}

// The raster path's font atlas holds every character the figure prints: the compare figure's title starts
// with "Δ" (U+0394), which ImGui's Latin-1 atlas drew as "?". Its first glyph must look like poppler's
// rendering of the same figure's PDF (dark-pixel masks overlap by 0.64 for Δ; "?" gave 0.19).
TEST(Figures, RasterFiguresDrawEveryCharacterOfTheirText) {
  test::TempDir d;
  test::write_small_demo_study(d);
  ASSERT_EQ(test::run_ipd("figure compare " + d.path() + " --dpi 288 --out " + d / "c.png").exit_code, 0);
  ASSERT_EQ(test::run_ipd("figure compare " + d.path() + " --out " + d / "c.pdf").exit_code, 0);
  ASSERT_EQ(test::run_command("pdftoppm -r 288 -png -singlefile '" + d / "c.pdf" + "' '" + d / "p" + "'").exit_code, 0);
  // 8 x 11 pt at 4 px/pt from (3, 3) pt: the title's first letter, inside the 4 pt margin.
  const cv::Rect first_glyph(12, 12, 32, 44);
  const cv::Mat a = cv::imread(d / "c.png", cv::IMREAD_GRAYSCALE)(first_glyph) < 128;
  const cv::Mat b = cv::imread(d / "p.png", cv::IMREAD_GRAYSCALE)(first_glyph) < 128;
  const double both = cv::countNonZero(a & b), either = cv::countNonZero(a | b);
  ASSERT_GT(either, 100);
  EXPECT_GT(both / either, 0.5);
}

TEST(Figures, ClearMessagesAndNoFileOnError) {
  test::TempDir d, empty;
  test::write_figure_study(d, false);
  auto r = test::run_ipd("figure pairs " + d.path() + " --scene nope --out " + d / "x.png");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_EQ(r.err, "error: " + d.path() + ": no scene 'nope' in both 'real' and 'synth'\n");
  EXPECT_FALSE(fs::exists(d / "x.png"));
  test::write_text(empty / "real/labels/a.txt", "");
  test::write_text(empty / "synth/labels/b.txt", "");
  r = test::run_ipd("figure registration " + empty.path() + " --out " + empty / "x.pdf");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_EQ(r.err, "error: " + empty.path() + ": no scene is present in both 'real' and 'synth'\n");
  r = test::run_ipd("figure table " + empty / "missing" + " --out " + empty / "x.png");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_EQ(r.err, "error: " + empty / "missing" + ": no such study directory\n");
  // Bad option values are usage errors (2) naming what is accepted.
  r = test::run_ipd("figure pairs " + d.path() + " --layers gt,boxes --out " + d / "x.pdf");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.err,
            "error: --layers: unknown layer 'boxes' (accepted: gt, pred, conf, indices, pairs, legend, "
            "comma-separated)\n");
  r = test::run_ipd("figure pairs " + d.path() + " --crop 0.5,0,0.2,1 --out " + d / "x.pdf");
  EXPECT_EQ(r.exit_code, 2);
  r = test::run_ipd("figure pairs " + d.path() + " --font-pt 5 --out " + d / "x.pdf");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.err, "error: --font-pt: 5 is outside 6..72 (nothing smaller than 6 pt on the page)\n");
  // A width of 0 or -3 drew the default column width without a word, while 0.01 was refused.
  for (const char* width : {"0", "-3", "0.01"}) {
    r = test::run_ipd("figure pairs " + d.path() + " --width-in " + width + " --out " + d / "x.pdf");
    EXPECT_EQ(r.exit_code, 2) << width;
    EXPECT_EQ(r.err, "error: --width-in: " + std::string(width) + " is not a figure width (1 to 40 inches)\n");
  }
  r = test::run_ipd("figure pairs " + d.path() + " --font " + d / "nope.ttf" + " --out " + d / "x.pdf");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_EQ(r.err, "error: " + d / "nope.ttf" + ": no such font file\n");
  // A path that exists but is no regular file was "no such font file" too: what is there is named.
  r = test::run_ipd("figure pairs " + d.path() + " --font /dev/zero --out " + d / "x.pdf");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_EQ(r.err, "error: /dev/zero: is a character device, not a font file (expected a TrueType or OpenType font)\n");
  r = test::run_ipd("figure pairs " + d.path() + " --font " + d.path() + " --out " + d / "x.pdf");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_EQ(r.err, "error: " + d.path() + ": is a directory, not a font file (expected a TrueType or OpenType font)\n");
  EXPECT_FALSE(fs::exists(d / "x.pdf"));
  // --out into a folder that does not exist: a usage error naming it, nothing created; --mkdir creates it.
  r = test::run_ipd("figure table " + d.path() + " --out " + d / "figs/t.png");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.err, "error: --out " + d / "figs/t.png" + ": the folder '" + d / "figs" +
                       "' does not exist (create it, or pass --mkdir)\n");
  EXPECT_FALSE(fs::exists(d / "figs"));
  r = test::run_ipd("figure pairs " + d.path() + " --out " + d / "study.yaml/x.pdf");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.err, "error: --out " + d / "study.yaml/x.pdf" + ": '" + d / "study.yaml" + "' is not a folder\n");
  // A successful run leaves the figure and nothing else (no temp files).
  r = test::run_ipd("figure table " + d.path() + " --mkdir --out " + d / "figs/t.png");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  int files = 0;
  for (const auto& e : fs::directory_iterator(d / "figs")) files += e.is_regular_file();
  EXPECT_EQ(files, 1);
}

TEST(Figures, DefaultSceneIsTheLargestContribution) {
  test::TempDir d;
  test::write_figure_study(d, false);
  // A second scene where both sides agree (contributes 0).
  test::write_text(d / "real/labels/s0.txt", "0 0.5 0.5 0.2 0.2\n");
  test::write_text(d / "synth/labels/s0.txt", "0 0.5 0.5 0.2 0.2\n");
  test::write_text(d / "real/predictions/det/s0.txt", "0 0.5 0.5 0.2 0.2 0.9\n");
  test::write_text(d / "synth/predictions/det/s0.txt", "0 0.5 0.5 0.2 0.2 0.9\n");
  const auto r = test::run_ipd("figure pairs " + d.path() + " --dpi 72 --out " + d / "p.png");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err, "scene s1: it contributes most to IPD(real, synth) for det\n");
}

TEST(Figures, DefaultSceneIsChosenAtTheFiguresConfidence) {
  test::TempDir d;
  test::write_figure_study(d, false);
  // s0 agrees at every threshold up to 0.3 (diff 0); above it, its real detection is hidden: perf 0 vs 1, a
  // larger contribution than s1's |0.6 - 0.818| = 0.218.
  test::write_text(d / "real/labels/s0.txt", "0 0.5 0.5 0.2 0.2\n");
  test::write_text(d / "synth/labels/s0.txt", "0 0.5 0.5 0.2 0.2\n");
  test::write_text(d / "real/predictions/det/s0.txt", "0 0.5 0.5 0.2 0.2 0.3\n");
  test::write_text(d / "synth/predictions/det/s0.txt", "0 0.5 0.5 0.2 0.2 0.9\n");
  auto r = test::run_ipd("figure pairs " + d.path() + " --dpi 72 --out " + d / "p.png");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err, "scene s1: it contributes most to IPD(real, synth) for det\n");
  r = test::run_ipd("figure pairs " + d.path() + " --conf 0.5 --dpi 72 --out " + d / "p.png");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err, "scene s0: it contributes most to IPD(real, synth) for det at conf \u2265 0.5\n");
}

}  // namespace
}  // namespace ipd
