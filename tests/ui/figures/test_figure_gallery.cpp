// `ipd figure gallery`: the worst |diff| rock pairs of a study, chosen and ordered as the studio's gallery,
// drawn as crops with their GT box, best prediction and performance values.
#include <gtest/gtest.h>

#include <fmt/format.h>
#include <cmath>
#include <filesystem>
#include <opencv2/imgcodecs.hpp>
#include <set>
#include <tuple>

#include "core/ipd/ipd.h"
#include "core/study/study.h"
#include "tests/support/pdf_text.h"
#include "tests/support/test_support.h"
#include "ui/figures/figure_common.h"
#include "ui/figures/figure_gallery.h"

namespace ipd {
namespace {

// Two scenes of three rocks at the same places in both domains (registration pairs rock k with rock k).
// A prediction of a 0.1-wide box shifted by dx has IoU (0.1 - dx) / (0.1 + dx): 0.02 -> 2/3, 0.05 -> 1/3,
// 0.01 -> 9/11; no prediction: 0.
//   s1: real perf 1, 2/3, 0        synth 1/3, 1, 9/11    |diff| 2/3, 1/3, 9/11
//   s2: real perf 0, 1, 1          synth 1, 9/11, 1      |diff| 1, 2/11, 0
// Largest |diff| first: s2 rock 1 (1), s1 rock 3 (0.818), s1 rock 1 (0.667), s1 rock 2 (0.333),
// s2 rock 2 (0.182), s2 rock 3 (0).
void write_gallery_study(const test::TempDir& d, bool pictures) {
  test::write_text(d / "study.yaml",
                   "domains: [real, synth]\nimage_size: [100, 100]\nmodels: {det: {trained_on: real}}\n");
  const std::string s1 = "0 0.2 0.2 0.1 0.1\n0 0.7 0.3 0.1 0.1\n0 0.4 0.7 0.1 0.1\n";
  const std::string s2 = "0 0.3 0.3 0.1 0.1\n0 0.8 0.2 0.1 0.1\n0 0.5 0.8 0.1 0.1\n";
  for (const std::string dom : {"real", "synth"}) {
    test::write_text(d / (dom + "/labels/s1.txt"), s1);
    test::write_text(d / (dom + "/labels/s2.txt"), s2);
  }
  test::write_text(d / "real/predictions/det/s1.txt", "0 0.2 0.2 0.1 0.1 0.9\n0 0.72 0.3 0.1 0.1 0.9\n");
  test::write_text(d / "synth/predictions/det/s1.txt",
                   "0 0.25 0.2 0.1 0.1 0.9\n0 0.7 0.3 0.1 0.1 0.9\n0 0.41 0.7 0.1 0.1 0.9\n");
  test::write_text(d / "real/predictions/det/s2.txt", "0 0.8 0.2 0.1 0.1 0.9\n0 0.5 0.8 0.1 0.1 0.9\n");
  test::write_text(d / "synth/predictions/det/s2.txt",
                   "0 0.3 0.3 0.1 0.1 0.9\n0 0.81 0.2 0.1 0.1 0.9\n0 0.5 0.8 0.1 0.1 0.9\n");
  if (!pictures) return;
  for (const std::string dom : {"real", "synth"})
    for (const std::string stem : {"s1", "s2"}) {
      std::filesystem::create_directories(d / (dom + "/images"));
      cv::imwrite(d / (dom + "/images/" + stem + ".png"), cv::Mat(100, 100, CV_8UC3, cv::Scalar(40, 160, 220)));
    }
}

StudyLabels labels_of(const test::TempDir& d) { return load_labels(open_study(d.path())); }

const TableCell& real_synth(const CrossTable& t) { return *t.cell("det", "real", "synth"); }

// A right rock is named by its own number and by its pair's, which is the left rock's (the pictures number a pair so
// on both sides): synth lists real's two rocks in the other order.
TEST(FigureGallery, ARightRockOfAnotherNumberIsNamedWithItsPair) {
  test::TempDir d;
  test::write_text(d / "study.yaml", "domains: [real, synth]\nmodels:\n  det: {trained_on: real}\n");
  test::write_text(d / "real/labels/s1.txt", "0 0.2 0.2 0.1 0.1\n0 0.7 0.7 0.1 0.1\n0 0.2 0.7 0.1 0.1\n");
  test::write_text(d / "synth/labels/s1.txt", "0 0.7 0.7 0.1 0.1\n0 0.2 0.2 0.1 0.1\n0 0.2 0.7 0.1 0.1\n");
  for (const std::string dom : {"real", "synth"})
    test::write_text(d / (dom + "/predictions/det/s1.txt"), "0 0.21 0.2 0.1 0.1 0.9\n");
  const StudyLabels labels = labels_of(d);
  const CrossTable t = compute_cross_table(labels, {});
  const ui::GalleryInput in = ui::gallery_input(labels, real_synth(t), 3, GallerySort::kDiff);
  ASSERT_EQ(in.entries.size(), 3u);
  for (const ui::GalleryEntry& e : in.entries) {
    EXPECT_EQ(e.a.pair, -1);
    EXPECT_EQ(e.b.pair, e.b.rock == e.a.rock ? -1 : e.a.rock) << "real rock " << e.a.rock;
    EXPECT_EQ(e.b.rock, e.a.rock == 2 ? 2 : 1 - e.a.rock);
  }
}

TEST(FigureGallery, PairsAreTheLargestDiffFirstWithTheirValues) {
  test::TempDir d;
  write_gallery_study(d, false);
  const StudyLabels labels = labels_of(d);
  const CrossTable t = compute_cross_table(labels, {});
  const ui::GalleryInput in = ui::gallery_input(labels, real_synth(t), 4, GallerySort::kDiff);
  EXPECT_EQ(in.counted_pairs, 6);
  ASSERT_EQ(in.entries.size(), 4u);
  const std::vector<std::tuple<std::string, int, double, double>> expected = {
      {"s2", 0, 0.0, 1.0}, {"s1", 2, 0.0, 9.0 / 11}, {"s1", 0, 1.0, 1.0 / 3}, {"s1", 1, 2.0 / 3, 1.0}};
  for (size_t k = 0; k < expected.size(); ++k) {
    const auto& [stem, rock, perf_a, perf_b] = expected[k];
    EXPECT_EQ(in.entries[k].stem, stem) << k;
    EXPECT_EQ(in.entries[k].a.rock, rock) << k;
    EXPECT_EQ(in.entries[k].b.rock, rock) << k;
    EXPECT_NEAR(in.entries[k].a.perf, perf_a, 1e-9) << k;
    EXPECT_NEAR(in.entries[k].b.perf, perf_b, 1e-9) << k;
    EXPECT_NEAR(in.entries[k].diff, std::abs(perf_a - perf_b), 1e-9) << k;
  }
  // The best prediction of s1 rock 1 in synth is the one shifted by 0.05; real's s2 rock 1 has none.
  EXPECT_TRUE(in.entries[2].b.has_pred);
  EXPECT_DOUBLE_EQ(in.entries[2].b.pred.cx, 0.25);
  EXPECT_FALSE(in.entries[0].a.has_pred);
  // A square around the rock, 2.5 x its side but at least 2.5 x 16 px (40 px of the 100 px picture).
  EXPECT_NEAR(in.entries[2].a.region.x0, 0.0, 1e-9);
  EXPECT_NEAR(in.entries[2].a.region.x1, 0.4, 1e-9);
  // perf A, largest first: the three pairs whose A rock is found exactly (perf 1, up to rounding), then s1
  // rock 2 (2/3).
  const ui::GalleryInput by_a = ui::gallery_input(labels, real_synth(t), 4, GallerySort::kPerfA);
  ASSERT_EQ(by_a.entries.size(), 4u);
  std::set<std::string> first;
  for (size_t k = 0; k < 3; ++k) {
    first.insert(by_a.entries[k].stem + " " + std::to_string(by_a.entries[k].a.rock));
    EXPECT_NEAR(by_a.entries[k].a.perf, 1.0, 1e-12);
    EXPECT_GE(by_a.entries[k].a.perf, by_a.entries[k + 1].a.perf);
  }
  EXPECT_EQ(first, (std::set<std::string>{"s1 0", "s2 1", "s2 2"}));
  EXPECT_EQ(by_a.entries[3].stem + " " + std::to_string(by_a.entries[3].a.rock), "s1 1");
}

// With pictures, each crop keeps only its square of pixels: 40 x 40 of the 100 x 100 picture (16 px is the
// least side, 2.5 x 16 = 40; the rock's 10 px x 2.5 = 25 is smaller).
// A crop is square in pixels, not in normalised units: a 0.1 x 0.1 box of a 960 x 600 picture is 96 x 60 px,
// so the crop is 2.5 x 96 = 240 px each way: 0.25 of the width, 0.4 of the height (drawn square by the figure
// and the studio's gallery alike, the rock keeps its 96:60 shape).
TEST(FigureGallery, CropRegionIsASquareOfPixels) {
  const ui::Crop r = ui::gallery_crop_region(Box{0, 0.5, 0.5, 0.1, 0.1}, 960, 600);
  EXPECT_NEAR(r.x0, 0.375, 1e-12);
  EXPECT_NEAR(r.x1, 0.625, 1e-12);
  EXPECT_NEAR(r.y0, 0.3, 1e-12);
  EXPECT_NEAR(r.y1, 0.7, 1e-12);
  // A rock under 16 px gets a 40 px crop: 20 px either side of its centre.
  const ui::Crop tiny = ui::gallery_crop_region(Box{0, 0.5, 0.5, 0.001, 0.001}, 960, 600);
  EXPECT_NEAR(tiny.x1 - 0.5, 20.0 / 960, 1e-12);
  EXPECT_NEAR(tiny.y1 - 0.5, 20.0 / 600, 1e-12);
  // An unknown size is measured in the POLAR cameras' pixels.
  EXPECT_EQ(ui::gallery_picture_size(0, 600), (std::pair<int, int>{1936, 1216}));
  EXPECT_EQ(ui::gallery_picture_size(960, 600), (std::pair<int, int>{960, 600}));
}

TEST(FigureGallery, CropsComeFromThePictures) {
  test::TempDir d;
  write_gallery_study(d, true);
  const StudyLabels labels = labels_of(d);
  const CrossTable t = compute_cross_table(labels, {});
  ui::GalleryInput in = ui::gallery_input(labels, real_synth(t), 2, GallerySort::kDiff);
  ui::load_gallery_pictures(in, labels.study);
  EXPECT_TRUE(in.pictures);
  ASSERT_EQ(in.entries.size(), 2u);
  EXPECT_EQ(in.entries[0].a.pixels.cols, 40);
  EXPECT_EQ(in.entries[0].a.pixels.rows, 40);
  EXPECT_NEAR(in.entries[0].a.covered.x0, 0.1, 1e-9);  // s2 rock 1 at (0.3, 0.3): 0.1 .. 0.5
}

// The CLI's PDF: a single column, the entries' values as text, nothing overlapping, no text under 7 pt;
// a labels-only study says its crops are boxes on a plain background.
// One vocabulary for the sort keys (ipd figure gallery --sort, the studio's replay) and one label that names the
// domains (the figure's title, the studio's combo).
TEST(FigureGallery, SortKeysAndTheirLabels) {
  GallerySort sort = GallerySort::kDiff;
  ASSERT_TRUE(parse_gallery_sort("perf-b", &sort));
  EXPECT_EQ(sort, GallerySort::kPerfB);
  EXPECT_FALSE(parse_gallery_sort("perf-right", &sort));
  EXPECT_EQ(gallery_sort_label(GallerySort::kPerfA, "real", "synth"), "perf real");
  EXPECT_EQ(gallery_sort_label(GallerySort::kPerfB, "real", "synth"), "perf synth");
  EXPECT_EQ(gallery_sort_label(GallerySort::kDiff, "real", "synth"), "|diff|");
  EXPECT_EQ(gallery_sort_label(GallerySort::kSize, "real", "synth"), "size");
}

TEST(FigureGallery, PdfPrintsTheChosenPairsInOrder) {
  test::TempDir d;
  write_gallery_study(d, false);
  const std::string out = d / "gallery.pdf";
  const auto r = test::run_ipd("figure gallery " + d.path() + " --count 4 --no-cache --out " + out);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const test::PdfText t = test::pdf_text(out);
  EXPECT_NEAR(t.width, 252, 1.0);
  const std::string all = t.all();
  size_t at = 0;
  for (const std::string entry :
       {"1. s2, |diff| 1.000", "2. s1, |diff| 0.818", "3. s1, |diff| 0.667", "4. s1, |diff| 0.333"}) {
    const size_t found = all.find(entry, at);
    ASSERT_NE(found, std::string::npos) << entry << "\n" << all;
    at = found;
  }
  EXPECT_NE(all.find("The first 4 of 6 counted pairs; left real, right synth."), std::string::npos) << all;
  EXPECT_NE(all.find("Labels-only study: boxes on a plain background."), std::string::npos) << all;
  EXPECT_TRUE(test::overlapping(t).empty());
  // Rasterised, the page is what a reader sees (pdftoppm).
  const auto ppm = test::run_command("pdftoppm -r 100 -png -singlefile '" + out + "' '" + (d / "page") + "'");
  ASSERT_EQ(ppm.exit_code, 0) << ppm.err;
  const cv::Mat page = cv::imread(d / "page.png");
  ASSERT_FALSE(page.empty());
  EXPECT_NEAR(page.cols, 350, 1);  // 3.5 in at 100 dpi
}

// Drawn through the figure canvas: every text at least 7 pt, crops square, A left of B in each entry, two
// entries side by side in a single column and none overlapping another.
TEST(FigureGallery, LayoutIsSquareCropsSideBySide) {
  test::TempDir d;
  write_gallery_study(d, false);
  const StudyLabels labels = labels_of(d);
  const CrossTable t = compute_cross_table(labels, {});
  const ui::GalleryInput in = ui::gallery_input(labels, real_synth(t), 6, GallerySort::kDiff);
  const ui::FontMetrics metrics(ui::default_font_file());
  ui::DisplayList fig(metrics);
  ui::FigureOptions o;
  const ui::GalleryLayout l = ui::draw_gallery_figure(fig, in, o);
  ASSERT_EQ(l.left.size(), 6u);
  for (size_t k = 0; k < 6; ++k) {
    EXPECT_NEAR(l.left[k].width(), l.left[k].height(), 1e-9);
    EXPECT_NEAR(l.left[k].width(), l.right[k].width(), 1e-9);
    EXPECT_LT(l.left[k].x1, l.right[k].x0);
    EXPECT_DOUBLE_EQ(l.left[k].y0, l.right[k].y0);
  }
  EXPECT_DOUBLE_EQ(l.left[0].y0, l.left[1].y0);  // entries 1 and 2 on one row
  EXPECT_LT(l.right[0].x1, l.left[1].x0);
  EXPECT_GT(l.left[2].y0, l.left[0].y1);  // entry 3 on the next row
  for (const auto& text : fig.texts()) EXPECT_GE(text.size_pt, 7.0) << text.text;
  // Each crop's value right under it: entry 2 is s1 rock 3, perf 0 in real and 9/11 in synth.
  const auto under = [&](const std::string& s, const ui::PtRect& crop) {
    for (const auto& text : fig.texts())
      if (text.text == s && text.box.x0 >= crop.x0 - 1e-9 && text.box.x1 <= crop.x1 + 1e-9 && text.box.y0 > crop.y1 &&
          text.box.y0 < crop.y1 + 25)
        return true;
    return false;
  };
  EXPECT_TRUE(under("rock 3", l.left[1]));
  EXPECT_TRUE(under("perf 0.000", l.left[1]));
  EXPECT_TRUE(under("perf 0.818", l.right[1]));
  EXPECT_FALSE(under("perf 0.818", l.left[1]));
  EXPECT_LE(l.right[1].x1, fig.width_pt - ui::fig::kFigureMargin + 1e-9);
}

// One rock pair of a segmentation study, with its box IoU beside its mask IoU. Scene s1 has three square rocks
// 0.1 wide (10 px of 100) at the same places in both domains. Rock 1 of real is predicted by the triangle
// that is its lower-left half: mask IoU = 0.005 / 0.01 = 0.5, while the triangle's box is the square's, box
// IoU 1; synth predicts the square itself (both 1). |diff| = 0.5.
void write_mask_pair_study(const test::TempDir& d) {
  test::write_text(
      d / "study.yaml",
      "domains: [real, synth]\nimage_size: [100, 100]\ntask: segment\nmodels: {det: {trained_on: real}}\n");
  const auto square = [](double x, double y) {
    return fmt::format("{} {} {} {} {} {} {} {}", x, y, x + 0.1, y, x + 0.1, y + 0.1, x, y + 0.1);
  };
  const std::string gt = "0 " + square(0.2, 0.2) + "\n0 " + square(0.6, 0.6) + "\n0 " + square(0.4, 0.75) + "\n";
  const std::string rest = "0 " + square(0.6, 0.6) + " 0.9\n0 " + square(0.4, 0.75) + " 0.9\n";
  for (const std::string dom : {"real", "synth"}) test::write_text(d / (dom + "/labels/s1.txt"), gt);
  test::write_text(d / "real/predictions/det/s1.txt", "0 0.2 0.2 0.3 0.2 0.2 0.3 0.9\n" + rest);
  test::write_text(d / "synth/predictions/det/s1.txt", "0 " + square(0.2, 0.2) + " 0.9\n" + rest);
}

TEST(FigureGallery, OneRockPairShowsBoxIouBesideMaskIou) {
  test::TempDir d;
  write_mask_pair_study(d);
  const std::string out = d / "rock.pdf";
  const auto r = test::run_ipd("figure gallery " + d.path() + " --scene s1 --rock 1 --no-cache --out " + out);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string all = test::pdf_text(out).all();
  EXPECT_NE(all.find("Rock 1 of real in s1 and its partner in synth, model det"), std::string::npos) << all;
  EXPECT_NE(all.find("1. s1, |diff| 0.500"), std::string::npos) << all;
  EXPECT_NE(all.find("Left real, right synth."), std::string::npos) << all;
  EXPECT_NE(all.find("mask IoU 0.500"), std::string::npos) << all;  // real: the triangle
  EXPECT_EQ(all.find("2. s1"), std::string::npos) << all;           // one pair only
  size_t box_ious = 0;
  for (size_t at = 0; (at = all.find("box IoU 1.000", at)) != std::string::npos; ++at) ++box_ious;
  EXPECT_EQ(box_ious, 2u) << all;  // both sides: the triangle's box is the square's
  // The one pair spans the column: drawn in process, its right crop ends at the right margin.
  const StudyLabels labels = labels_of(d);
  const CrossTable t = compute_cross_table(labels, {});
  const ui::GalleryInput in = ui::gallery_input(labels, real_synth(t), 8, GallerySort::kDiff, "s1", 1);
  ASSERT_EQ(in.entries.size(), 1u);
  EXPECT_NEAR(in.entries[0].a.perf, 0.5, 1e-9);
  EXPECT_NEAR(in.entries[0].a.box_iou, 1.0, 1e-9);
  const ui::FontMetrics metrics(ui::default_font_file());
  ui::DisplayList fig(metrics);
  ui::FigureOptions o;
  const ui::GalleryLayout l = ui::draw_gallery_figure(fig, in, o);
  ASSERT_EQ(l.right.size(), 1u);
  EXPECT_NEAR(l.right[0].x1, 252 - ui::fig::kFigureMargin, 1e-6);
  // A rock in no pair, and --rock without --scene, are refused by name.
  const auto bad = test::run_ipd("figure gallery " + d.path() + " --scene s1 --rock 9 --no-cache --out " + out);
  EXPECT_NE(bad.exit_code, 0);
  EXPECT_NE(bad.err.find("--rock 9: rock 9 of real in s1 is in no counted pair of real | synth for model det (its "
                         "paired rocks: 1, 2, 3)"),
            std::string::npos)
      << bad.err;
  const auto no_scene = test::run_ipd("figure gallery " + d.path() + " --rock 1 --out " + out);
  EXPECT_EQ(no_scene.exit_code, 2);
  EXPECT_NE(no_scene.err.find("error: --rock 1 needs --scene: rock numbers are a scene's"), std::string::npos)
      << no_scene.err;
}

// Counts what a figure draws, for the stroke rules below.
struct StrokeCounter : ui::Canvas {
  int rects = 0;
  std::vector<double> lines;  // lengths
  void rect(const ui::PtRect&, ui::Colour, double) override { ++rects; }
  void fill_rect(const ui::PtRect&, ui::Colour) override {}
  void line(ui::Pt a, ui::Pt b, ui::Colour, double) override { lines.push_back(std::hypot(b.x - a.x, b.y - a.y)); }
  void polyline(const std::vector<ui::Pt>&, ui::Colour, double, bool) override {}
  void circle(ui::Pt, double, ui::Colour, double) override {}
  void fill_circle(ui::Pt, double, ui::Colour) override {}
  void text(ui::Pt, ui::Anchor, const ui::TextStyle&, const std::string&) override {}
  void image(const ui::FigurePicture&, const ui::PtRect&) override {}
  void push_clip(const ui::PtRect&) override {}
  void pop_clip() override {}
  ui::Pt measure(const ui::TextStyle& st, const std::string& s) override {
    return {0.5 * st.size_pt * s.size(), 1.2 * st.size_pt};
  }
};

// A small prediction's dashed outline keeps at least five dashes: a 2 x 2 pt square (perimeter 8 pt) asked
// for 2.24 pt dashes (4 x the 0.56 pt stroke at 8 pt) gets 8 / (5 x 1.6) = 1 pt dashes with 0.6 pt gaps, so
// about 5 pt of its 8 are inked in 5 dashes; a tiny one (perimeter 3 pt) dots at 0.8 pt; a large one keeps
// the length asked for.
TEST(FigureStrokes, DashesScaleToASmallOutlinesPerimeter) {
  EXPECT_DOUBLE_EQ(ui::fig::outline_dash(100, 2.24), 2.24);
  EXPECT_DOUBLE_EQ(ui::fig::outline_dash(8, 2.24), 1.0);
  EXPECT_DOUBLE_EQ(ui::fig::outline_dash(3, 2.24), 0.8);
  for (int polygon = 0; polygon < 2; ++polygon) {
    StrokeCounter c;
    if (polygon)
      ui::fig::dashed_polygon(c, {{10, 10}, {12, 10}, {12, 12}, {10, 12}}, ui::fig::kPredC, 0.56, 2.24);
    else
      ui::fig::dashed_rect(c, {10, 10, 12, 12}, ui::fig::kPredC, 0.56, 2.24);
    double inked = 0, longest = 0;
    for (double len : c.lines) inked += len, longest = std::max(longest, len);
    EXPECT_LE(longest, 1.0 + 1e-9) << polygon;
    EXPECT_NEAR(inked, 5.0, 1.0) << polygon;
    EXPECT_GE(c.lines.size(), 5u) << polygon;
  }
}

// Outlines are named in the legend by line samples: a solid stroke on its halo for GT, two dashes for a
// prediction; boxes by boxes.
TEST(FigureStrokes, OutlineLegendSwatchesAreLineSamples) {
  StrokeCounter c;
  ui::fig::draw_legend(c, {0, 0}, 200, ui::fig::style(8, ui::fig::kInk),
                       {{ui::fig::Swatch::kOutline, ui::fig::kGtC, "GT rock", ui::fig::kDarkHalo},
                        {ui::fig::Swatch::kDashedOutline, ui::fig::kPredC, "prediction", ui::fig::kLightHalo}});
  EXPECT_EQ(c.rects, 0);
  ASSERT_EQ(c.lines.size(), 6u);                    // GT: halo + stroke; prediction: two dashes, each halo + stroke
  EXPECT_GT(c.lines[0], 5.0);                       // the solid sample spans the swatch
  EXPECT_NEAR(c.lines[2], c.lines[0] / 2.6, 1e-9);  // a dash: 1 / 2.6 of it
  StrokeCounter boxes;
  ui::fig::draw_legend(boxes, {0, 0}, 200, ui::fig::style(8, ui::fig::kInk),
                       {{ui::fig::Swatch::kBox, ui::fig::kGtC, "GT rock", ui::fig::kDarkHalo}});
  EXPECT_EQ(boxes.rects, 2);
}

}  // namespace
}  // namespace ipd
