// A journal's production check on the figures, measured on the PDFs as a production editor would (pdftotext
// -bbox, pdftoppm at 288 dpi): every text at least 7 pt at the defaults, a pair's number on both pictures
// or on neither (demo, a 60-rock 1936 x 1216 study, a POLAR-Sim layout), boxes that survive greyscale print
// and deuteranopia, a no-picture notice that covers no label, footnotes that suggest what helps.
#include <gtest/gtest.h>

#include <iostream>

#include <fmt/format.h>
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <regex>
#include <set>

#include "core/demo/demo_study.h"
#include "core/study/study.h"
#include "tests/support/figure_test_study.h"
#include "tests/support/pdf_text.h"
#include "tests/support/test_support.h"
#include "ui/figures/figure_input.h"
#include "ui/figures/figure_scene.h"

namespace ipd {
namespace {

using test::PdfText;
using test::Word;

// DejaVu Sans' line box over its em size: pdftotext's word height is the line box.
constexpr double kLineOverEm = 1.1641;
double size_pt(const Word& w) { return (w.y1 - w.y0) / kLineOverEm; }

PdfText figure(const test::TempDir& d, const std::string& args, const std::string& name) {
  const std::string out = d / name;
  const auto r = test::run_ipd("figure " + args + " --out " + out);
  EXPECT_EQ(r.exit_code, 0) << args << ": " << r.err;
  return test::pdf_text(out);
}

TEST(FigurePrint, EveryTextIsAtLeast7PtAtTheDefaults) {
  test::TempDir d;
  DemoStudyOptions demo;
  demo.scenes = 3;
  write_demo_study(d.path(), demo);
  for (const std::string kind : {"pairs", "registration", "table", "compare", "distribution", "breakdown"})
    for (const std::string column : {"single", "double"}) {
      std::vector<std::string> extra = {""};
      if (kind == "pairs") extra.push_back(" --layers gt,pred,conf,indices,pairs,legend");
      if (kind == "table") extra.push_back(" --ci");
      for (const std::string& e : extra) {
        const PdfText t = figure(d, kind + " " + d.path() + " --column " + column + e, kind + column + ".pdf");
        ASSERT_FALSE(t.words.empty()) << kind << " " << column << e;
        for (const Word& w : t.words)
          EXPECT_GE(size_pt(w), 7 - 0.01)
              << kind << " " << column << e << ": '" << w.text << "' " << size_pt(w) << " pt";
      }
    }
  // Smaller only when asked: --font-pt 6 gives 6 pt footnotes.
  const PdfText t =
      figure(d, "pairs " + d.path() + " --font-pt 6 --layers gt,pred,conf,indices,pairs,legend", "small.pdf");
  double smallest = 99;
  for (const Word& w : t.words) smallest = std::min(smallest, size_pt(w));
  EXPECT_NEAR(smallest, 6, 0.01);
}

// The pair numbers shown on each picture of a pairs or registration figure (digit-only words between the
// left caption and the legend), and the footnote's count of unnumbered pairs. The pictures are side by side
// (split at the page's middle) or stacked (split at the second picture's caption `b`, at the left margin).
struct ShownNumbers {
  std::multiset<int> left, right;
  int pairs = -1, unnumbered = 0;
  bool stacked = false;
};
ShownNumbers shown_numbers(const PdfText& t, const std::string& a, const std::string& b) {
  ShownNumbers s;
  double top = 0, bottom = t.height, split_y = 0;
  for (const Word& w : t.words)
    if (w.text == a && top == 0) top = w.y1;  // the left caption
  for (const Word& w : t.words)
    if (w.text == "GT" && w.y0 > top) bottom = std::min(bottom, w.y0);  // the legend's first entry
  for (const Word& w : t.words)
    if (w.text == b && w.y0 > top && w.x0 < 10) s.stacked = true, split_y = w.y0;
  for (const Word& w : t.words)
    if (w.y0 >= top && w.y1 <= bottom && !w.text.empty() &&
        std::all_of(w.text.begin(), w.text.end(), [](char c) { return std::isdigit(static_cast<unsigned char>(c)); }))
      ((s.stacked ? w.y0 < split_y : w.x0 < t.width / 2) ? s.left : s.right).insert(std::stoi(w.text));
  std::smatch m;
  const std::string all = t.all();
  if (std::regex_search(all, m, std::regex("\\((\\d+) pairs?\\)"))) s.pairs = std::stoi(m[1]);
  if (std::regex_search(all, m,
                        std::regex("(\\d+) pairs? unnumbered: no room for (its|their) number on both pictures "
                                   "\\(to show (it|them): --crop, fewer --layers or ")))
    s.unnumbered = std::stoi(m[1]);
  return s;
}

void expect_pairs_on_both_sides(const test::TempDir& d, const std::string& scene_args, const std::string& a,
                                int min_numbered, const std::string& b = "synth") {
  for (const std::string kind : {"pairs", "registration"})
    for (const std::string column : {"single", "double"})
      for (const std::string layers : {"", " --layers gt,pred,conf,indices,pairs,legend"}) {
        const std::string at = kind + " " + column + layers;
        const PdfText t = figure(d, kind + " " + d.path() + scene_args + " --column " + column + layers, "p.pdf");
        const ShownNumbers s = shown_numbers(t, kind == "pairs" ? a : "before", kind == "pairs" ? b : "after");
        ASSERT_GT(s.pairs, 0) << at << ": " << t.all();
        EXPECT_EQ(s.left, s.right) << at << ": a pair's number on one picture only";
        // Each pair once per side; the unnumbered ones are counted in the footnote.
        EXPECT_EQ(std::set<int>(s.left.begin(), s.left.end()).size(), s.left.size()) << at;
        EXPECT_EQ(int(s.left.size()) + s.unnumbered, s.pairs) << at << ": " << t.all();
        EXPECT_GE(int(s.left.size()), min_numbered) << at;
        if (column == "double") {
          EXPECT_EQ(t.all().find("--column double"), std::string::npos) << at << ": " << t.all();
        }
      }
}

// The 60-rock 1936 x 1216 labels-only study: before, 89 numbers were dropped independently on each side
// (12, 13, 19 only on the left, 8, 18, 35, 36, 58 only on the right). Fig. 2 (registration) likewise.
TEST(FigurePrint, APairsNumberShowsOnBothPicturesOrNeitherIn60RockScenes) {
  test::TempDir d;
  DemoStudyOptions demo;
  demo.scenes = 2;
  demo.min_rocks = demo.max_rocks = 60;
  demo.width = 1936, demo.height = 1216;
  demo.labels_only = true;
  write_demo_study(d.path(), demo);
  expect_pairs_on_both_sides(d, "", "real", 5, "principled");
}

TEST(FigurePrint, APairsNumberShowsOnBothPicturesOrNeitherInTheDemo) {
  test::TempDir d;
  DemoStudyOptions demo;
  demo.scenes = 3;
  write_demo_study(d.path(), demo);
  expect_pairs_on_both_sides(d, " --scene scene_02", "real", 9, "principled");
}

// A real layout: POLAR-Sim terrain 04, camera B, the same view under two sun azimuths (60 and 58 boxes),
// predictions the GT boxes shifted a little.
TEST(FigurePrint, APairsNumberShowsOnBothPicturesOrNeitherOnAPolarSimLayout) {
  namespace fs = std::filesystem;
  const fs::path root = fs::path(IPD_SHARED_DATA) / "labels/Terrain04";
  if (!fs::exists(root / "04_B_on_350_R_1024.txt")) GTEST_SKIP() << "POLAR-Sim labels not found under " << root;
  test::TempDir d;
  test::write_text(d / "study.yaml",
                   "domains: [real, synth]\nimage_size: [1936, 1216]\nmodels: {det: {trained_on: real}}\n");
  const std::pair<const char*, const char*> sides[] = {{"real", "04_B_on_350_R_1024.txt"},
                                                       {"synth", "04_B_on_30_R_1024.txt"}};
  for (const auto& [domain, file] : sides) {
    std::ifstream in(root / file);
    std::string labels, predictions;
    int cls = 0;
    double cx, cy, w, h;
    for (int k = 0; in >> cls >> cx >> cy >> w >> h; ++k) {
      if (cls != 0) continue;
      labels += fmt::format("0 {} {} {} {}\n", cx, cy, w, h);
      predictions += fmt::format("0 {} {} {} {} {:.2f}\n", cx + 0.2 * w, cy, w, h, 0.5 + 0.01 * (k % 40));
    }
    test::write_text(d / (std::string(domain) + "/labels/s.txt"), labels);
    test::write_text(d / (std::string(domain) + "/predictions/det/s.txt"), predictions);
  }
  expect_pairs_on_both_sides(d, "", "real", 5);
}

// The unnumbered pairs a scene figure's footnote counts ("15 pairs unnumbered: ..."), 0 without one.
int unnumbered_pairs(const PdfText& t) {
  std::smatch m;
  const std::string all = t.all();
  return std::regex_search(all, m, std::regex("([0-9]+) pairs? unnumbered")) ? std::stoi(m[1]) : 0;
}

// A dense real layout at one column: POLAR-Sim terrain 04, camera A, left, under sun 180 and sun 30 (28 rocks
// each, 28 pairs), predictions the GT boxes shifted by a fifth of their width. Side by side, each picture is
// 120 pt wide and about half the pairs go unnumbered; the figure then stacks the pictures (each 244 pt wide)
// and numbers at least 80% of the pairs, in the pairs and the registration figure, with or without --crop auto.
TEST(FigurePrint, APolarViewAtOneColumnNumbersFourFifthsOfItsPairs) {
  namespace fs = std::filesystem;
  const fs::path root = fs::path(IPD_SHARED_DATA) / "labels/Terrain04";
  if (!fs::exists(root / "04_A_off_180_L_1024.txt"))
    GTEST_SKIP() << "POLAR-Sim labels not found under " << root << " (../shared/data/polar-sim): not measured";
  test::TempDir d;
  test::write_text(d / "study.yaml",
                   "domains: [real, synth]\nimage_size: [1936, 1216]\nmodels: {det: {trained_on: real}}\n");
  const std::pair<const char*, const char*> sides[] = {{"real", "04_A_off_180_L_1024.txt"},
                                                       {"synth", "04_A_off_30_L_1024.txt"}};
  for (const auto& [domain, file] : sides) {
    std::ifstream in(root / file);
    std::string labels, predictions;
    int cls = 0, rocks = 0;
    double cx, cy, w, h;
    for (int k = 0; in >> cls >> cx >> cy >> w >> h; ++k) {
      if (cls != 0) continue;
      ++rocks;
      labels += fmt::format("0 {} {} {} {}\n", cx, cy, w, h);
      predictions += fmt::format("0 {} {} {} {} {:.2f}\n", cx + 0.2 * w, cy, w, h, 0.5 + 0.01 * (k % 40));
    }
    ASSERT_EQ(rocks, 28) << file;
    test::write_text(d / (std::string(domain) + "/labels/s.txt"), labels);
    test::write_text(d / (std::string(domain) + "/predictions/det/s.txt"), predictions);
  }
  for (const std::string kind : {"pairs", "registration"}) {
    const PdfText title = figure(d, kind + " " + d.path() + " --panels side", kind + "_side.pdf");
    ASSERT_NE(title.all().find("(28 pairs)"), std::string::npos) << title.all();
    const int side = unnumbered_pairs(title);
    EXPECT_GT(side, 28 / 5) << kind << ": side by side numbers more than 80% already";
    for (const std::string crop : {"", " --crop auto"}) {
      const PdfText t = figure(d, kind + " " + d.path() + crop, kind + "_auto.pdf");
      const int unnumbered = unnumbered_pairs(t);
      EXPECT_LE(unnumbered, 28 / 5) << kind << crop << ": " << 28 - unnumbered << " of 28 pairs numbered";
      std::cout << "[ measured ] " << kind << crop << " at one column: " << 28 - unnumbered
                << " of 28 pairs numbered (side by side: " << 28 - side << ")\n";
      EXPECT_NEAR(t.width, 252, 1.0);
      EXPECT_TRUE(test::overlapping(t).empty()) << kind << crop << ": " << test::overlapping(t).front();
    }
  }
}

// Labels-only pictures carry a "no picture" notice: no label may sit on it (4 overlaps in one 60-rock scene).
TEST(FigurePrint, TheNoPictureNoticeCoversNoLabel) {
  test::TempDir d;
  DemoStudyOptions demo;
  demo.scenes = 2;
  demo.min_rocks = demo.max_rocks = 60;
  demo.labels_only = true;
  write_demo_study(d.path(), demo);
  for (const std::string column : {"single", "double"}) {
    const PdfText t =
        figure(d, "pairs " + d.path() + " --column " + column + " --layers gt,pred,conf,indices,pairs,legend", "n.pdf");
    int notices = 0;
    for (const Word& n : t.words) {
      if (n.text != "picture") continue;
      ++notices;
      for (const Word& w : t.words)
        if (&w != &n && w.text != "no" && w.x0 < n.x1 && n.x0 < w.x1 && w.y0 < n.y1 && n.y0 < w.y1)
          ADD_FAILURE() << column << ": '" << w.text << "' on the no-picture notice";
    }
    EXPECT_EQ(notices, 2) << column;
    EXPECT_TRUE(test::overlapping(t).empty()) << column << ": " << test::overlapping(t).front();
  }
}

// The notice goes where it crosses no rock: the top middle when it is clear, else the bottom middle, else the
// first clear corner; panel 100 x 60 pt, notice 30 x 6 pt, 2 pt inside the edge.
TEST(FigurePrint, TheNoPictureNoticeIsPlacedOffTheRocks) {
  const ui::PtRect panel{0, 0, 100, 60};
  const ui::Pt size{30, 6};
  auto at = [&](const std::vector<ui::PtRect>& boxes) {
    const ui::PtRect r = ui::place_notice(panel, size, boxes, 2);
    return fmt::format("{} {} {} {}", r.x0, r.y0, r.x1, r.y1);
  };
  EXPECT_EQ(at({}), "35 2 65 8");                                // (100 - 30) / 2 = 35, 2 below the top
  EXPECT_EQ(at({{30, 0, 70, 20}}), "35 52 65 58");               // a rock at the top middle: the bottom middle
  EXPECT_EQ(at({{33, 0, 67, 60}}), "2 2 32 8");                  // a column of rocks in the middle: top left
  EXPECT_EQ(at({{33, 0, 67, 60}, {0, 0, 32, 9}}), "68 2 98 8");  // and one at top left: top right
  // Rocks everywhere: the place that covers the least of them (top left: 2 x 6 of the wide box only).
  EXPECT_EQ(at({{30, 0, 100, 60}, {0, 9, 30, 60}}), "2 2 32 8");
}

TEST(FigurePrint, FootnotesSuggestOnlyWhatHelps) {
  test::TempDir d;
  DemoStudyOptions demo;
  demo.scenes = 40;
  demo.labels_only = true;
  write_demo_study(d.path(), demo);
  for (const std::string column : {"single", "double"}) {
    const PdfText t = figure(d, "distribution " + d.path() + " --column " + column, "dist.pdf");
    EXPECT_EQ(t.all().find("--crop"), std::string::npos) << column << ": " << t.all();  // no pictures to crop
    if (column == "double") {
      EXPECT_EQ(t.all().find("--column double"), std::string::npos) << t.all();
    }
  }
}

// --- Greyscale and colour vision -------------------------------------------------------------------------

// Machado et al. (2009) deuteranopia, severity 1, applied to linear RGB.
cv::Mat deuteranopia(const cv::Mat& bgr) {
  cv::Mat out = bgr.clone();
  const auto lin = [](double v) {
    v /= 255;
    return v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4);
  };
  const auto srgb = [](double v) {
    v = std::clamp(v, 0.0, 1.0);
    return 255 * (v <= 0.0031308 ? 12.92 * v : 1.055 * std::pow(v, 1 / 2.4) - 0.055);
  };
  for (int y = 0; y < out.rows; ++y)
    for (int x = 0; x < out.cols; ++x) {
      cv::Vec3b& p = out.at<cv::Vec3b>(y, x);
      const double r = lin(p[2]), g = lin(p[1]), b = lin(p[0]);
      p = cv::Vec3b(cv::saturate_cast<uchar>(srgb(-0.011820 * r + 0.042940 * g + 0.968881 * b)),
                    cv::saturate_cast<uchar>(srgb(0.280085 * r + 0.672501 * g + 0.047413 * b)),
                    cv::saturate_cast<uchar>(srgb(0.367322 * r + 0.860646 * g - 0.227968 * b)));
    }
  return out;
}

cv::Mat grey(const cv::Mat& bgr) {
  cv::Mat g;
  cv::cvtColor(bgr, g, cv::COLOR_BGR2GRAY);
  return g;
}

// Along a vertical box edge at page x `x_pt`, from `y0_pt` to `y1_pt`: how far the stroke (and its halo,
// within 1.5 pt of the edge) stands out from the terrain 4 to 7 pt outside (`outside`: -1 left, +1 right),
// as the 95th percentile of |grey - terrain median|; and the share of the edge's rows with ink (a stroke or
// its halo 40 grey levels off the terrain).
struct EdgeContrast {
  double contrast = 0, inked = 0;
};
EdgeContrast edge_contrast(const cv::Mat& g, double x_pt, double y0_pt, double y1_pt, int outside) {
  const double px = 4;  // 288 dpi
  std::vector<int> terrain, diff;
  const int ex = int(std::lround(x_pt * px));
  for (int y = int(y0_pt * px); y < int(y1_pt * px); ++y)
    for (int x = ex + outside * int(4 * px); x != ex + outside * int(7 * px); x += outside)
      terrain.push_back(g.at<uchar>(y, x));
  std::nth_element(terrain.begin(), terrain.begin() + terrain.size() / 2, terrain.end());
  const int t = terrain[terrain.size() / 2];
  int on = 0, n = 0;
  for (int y = int(y0_pt * px); y < int(y1_pt * px); ++y) {
    bool inked = false;
    for (int x = ex - int(1.5 * px); x <= ex + int(1.5 * px); ++x) {
      diff.push_back(std::abs(g.at<uchar>(y, x) - t));
      inked |= diff.back() > 40;
    }
    on += inked, ++n;
  }
  std::sort(diff.begin(), diff.end());
  return {double(diff[diff.size() * 95 / 100]), double(on) / n};
}

// One GT box and one prediction a side, on dark terrain (left: grey 95) and bright terrain (right: grey
// 200), drawn one layer at a time; each box edge, in greyscale and simulated deuteranopia, stands out from
// the terrain by 80 grey levels or more (red predictions on grey terrain: about 25, pink GT: about 45), GT
// is solid and a prediction dashed.
TEST(FigurePrint, BoxesSurviveGreyscaleAndDeuteranopia) {
  test::TempDir d;
  test::write_figure_study(d, true);
  cv::Mat bright(400, 640, CV_8UC3, cv::Scalar(200, 200, 200));
  cv::imwrite(d / "synth/images/s1.png", bright);
  const StudyLabels labels = load_labels(open_study(d.path()));
  const ui::SceneFigureInput in = ui::scene_input_from_study(labels, "real", "synth", "det", "s1", 0, {});
  for (const std::string layer : {"gt", "pred"}) {
    const std::string pdf = d / (layer + ".pdf");
    ASSERT_EQ(test::run_ipd("figure pairs " + d.path() + " --scene s1 --layers " + layer + " --out " + pdf).exit_code,
              0);
    ASSERT_EQ(test::run_command("pdftoppm -r 288 -png -singlefile '" + pdf + "' '" + pdf + "'").exit_code, 0);
    const cv::Mat img = cv::imread(pdf + ".png", cv::IMREAD_COLOR);
    ASSERT_FALSE(img.empty());
    ui::FigureOptions o;
    o.layers = ui::parse_layers(layer);
    const ui::FontMetrics metrics(ui::default_font_file());
    ui::DisplayList fig(metrics);
    const ui::PairsLayout l = ui::draw_pairs_figure(fig, in, o);
    for (int side = 0; side < 2; ++side) {
      const ui::PtRect& p = side == 0 ? l.left : l.right;
      // GT: left edge x = 0.20 (terrain to the left); prediction: right edge x = 0.45 / 0.42 (to the right).
      const double x = layer == "gt" ? 0.20 : side == 0 ? 0.45 : 0.42;
      const double x_pt = p.x0 + x * p.width(), y0 = p.y0 + 0.32 * p.height(), y1 = p.y0 + 0.48 * p.height();
      for (const bool cvd : {false, true}) {
        const std::string at = layer + (side == 0 ? " on dark" : " on bright") + (cvd ? ", deuteranopia" : ", grey");
        const EdgeContrast e = edge_contrast(grey(cvd ? deuteranopia(img) : img), x_pt, y0, y1, layer == "gt" ? -1 : 1);
        EXPECT_GE(e.contrast, 80) << at;
        if (layer == "gt") {
          EXPECT_GT(e.inked, 0.95) << at << ": solid";
        } else {
          EXPECT_LT(e.inked, 0.8) << at << ": dashed";
          EXPECT_GT(e.inked, 0.3) << at << ": dashed";
        }
      }
    }
  }
}

// The marks of a figure as drawn: filled circles (dots), stroked circles (rings) and lines, in points.
class MarkRecorder : public ui::Canvas {
 public:
  struct Mark {
    ui::Pt a, b;  // a circle's centre (b unused) or a line's ends
    double radius = 0;
    ui::Colour colour;
  };
  std::vector<Mark> dots, rings, lines;
  void rect(const ui::PtRect&, ui::Colour, double) override {}
  void fill_rect(const ui::PtRect&, ui::Colour) override {}
  void line(ui::Pt a, ui::Pt b, ui::Colour c, double) override { lines.push_back({a, b, 0, c}); }
  void polyline(const std::vector<ui::Pt>&, ui::Colour, double, bool) override {}
  void circle(ui::Pt c, double r, ui::Colour col, double) override { rings.push_back({c, {}, r, col}); }
  void fill_circle(ui::Pt c, double r, ui::Colour col) override { dots.push_back({c, {}, r, col}); }
  void text(ui::Pt, ui::Anchor, const ui::TextStyle&, const std::string&) override {}
  void image(const ui::FigurePicture&, const ui::PtRect&) override {}
  void push_clip(const ui::PtRect&) override {}
  void pop_clip() override {}
  ui::Pt measure(const ui::TextStyle&, const std::string&) override { return {}; }
};

// The largest grey-level distance from the panel's grey 248 over the pixels of a short segment (page points,
// 288 dpi): a stroke anywhere on it counts, anti-aliased or not.
int ink_on(const cv::Mat& g, ui::Pt from, ui::Pt to) {
  int best = 0;
  for (int k = 0; k <= 16; ++k) {
    const double x = (from.x + (to.x - from.x) * k / 16) * 4, y = (from.y + (to.y - from.y) * k / 16) * 4;
    best = std::max(best, std::abs(int(g.at<uchar>(int(std::lround(y)), int(std::lround(x)))) - 248));
  }
  return best;
}

// The registration figure has no picture under its marks: blue dots (rocks of A), pink rings (rocks of B)
// and green pair lines on a light grey panel. Each must stay visible printed in grey and seen with
// deuteranopia: 60 grey levels or more from the panel (pink, the lightest, is about 88 in grey and 78 with
// deuteranopia; a pastel or yellow would be 10 to 30).
TEST(FigurePrint, RegistrationMarksSurviveGreyscaleAndDeuteranopia) {
  test::TempDir d;
  test::write_text(d / "study.yaml",
                   "domains: [real, synth]\nimage_size: [640, 400]\nmodels: {det: {trained_on: real}}\n");
  // Three rocks, the synthetic twin's 0.08 to the right: in the "before" panel each pair line is longer than
  // a ring's radius, so its middle is clear of both marks.
  test::write_text(d / "real/labels/s1.txt", "0 0.20 0.30 0.05 0.05\n0 0.60 0.50 0.05 0.05\n0 0.40 0.75 0.05 0.05\n");
  test::write_text(d / "synth/labels/s1.txt", "0 0.28 0.30 0.05 0.05\n0 0.68 0.50 0.05 0.05\n0 0.48 0.75 0.05 0.05\n");
  const std::string pdf = d / "reg.pdf";
  const auto r = test::run_ipd("figure registration " + d.path() + " --scene s1 --layers gt,pairs --out " + pdf);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  ASSERT_EQ(test::run_command("pdftoppm -r 288 -png -singlefile '" + pdf + "' '" + pdf + "'").exit_code, 0);
  const cv::Mat img = cv::imread(pdf + ".png", cv::IMREAD_COLOR);
  ASSERT_FALSE(img.empty());

  const Study study = open_study(d.path());
  const StudyLabels labels = load_labels(study);
  RegistrationOptions reg = study.config.registration;
  reg.aspect = study.aspect();
  const ui::SceneFigureInput in = ui::scene_input_from_study(labels, "real", "synth", "det", "s1", 0, reg);
  ASSERT_EQ(in.pairs.size(), 3u);
  ui::FigureOptions o;
  o.layers = ui::parse_layers("gt,pairs");
  const ui::FontMetrics metrics(ui::default_font_file());
  ui::DisplayList fig(metrics);
  ui::draw_registration_figure(fig, in, o);
  MarkRecorder marks;
  fig.replay(marks);
  ASSERT_EQ(marks.dots.size(), 6u);   // three rocks of A per panel
  ASSERT_EQ(marks.rings.size(), 6u);  // three rocks of B per panel
  // The "before" panel is drawn first: its first three dots, rings and green lines (each line twice: a white
  // halo, then the line).
  std::vector<MarkRecorder::Mark> green;
  for (const auto& l : marks.lines)
    if (l.colour.g > l.colour.r + 50) green.push_back(l);
  ASSERT_GE(green.size(), 3u);
  for (const bool cvd : {false, true}) {
    const cv::Mat g = grey(cvd ? deuteranopia(img) : img);
    const std::string seen = cvd ? "deuteranopia" : "grey";
    for (int k = 0; k < 3; ++k) {
      const auto& dot = marks.dots[k];
      EXPECT_GE(ink_on(g, dot.a, dot.a), 60) << "dot " << k << ", " << seen;
      // A ring's top, where no pair line passes (the lines run to the right).
      const auto& ring = marks.rings[k];
      const ui::Pt top{ring.a.x, ring.a.y - ring.radius};
      EXPECT_GE(ink_on(g, {top.x, top.y - 0.4}, {top.x, top.y + 0.4}), 60) << "ring " << k << ", " << seen;
      const ui::Pt mid{(green[k].a.x + green[k].b.x) / 2, (green[k].a.y + green[k].b.y) / 2};
      EXPECT_GE(ink_on(g, {mid.x, mid.y - 0.3}, {mid.x, mid.y + 0.3}), 60) << "line " << k << ", " << seen;
    }
  }
}

}  // namespace
}  // namespace ipd
