// Figure files as a reader of the paper gets them, checked with poppler-utils (pdfinfo, pdftotext -bbox):
// page width = column width, text as text, no two words overlapping; SVG is XML with a size; PNG width =
// inches x dpi; unknown extensions refused; the GUI's export and the CLI give the same PDF for one view.
#include <gtest/gtest.h>

#include <fmt/format.h>
#include <cmath>
#include <filesystem>
#include <map>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <regex>
#include <sstream>

#include "core/demo/demo_study.h"
#include "core/session/session.h"
#include "core/util/atomic_file.h"
#include "tests/support/figure_test_study.h"
#include "tests/support/pdf_text.h"
#include "tests/support/test_support.h"
#include "ui/figures/figure_export.h"
#include "ui/gui/export_dialog.h"

namespace fs = std::filesystem;

namespace ipd {
namespace {

using test::has_word;
using test::overlapping;
using test::pdf_text;
using test::PdfText;
using test::Word;

TEST(FigureFiles, PdfPageIsTheColumnWidthAndCarriesTheText) {
  test::TempDir d;
  test::write_figure_study(d, true);
  for (const auto& [column, width_pt] : {std::pair<std::string, double>{"single", 252}, {"double", 515.52}}) {
    const std::string out = d / ("pairs_" + column + ".pdf");
    const auto r = test::run_ipd("figure pairs " + d.path() + " --scene s1 --column " + column + " --out " + out);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const auto info = test::run_command("pdfinfo '" + out + "'");
    std::smatch m;
    ASSERT_TRUE(std::regex_search(info.out, m, std::regex(R"re(Page size:\s+([\d.]+) x ([\d.]+) pts)re"))) << info.out;
    EXPECT_NEAR(std::stod(m[1]), width_pt, 1.0);
    const PdfText t = pdf_text(out);
    EXPECT_NEAR(t.width, width_pt, 1.0);
    // Title with the scene's IPD: pair (rock 1 of both) perf |IoU(gt, pred) real - synth|.
    //   real: GT [0.20,0.40]x[0.275,0.525], pred [0.25,0.45]: IoU = 0.15/0.25 = 0.6
    //   synth: pred [0.22,0.42]: IoU = 0.18/0.22 = 0.818181...; |0.6 - 0.8182| = 0.2182
    EXPECT_NE(t.all().find("s1: real vs synth, model det, scene IPD 0.2182 (1 pair)"), std::string::npos) << t.all();
    EXPECT_TRUE(has_word(t, "1"));   // the pair's number
    EXPECT_TRUE(has_word(t, "x2"));  // the unpaired rock, by its own index
    EXPECT_NE(t.all().find("unpaired GT (x index)"), std::string::npos) << t.all();  // and its legend entry
    EXPECT_EQ(has_word(t, "0.87"), column == "double");  // confidences: double column only by default
    EXPECT_TRUE(overlapping(t).empty());
  }
}

// Every font of the PDF embedded (as a subset), and --font picks another one.
TEST(FigureFiles, FontsAreEmbeddedAndChosenWithFont) {
  test::TempDir d;
  test::write_figure_study(d, false);
  ASSERT_EQ(test::run_ipd("figure table " + d.path() + " --out " + d / "sans.pdf").exit_code, 0);
  const std::string serif = "/usr/share/fonts/truetype/dejavu/DejaVuSerif.ttf";
  ASSERT_EQ(test::run_ipd("figure table " + d.path() + " --font " + serif + " --out " + d / "serif.pdf").exit_code, 0);
  for (const auto& [file, family] :
       {std::pair<std::string, std::string>{"sans.pdf", "DejaVuSans"}, {"serif.pdf", "DejaVuSerif"}}) {
    const auto r = test::run_command("pdffonts '" + d / file + "'");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    // Regular and bold (the row's best), each "+FAMILY... TrueType WinAnsi yes yes yes".
    const std::regex embedded("\\+" + family + "(-Bold)?\\s+TrueType\\s+\\S+\\s+yes\\s+yes");
    const auto n = std::distance(std::sregex_iterator(r.out.begin(), r.out.end(), embedded), std::sregex_iterator());
    EXPECT_EQ(n, 2) << r.out;
  }
}

TEST(FigureFiles, PicturesGoInAtTheirOwnResolutionCutToTheCrop) {
  test::TempDir d;
  test::write_figure_study(d, true);  // 640 x 400 pictures
  const std::string out = d / "crop.pdf";
  ASSERT_EQ(
      test::run_ipd("figure pairs " + d.path() + " --crop 0.25,0.25,0.75,0.75 --column double --out " + out).exit_code,
      0);
  const auto r = test::run_command("pdfimages -list '" + out + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  // Two images of 320 x 200 pixels: the crop's own pixels, neither resampled nor padded.
  const std::regex image(R"re(\n\s+1\s+\d+\s+image\s+(\d+)\s+(\d+))re");
  int images = 0;
  for (auto it = std::sregex_iterator(r.out.begin(), r.out.end(), image); it != std::sregex_iterator();
       ++it, ++images) {
    EXPECT_EQ((*it)[1], "320");
    EXPECT_EQ((*it)[2], "200");
  }
  EXPECT_EQ(images, 2) << r.out;
}

TEST(FigureFiles, NoWordsOverlapOnTheDemosBusiestScene) {
  test::TempDir d;
  DemoStudyOptions demo;
  demo.scenes = 3;  // scene_02 (17 rocks a side) is the busiest of the demo study
  write_demo_study(d.path(), demo);
  for (const std::string kind : {"pairs", "registration"})
    for (const std::string column : {"single", "double"}) {
      const std::string out = d / (kind + column + ".pdf");
      const auto r = test::run_ipd("figure " + kind + " " + d.path() + " --scene scene_02 --column " + column +
                                   " --layers gt,pred,conf,indices,pairs,legend --out " + out);
      ASSERT_EQ(r.exit_code, 0) << r.err;
      const PdfText t = pdf_text(out);
      EXPECT_GT(t.words.size(), 20u) << kind << " " << column;
      for (int n = 1; n <= 9; ++n) EXPECT_TRUE(has_word(t, std::to_string(n))) << kind << " " << column << " " << n;
      const auto bad = overlapping(t);
      EXPECT_TRUE(bad.empty()) << kind << " " << column << ": " << (bad.empty() ? "" : bad.front());
      for (const Word& w : t.words) EXPECT_GE(w.y1 - w.y0, 6.0) << w.text;  // nothing under 6 pt
      // Every rock of scene_02 is paired: no legend entry for unpaired rocks the page doesn't show.
      if (kind == "pairs") {
        EXPECT_EQ(t.all().find("unpaired"), std::string::npos) << column << ": " << t.all();
      }
      for (const Word& w : t.words) EXPECT_LE(w.x1, t.width + 0.5) << kind << " " << column << ": " << w.text;
    }
  // Pairs fixed by hand (one of them wrong): the panel says how it was aligned, and the caption stays on the
  // page in a single column.
  test::write_text(d / "pairs/real__principled/scene_02.json", R"({"pairs": [[0, 1], [1, 0], [2, 2], [3, 3]]})");
  const std::string out = d / "fixed.pdf";
  const auto r = test::run_ipd("figure registration " + d.path() + " --scene scene_02 --column single --out " + out);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const PdfText t = pdf_text(out);
  EXPECT_NE(t.all().find("aligned by the pairs"), std::string::npos) << t.all();
  for (const Word& w : t.words) EXPECT_LE(w.x1, t.width + 0.5) << w.text;
}

// Table I with intervals in one IEEE column (3 models x 3 domain pairs, as the demo): each interval
// "[lo, hi]" stays on one line under its value, at 6 pt or more, and no words overlap.
TEST(FigureFiles, TableIntervalsFitOnOneLineInASingleColumn) {
  test::TempDir d;
  test::write_small_demo_study(d);
  for (const std::string column : {"single", "double"}) {
    const std::string out = d / ("table_" + column + ".pdf");
    const auto r = test::run_ipd("figure table " + d.path() + " --ci 0.95 --column " + column + " --out " + out);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const PdfText t = pdf_text(out);
    int intervals = 0;
    for (size_t k = 0; k < t.words.size(); ++k) {
      if (t.words[k].text.front() != '[') continue;
      ++intervals;
      ASSERT_LT(k + 1, t.words.size());
      const Word &lo = t.words[k], &hi = t.words[k + 1];  // "[0.021," and "0.037]"
      EXPECT_EQ(hi.text.back(), ']') << column << ": " << lo.text << " " << hi.text;
      EXPECT_NEAR(hi.y0, lo.y0, 0.5) << column << ": " << lo.text << " " << hi.text << " wraps";
      EXPECT_GT(hi.x0, lo.x1) << column << ": " << lo.text << " " << hi.text;
      EXPECT_GE(lo.y1 - lo.y0, 6.0) << lo.text;
    }
    EXPECT_EQ(intervals, 6) << column << ": " << t.all();  // the cells that involve their row's training domain
    const auto bad = overlapping(t);
    EXPECT_TRUE(bad.empty()) << column << ": " << (bad.empty() ? "" : bad.front());
    EXPECT_NE(t.all().find("Brackets: 95% scene-bootstrap interval."), std::string::npos) << t.all();
  }
}

// The cross table's shown cells as `ipd table --format csv` gives them: the value ("0.3120") and, when the cell
// has one, its interval's ends ("[0.223," and "0.393]", as pdftotext splits "[0.223, 0.393]"), per row and pair.
struct CsvCell {
  std::string model, a, b, value, low, high;
};
std::vector<CsvCell> csv_cells(const std::string& csv) {
  std::vector<CsvCell> out;
  std::istringstream in(csv);
  std::string line;
  std::getline(in, line);  // header: model,trained_on,a,b,ipd,...,involves_training_domain,ci_low,ci_high,...
  std::vector<std::string> head;
  {
    std::istringstream h(line);
    for (std::string f; std::getline(h, f, ',');) head.push_back(f);
  }
  const auto col = [&](const std::string& name) {
    return static_cast<size_t>(std::find(head.begin(), head.end(), name) - head.begin());
  };
  while (std::getline(in, line)) {
    std::vector<std::string> f;
    std::istringstream r(line);
    for (std::string x; std::getline(r, x, ',');) f.push_back(x);
    if (f.size() < head.size() || f[col("ipd")].empty()) continue;
    if (f[col("involves_training_domain")] != "true") continue;  // "–" in the figure
    const auto fixed = [](const std::string& v, int digits) { return fmt::format("{:.{}f}", std::stod(v), digits); };
    out.push_back({f[col("model")], f[col("a")], f[col("b")], fixed(f[col("ipd")], 4),
                   f[col("ci_low")].empty() ? "" : fixed(f[col("ci_low")], 3),
                   f[col("ci_high")].empty() ? "" : fixed(f[col("ci_high")], 3)});
  }
  return out;
}

// Table I never drops a cell: for 2 to 5 domains and 1 to 3 detectors, at one and at two columns, every shown
// cell's value and both ends of its interval are words of the PDF (pdftotext), and no word runs past the page's right
// margin. Four or five domains at one column don't fit one table: the figure draws two, each with the row names.
TEST(FigureFiles, TableFigureKeepsEveryCellForTwoToFiveDomainsAndOneToThreeDetectors) {
  test::TempDir d;
  test::write_small_demo_study(d);
  // Five domains (two copies with long names, as renderer settings are named) and a third detector trained on
  // real, so every detector count fits every domain count.
  fs::copy(d / "hapke", d / "sun30", fs::copy_options::recursive);
  fs::copy(d / "principled", d / "sun350", fs::copy_options::recursive);
  for (const std::string dom : {"real", "principled", "hapke", "sun30", "sun350"})
    fs::copy(d / (dom + "/predictions/det-real"), d / (dom + "/predictions/det-real2"), fs::copy_options::recursive);
  test::write_text(d / "study.yaml",
                   "domains: [real, principled, hapke, sun30, sun350]\nimage_size: [960, 600]\nmodels:\n"
                   "  det-real: {trained_on: real}\n  det-principled: {trained_on: principled}\n"
                   "  det-real2: {trained_on: real}\n");
  const std::vector<std::string> domains = {"real", "principled", "hapke", "sun30", "sun350"};
  const std::vector<std::string> models = {"det-real", "det-principled", "det-real2"};
  int split = 0;
  for (size_t nd = 2; nd <= 5; ++nd)
    for (size_t nm = 1; nm <= 3; ++nm) {
      std::string doms, mods;
      for (size_t k = 0; k < nd; ++k) doms += (k ? "," : "") + domains[k];
      for (size_t k = 0; k < nm; ++k) mods += (k ? "," : "") + models[k];
      const std::string opts = " --domains " + doms + " --model " + mods + " --bootstrap 200";
      const auto csv = test::run_ipd("table " + d.path() + opts + " --format csv");
      ASSERT_EQ(csv.exit_code, 0) << csv.err;
      const std::vector<CsvCell> cells = csv_cells(csv.out);
      ASSERT_FALSE(cells.empty()) << csv.out;
      for (const std::string column : {"single", "double"}) {
        const std::string out = d / fmt::format("table_{}_{}_{}.pdf", nd, nm, column);
        const std::string what = fmt::format("{} domains, {} models, {} column", nd, nm, column);
        const auto r = test::run_ipd("figure table " + d.path() + opts + " --ci --column " + column + " --out " + out);
        ASSERT_EQ(r.exit_code, 0) << what << ": " << r.err;
        const PdfText t = pdf_text(out);
        for (const Word& w : t.words) EXPECT_LE(w.x1, t.width - 4 + 0.05) << what << ": " << w.text;
        // Each value and interval end is a word of the page as often as the cells hold it.
        std::map<std::string, int> need, have;
        for (const CsvCell& c : cells) {
          ++need[c.value];
          if (!c.low.empty()) ++need["[" + c.low + ","], ++need[c.high + "]"];
        }
        for (const Word& w : t.words) ++have[w.text];
        for (const auto& [word, n] : need) EXPECT_GE(have[word], n) << what << ": \"" << word << "\" in " << t.all();
        int headers = 0;
        for (const Word& w : t.words) headers += w.text == "Train";
        if (headers > 1) ++split;
        EXPECT_TRUE(overlapping(t).empty()) << what;
      }
    }
  EXPECT_GT(split, 0);  // some single-column tables were split in two, not cut
}

// The blank border around everything drawn on a PDF's page, in points (rendered at 4 px per point; a
// pixel counts as ink when a channel is below 245).
struct InkMargins {
  double left = 0, top = 0, right = 0, bottom = 0;
};
InkMargins ink_margins(const std::string& pdf) {
  const std::string png = pdf + ".ink";
  const auto r = test::run_command("pdftoppm -r 288 -png -singlefile '" + pdf + "' '" + png + "'");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  const cv::Mat img = cv::imread(png + ".png", cv::IMREAD_COLOR);
  if (img.empty()) return {};
  cv::Mat channel_min;
  cv::Mat channels[3];
  cv::split(img, channels);
  cv::min(channels[0], channels[1], channel_min);
  cv::min(channel_min, channels[2], channel_min);
  std::vector<cv::Point> ink;
  cv::findNonZero(channel_min < 245, ink);
  if (ink.empty()) return {};
  const cv::Rect box = cv::boundingRect(ink);
  return {box.x / 4.0, box.y / 4.0, (img.cols - box.x - box.width) / 4.0, (img.rows - box.y - box.height) / 4.0};
}

// Every kind, single and double column: no word within 4 pt (kFigureMargin) of the page's edges, and the
// title starts right at that margin on every kind (the same margin everywhere, not one per kind). The
// demo has a picture-less scene here, so the pairs panels and the registration plots are drawn boxes.
TEST(FigureFiles, EveryKindKeepsTheSameMarginFreeOfText) {
  test::TempDir d;
  test::write_small_demo_study(d);
  const double margin = 4.0, hair = 0.05;  // poppler rounds word boxes
  for (const std::string kind : {"pairs", "registration", "table", "compare", "distribution", "breakdown"})
    for (const std::string column : {"single", "double"}) {
      const std::string out = d / (kind + "_" + column + ".pdf");
      const std::string layers = kind == "pairs" ? " --layers gt,pred,conf,indices,pairs,legend" : "";
      const auto r =
          test::run_ipd("figure " + kind + " " + d.path() + " --column " + column + layers + " --out " + out);
      ASSERT_EQ(r.exit_code, 0) << kind << " " << column << ": " << r.err;
      const PdfText t = pdf_text(out);
      ASSERT_FALSE(t.words.empty()) << kind << " " << column;
      double left = t.width, top = t.height;
      for (const Word& w : t.words) {
        EXPECT_GE(w.x0, margin - hair) << kind << " " << column << ": '" << w.text << "' in the left margin";
        EXPECT_LE(w.x1, t.width - margin + hair) << kind << " " << column << ": '" << w.text << "' in the right margin";
        EXPECT_GE(w.y0, margin - hair) << kind << " " << column << ": '" << w.text << "' in the top margin";
        EXPECT_LE(w.y1, t.height - margin + hair)
            << kind << " " << column << ": '" << w.text << "' in the bottom margin";
        left = std::min(left, w.x0);
        top = std::min(top, w.y0);
      }
      EXPECT_NEAR(left, margin, 0.1) << kind << " " << column;  // the title's first word
      EXPECT_NEAR(top, margin, 0.1) << kind << " " << column;
      // Drawn extents too (axes, rules, panels, and the words' boxes, which include the font's descent):
      // the blank border is the margin on every side, give or take a glyph's side bearing, anti-aliasing
      // and the page height rounded up to a whole point. The breakdown's bottom was ~10 pt, the
      // double-column distribution's right ~14 pt.
      const InkMargins ink = ink_margins(out);
      double right = 0, bottom = 0;
      for (const Word& w : t.words) right = std::max(right, w.x1), bottom = std::max(bottom, w.y1);
      const std::string at = kind + " " + column + ": blank ";
      for (const auto& [side, blank] : {std::pair<const char*, double>{"left", ink.left},
                                        {"top", ink.top},
                                        {"right", std::min(ink.right, t.width - right)},
                                        {"bottom", std::min(ink.bottom, t.height - bottom)}}) {
        EXPECT_GE(blank, margin - 0.3) << at << side << " " << blank << " pt";
        EXPECT_LE(blank, margin + 1.3) << at << side << " " << blank << " pt";
      }
    }
}

// A prediction inside another (both red): no spot beside the inner one reads as its own, so its confidence
// is left out and the footnote says so; the outer one's and the other picture's stay.
TEST(FigureFiles, ConfidenceLabelsThatCannotBeOwnedAreLeftOutAndCounted) {
  test::TempDir d;
  test::write_figure_study(d, false);
  test::write_text(d / "real/predictions/det/s1.txt", "0 0.30 0.40 0.30 0.35 0.87\n0 0.30 0.40 0.06 0.06 0.55\n");
  const std::string out = d / "nested.pdf";
  const auto r = test::run_ipd("figure pairs " + d.path() +
                               " --column double --layers gt,pred,conf,indices,pairs,legend --out " + out);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const PdfText t = pdf_text(out);
  EXPECT_TRUE(has_word(t, "0.87")) << t.all();
  EXPECT_TRUE(has_word(t, "0.93")) << t.all();
  EXPECT_FALSE(has_word(t, "0.55")) << t.all();
  EXPECT_NE(
      t.all().find(
          "1 confidence label left out: no free spot clearly beside its own box (try --crop or a larger --width-in)"),
      std::string::npos)
      << t.all();
  EXPECT_EQ(t.all().find("labels left out: no room"), std::string::npos) << t.all();
}

TEST(FigureFiles, SvgIsXmlWithASizeAndTextAsText) {
  test::TempDir d;
  test::write_figure_study(d, true);
  const std::string out = d / "p.svg";
  ASSERT_EQ(test::run_ipd("figure pairs " + d.path() + " --out " + out).exit_code, 0);
  const auto r = test::run_command(
      "python3 -c \"import sys, xml.etree.ElementTree as E; r = E.parse(sys.argv[1]).getroot(); "
      "n = '{http://www.w3.org/2000/svg}'; print(r.get('width'), r.get('height'), "
      "' '.join(t.text for t in r.iter(n + 'text')))\" '" +
      out + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.out.substr(0, 9), "252.00pt ");
  EXPECT_NE(r.out.find("scene IPD 0.2182"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find(" x2 "), std::string::npos) << r.out;
  // Small: the font cut to the glyphs used (the whole DejaVu Sans is 757 kB, 1 MB as base64), the pictures
  // as JPEG. The demo's pairs figure went from 4.9 MB to 0.47 MB (docs/benchmarks.md).
  const std::string svg = read_file(out);
  const std::string font = "data:font/ttf;base64,";
  size_t font_bytes = 0;
  int faces = 0;
  for (size_t at = svg.find(font); at != std::string::npos; at = svg.find(font, at + 1), ++faces)
    font_bytes += svg.find(')', at) - at - font.size();
  EXPECT_EQ(faces, 2);  // regular and bold (the picture captions)
  EXPECT_LT(font_bytes, 20000u);
  EXPECT_EQ(svg.find("data:image/png"), std::string::npos);
  EXPECT_NE(svg.find("data:image/jpeg;base64,/9j/"), std::string::npos);  // a JPEG's first bytes, FF D8 FF
}

// A picture that can't be read leaves its place empty with the reason in the figure, and says it on stderr
// (the run exited 0 without a word, the reason only inside the PDF).
TEST(FigureFiles, APictureThatCannotBeReadIsSaidOnStderr) {
  test::TempDir d;
  test::write_figure_study(d, true);
  test::write_text(d / "synth/images/s1.png", "not a picture");
  const auto r = test::run_ipd("figure pairs " + d.path() + " --out " + d / "p.svg");
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_NE(r.err.find("\nwarning: cannot decode " + d / "synth/images/s1.png" + "\n"), std::string::npos) << r.err;
}

TEST(FigureFiles, PngWidthIsInchesTimesDpi) {
  test::TempDir d;
  test::write_figure_study(d, true);
  ASSERT_EQ(test::run_ipd("figure pairs " + d.path() + " --out " + d / "a.png").exit_code, 0);
  EXPECT_EQ(cv::imread(d / "a.png").cols, 1050);  // 3.5 in x 300 dpi
  ASSERT_EQ(test::run_ipd("figure table " + d.path() + " --width-in 2 --dpi 100 --out " + d / "b.png").exit_code, 0);
  EXPECT_EQ(cv::imread(d / "b.png").cols, 200);
  ASSERT_EQ(
      test::run_ipd("figure registration " + d.path() + " --column double --dpi 150 --out " + d / "c.png").exit_code,
      0);
  EXPECT_EQ(cv::imread(d / "c.png").cols, 1074);  // 7.16 in x 150 dpi
}

TEST(FigureFiles, UnknownExtensionIsAUsageErrorAndWritesNothing) {
  test::TempDir d;
  test::write_figure_study(d, false);
  const auto r = test::run_ipd("figure pairs " + d.path() + " --out " + d / "fig.jpg");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.err, "error: " + d / "fig.jpg" +
                       ": unknown figure format '.jpg'; the file name must end in .pdf, .svg or .png\n");
  EXPECT_FALSE(fs::exists(d / "fig.jpg"));
  EXPECT_EQ(test::run_ipd("figure table " + d.path() + " --out " + d / "fig").exit_code, 2);
  EXPECT_FALSE(fs::exists(d / "fig"));
}

TEST(FigureFiles, GuiExportAndCliGiveTheSamePdfForTheSameView) {
  test::TempDir d;
  test::write_figure_study(d, true);
  // The GUI's view: threshold 0.9 (drops real's 0.87 prediction), rock 2 of real paired by hand with rock 1
  // of synth (the edit is saved where `ipd figure` reads it).
  Session s = Session::open(d.path());
  s.set_conf_threshold(0.9);
  run_save_job(s.apply(0, Edit::pair(1, 0)));
  ui::ExportRequest request;  // what the dialog returns by default: pairs, single column
  request.path = d / "gui.pdf";
  request.scene = 0;
  EXPECT_EQ(ui::export_figure(s, request), "exported " + d / "gui.pdf");
  const auto r = test::run_ipd("figure pairs " + d.path() + " --scene s1 --conf 0.9 --out " + d / "cli.pdf");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const PdfText from_gui = pdf_text(d / "gui.pdf"), from_cli = pdf_text(d / "cli.pdf");
  EXPECT_EQ(from_gui.all(), from_cli.all());
  // real has no prediction left: its rock scores 0, synth's 0.8182: IPD 0.8182 over the one (edited) pair.
  EXPECT_NE(from_gui.all().find("scene IPD 0.8182 (1 pair), conf \u2265 0.9, pairs fixed by hand"), std::string::npos)
      << from_gui.all();
  EXPECT_TRUE(has_word(from_gui, "x1"));  // real's rock 1 is unpaired now
  // A different view (no threshold) is a different figure.
  ASSERT_EQ(test::run_ipd("figure pairs " + d.path() + " --scene s1 --out " + d / "other.pdf").exit_code, 0);
  EXPECT_NE(pdf_text(d / "other.pdf").all(), from_gui.all());
}

TEST(FigureFiles, ExportFromTheGuiReportsProblemsInTheStatusLine) {
  test::TempDir d;
  test::write_figure_study(d, false);
  const Session s = Session::open(d.path());
  ui::ExportRequest request;
  request.scene = 0;
  request.path = d / "x.jpg";
  EXPECT_EQ(ui::export_figure(s, request),
            d / "x.jpg" + ": unknown figure format '.jpg'; the file name must end in .pdf, .svg or .png");
  request.path = d / "x.pdf";
  request.scene = 5;
  EXPECT_EQ(ui::export_figure(s, request), "export failed: no scene selected");
  EXPECT_FALSE(fs::exists(d / "x.pdf"));
}

TEST(FigureFiles, CropOfTheGuisZoom) {
  const ui::Crop whole = ui::crop_of_view({1.0f, {0, 0}});
  EXPECT_TRUE(whole.whole());
  // Zoom 4 about the picture point (0.25, 0.75): a quarter of each side around it.
  const ui::Crop c = ui::crop_of_view({4.0f, {-0.25f, 0.25f}});
  EXPECT_NEAR(c.x0, 0.125, 1e-6);
  EXPECT_NEAR(c.x1, 0.375, 1e-6);
  EXPECT_NEAR(c.y0, 0.625, 1e-6);
  EXPECT_NEAR(c.y1, 0.875, 1e-6);
  // Panned past the edge: clamped to the picture.
  const ui::Crop e = ui::crop_of_view({2.0f, {0.4f, 0}});
  EXPECT_NEAR(e.x1, 1.0, 1e-6);
  EXPECT_NEAR(e.x0, 0.65, 1e-6);
}

}  // namespace
}  // namespace ipd
