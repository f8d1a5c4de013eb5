#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <stdexcept>

#include "core/io/label_io.h"
#include "tests/support/test_support.h"

namespace ipd {
namespace {

LabelFile parse_gt(const std::string& text) { return parse_labels(text, "a.txt", {LabelKind::kGroundTruth}); }

std::string only_error(const LabelFile& f) {
  EXPECT_EQ(f.errors.size(), 1u);
  return f.errors.empty() ? "" : f.errors[0].to_string();
}

TEST(LabelIo, ParsesBoxesCommentsAndBlankLines) {
  const LabelFile f = parse_gt("# header\n\n0 0.5 0.25 0.1 0.2\n  1 0.1 0.9 0.05 0.05  # shadow\n");
  ASSERT_TRUE(f.errors.empty());
  ASSERT_EQ(f.boxes.size(), 2u);
  EXPECT_EQ(f.boxes[0].cls, 0);
  EXPECT_DOUBLE_EQ(f.boxes[0].cy, 0.25);
  EXPECT_DOUBLE_EQ(f.boxes[0].conf, 1.0);
  EXPECT_EQ(f.boxes[1].cls, 1);
  EXPECT_EQ(f.line_of_box, (std::vector<int>{3, 4}));
}

// A file over the per-image limit is refused whole with its exact box count; the parse keeps no more than one box
// past the limit in memory (a 16 MB file of short lines would otherwise hold a million).
TEST(LabelIo, AFileOverTheBoxLimitIsRefusedWithItsCountAndBoxesPastItAreNotKept) {
  std::string text;
  for (size_t k = 0; k < kMaxBoxesPerFile + 5; ++k) text += "0 0.5 0.5 0.1 0.1\n";
  const LabelFile f = parse_gt(text);
  ASSERT_EQ(f.errors.size(), 1u);
  EXPECT_TRUE(f.errors[0].unusable_file());
  EXPECT_EQ(f.errors[0].to_string(),
            "a.txt: 20005 boxes, more than the 20000 per image this tool handles "
            "(docs/study-format.md)");
  EXPECT_EQ(f.boxes.size(), kMaxBoxesPerFile + 1);
  EXPECT_EQ(f.line_of_box.size(), kMaxBoxesPerFile + 1);
}

TEST(LabelIo, PredictionsCarryConfidence) {
  const LabelFile f = parse_labels("0 0.5 0.5 0.1 0.1 0.87\n", "p.txt", {LabelKind::kPrediction});
  ASSERT_EQ(f.boxes.size(), 1u);
  EXPECT_DOUBLE_EQ(f.boxes[0].conf, 0.87);
}

TEST(LabelIo, EveryBadLineIsReportedWithFileLineAndWhat) {
  EXPECT_EQ(only_error(parse_gt("0 0.5 0.5\n")), "a.txt:1: expected 5 columns (class cx cy w h), found 3");
  EXPECT_EQ(only_error(parse_labels("0 0.5 0.5 0.1 0.1\n", "p.txt", {LabelKind::kPrediction})),
            "p.txt:1: expected 6 columns (class cx cy w h conf), found 5");
  EXPECT_EQ(only_error(parse_gt("0 0.5 abc 0.1 0.1\n")), "a.txt:1: expected a number for cy in column 3, found 'abc'");
  EXPECT_EQ(only_error(parse_gt("0 nan 0.5 0.1 0.1\n")),
            "a.txt:1: expected a finite number for cx in column 2, found 'nan'");
  EXPECT_EQ(only_error(parse_gt("0 0.5 0.5 inf 0.1\n")),
            "a.txt:1: expected a finite number for w in column 4, found 'inf'");
  EXPECT_EQ(only_error(parse_gt("0 0.5 0.5 0 0.1\n")),
            "a.txt:1: expected w >= 1e-06 (a millionth of the picture), found 0");
  // Tiny but positive: its area underflows (1e-300 squared is 0), so not even its copy pairs with it.
  EXPECT_EQ(only_error(parse_gt("0 0.5 0.5 0.1 1e-300\n")),
            "a.txt:1: expected h >= 1e-06 (a millionth of the picture), found 1e-300");
  EXPECT_EQ(only_error(parse_gt("0 0.5 0.5 0.1 -0.2\n")), "a.txt:1: expected h in [0, 1] (normalised), found -0.2");
  EXPECT_EQ(only_error(parse_gt("1.5 0.5 0.5 0.1 0.1\n")),
            "a.txt:1: expected a non-negative integer class in column 1, found '1.5'");
  EXPECT_EQ(only_error(parse_gt("-1 0.5 0.5 0.1 0.1\n")),
            "a.txt:1: expected a non-negative integer class in column 1, found '-1'");
  EXPECT_EQ(only_error(parse_gt("0 1.2 0.5 0.1 0.1\n")), "a.txt:1: expected cx in [0, 1] (normalised), found 1.2");
  // A file name pasted into a label line, as found in POLAR-Sim.
  EXPECT_EQ(only_error(parse_gt("01_A_off_180_L_0016.png\n")),
            "a.txt:1: expected 5 columns (class cx cy w h), found 1");
}

// strtod stops at the first byte it can't use: a field ending in a zero-filled block (what a crash leaves
// in a file being written) read as the number before it, and the rock kept a wrong height.
TEST(LabelIo, AByteThatIsNotPartOfTheNumberIsAnErrorNamingTheLine) {
  using namespace std::string_literals;
  EXPECT_EQ(only_error(parse_gt("0 0.5 0.5 0.1 0.20\0\0\0\0\n"s)),
            "a.txt:1: expected a number for h in column 5, found '0.20\\x00\\x00\\x00\\x00'");
  EXPECT_EQ(only_error(parse_labels("0 0.5 0.5 0.1 0.1 0.9\0 4782\n"s, "p.txt", {LabelKind::kPrediction})),
            "p.txt:1: expected 6 columns (class cx cy w h conf), found 7");
  EXPECT_EQ(only_error(parse_labels("0 0.5 0.5 0.1 0.1 0.9\0\n"s, "p.txt", {LabelKind::kPrediction})),
            "p.txt:1: expected a number for conf in column 6, found '0.9\\x00'");
  EXPECT_EQ(only_error(parse_gt("\n0 0.5\x01 0.5 0.1 0.1\n")),
            "a.txt:2: expected a number for cx in column 2, found '0.5\\x01'");
  EXPECT_EQ(only_error(parse_gt("0\0 0.5 0.5 0.1 0.1\n"s)),
            "a.txt:1: expected a non-negative integer class in column 1, found '0\\x00'");
  EXPECT_EQ(only_error(parse_gt("0 0x1p-2 0.5 0.1 0.1\n")),
            "a.txt:1: expected a number for cx in column 2, found '0x1p-2'");
  EXPECT_EQ(only_error(parse_gt("0 0.5 0.5e 0.1 0.1\n")),
            "a.txt:1: expected a number for cy in column 3, found '0.5e'");
  EXPECT_EQ(only_error(parse_gt("0 0.5 0.5 . 0.1\n")), "a.txt:1: expected a number for w in column 4, found '.'");
  EXPECT_EQ(only_error(parse_gt("0 -Infinity 0.5 0.1 0.1\n")),
            "a.txt:1: expected a finite number for cx in column 2, found '-Infinity'");
  // Every decimal spelling a label tool writes still reads.
  const LabelFile ok = parse_gt("0 +0.5 .25 5e-2 1.E-1\n");
  ASSERT_TRUE(ok.errors.empty()) << ok.errors[0].to_string();
  ASSERT_EQ(ok.boxes.size(), 1u);
  EXPECT_DOUBLE_EQ(ok.boxes[0].cx, 0.5);
  EXPECT_DOUBLE_EQ(ok.boxes[0].cy, 0.25);
  EXPECT_DOUBLE_EQ(ok.boxes[0].w, 0.05);
  EXPECT_DOUBLE_EQ(ok.boxes[0].h, 0.1);
}

TEST(LabelIo, SmallRoundingOutsideTheUnitRangeIsAccepted) {
  const LabelFile f = parse_gt("0 1.0004 -0.0003 0.1 0.1\n");
  EXPECT_TRUE(f.errors.empty());
  EXPECT_EQ(f.boxes.size(), 1u);
}

TEST(LabelIo, AllErrorsNotOnlyTheFirstAndGoodLinesKept) {
  const LabelFile f = parse_gt("0 0.5 0.5 0.1 0.1\nbad\n0 0.5 0.5 0.1\n0 0.2 0.2 0.1 0.1\n");
  ASSERT_EQ(f.errors.size(), 2u);
  EXPECT_EQ(f.errors[0].line, 2);
  EXPECT_EQ(f.errors[1].line, 3);
  EXPECT_EQ(f.boxes.size(), 2u);
  EXPECT_EQ(f.line_of_box, (std::vector<int>{1, 4}));
}

TEST(LabelIo, MissingFileIsAnEmptyImageUnreadableIsAnError) {
  test::TempDir dir;
  const LabelFile missing = read_labels(dir / "nope.txt", {});
  EXPECT_FALSE(missing.exists);
  EXPECT_TRUE(missing.boxes.empty());
  EXPECT_TRUE(missing.errors.empty());
  test::write_text(dir / "sub/x.txt", "");
  const LabelFile is_dir = read_labels(dir / "sub", {});
  ASSERT_EQ(is_dir.errors.size(), 1u);
  EXPECT_EQ(is_dir.errors[0].to_string(), dir / "sub" + ": is a directory, expected a file");
}

TEST(LabelIo, ClassAndConfidenceFilters) {
  LabelFile f = parse_labels("0 0.5 0.5 0.1 0.1 0.9\n1 0.5 0.5 0.1 0.1 0.9\n0 0.2 0.2 0.1 0.1 0.1\n", "p.txt",
                             {LabelKind::kPrediction});
  keep_class(&f, 0);
  ASSERT_EQ(f.boxes.size(), 2u);
  keep_confident(&f, 0.25);
  ASSERT_EQ(f.boxes.size(), 1u);
  EXPECT_EQ(f.line_of_box[0], 1);
}

TEST(LabelIo, WriteThenReadRoundTrips) {
  test::TempDir dir;
  Box b;
  b.cls = 2, b.cx = 0.125, b.cy = 0.5, b.w = 0.25, b.h = 0.0625, b.conf = 0.5;
  write_labels(dir / "deep/p.txt", {b}, LabelKind::kPrediction);
  const LabelFile f = read_labels(dir / "deep/p.txt", {LabelKind::kPrediction});
  ASSERT_EQ(f.boxes.size(), 1u);
  EXPECT_EQ(f.boxes[0].cls, 2);
  EXPECT_DOUBLE_EQ(f.boxes[0].w, 0.25);
  EXPECT_DOUBLE_EQ(f.boxes[0].conf, 0.5);
}

// A file read in pieces parses as the whole text: pieces of every size cut lines (and the BOM) anywhere.
TEST(LabelIo, APieceByPieceParseEqualsTheWholeTextsParse) {
  const std::string text =
      "\xEF\xBB\xBF"
      "0 0.5 0.5 0.1 0.2 0.9\r\n# rocks\n\n0 0.25 0.75 0.05\nx\n0 0.3 0.3 0.1 0.1 0.4\n0 0.6 0.6 0.2 0.2 "
      "0.7";
  const LabelFile whole = parse_labels(text, "f.txt", {LabelKind::kPrediction});
  ASSERT_EQ(whole.boxes.size(), 3u);
  ASSERT_EQ(whole.errors.size(), 2u);
  EXPECT_EQ(whole.line_of_box, (std::vector<int>{1, 6, 7}));
  for (size_t piece = 1; piece <= text.size(); ++piece) {
    LabelParser p("f.txt", {LabelKind::kPrediction});
    for (size_t at = 0; at < text.size(); at += piece) p.feed(std::string_view(text).substr(at, piece));
    const LabelFile f = p.finish();
    ASSERT_EQ(f.boxes.size(), whole.boxes.size()) << "pieces of " << piece;
    for (size_t k = 0; k < f.boxes.size(); ++k) {
      EXPECT_EQ(f.boxes[k].cx, whole.boxes[k].cx) << "pieces of " << piece;
      EXPECT_EQ(f.boxes[k].conf, whole.boxes[k].conf) << "pieces of " << piece;
    }
    EXPECT_EQ(f.line_of_box, whole.line_of_box) << "pieces of " << piece;
    ASSERT_EQ(f.errors.size(), whole.errors.size()) << "pieces of " << piece;
    for (size_t k = 0; k < f.errors.size(); ++k)
      EXPECT_EQ(f.errors[k].to_string(), whole.errors[k].to_string()) << "pieces of " << piece;
  }
}

// A study's label file is parsed as it is read (read_labels_beneath): the same boxes and errors as its text.
TEST(LabelIo, AStudysLabelFileReadBelowItsRootParsesAsItsText) {
  test::TempDir d;
  std::string text;
  for (int k = 0; k < 3000; ++k) text += "0 0.5 0.5 0.1 0.2 0.9\n";  // 66,000 bytes: two pieces of the read
  text += "0 0.5\n";
  test::write_text(d / "real/labels/s.txt", text);
  const LabelFile f = read_labels_beneath(d.path(), "real/labels/s.txt", {LabelKind::kPrediction});
  EXPECT_EQ(f.boxes.size(), 3000u);
  ASSERT_EQ(f.errors.size(), 1u);
  EXPECT_EQ(f.errors[0].line, 3001);
  EXPECT_EQ(f.path, d.path() + "/real/labels/s.txt");
  EXPECT_FALSE(read_labels_beneath(d.path(), "real/labels/none.txt", {}).exists);
}

}  // namespace
}  // namespace ipd

namespace ipd {
namespace {

// Random bytes and mutated label lines never crash the parser: every line is a box or an error.
TEST(LabelIo, GarbageNeverCrashesAndEveryLineIsAccountedFor) {
  std::mt19937 g(12);
  const std::string alphabet = "0123456789.-+eE nNaAiIfF#\t\r\x01\xff,;x";
  for (int round = 0; round < 3000; ++round) {
    std::string text;
    const int lines = static_cast<int>(g() % 6);
    for (int l = 0; l < lines; ++l) {
      if (g() % 2) {
        text += "0 0.5 0.5 0.1 0.1";  // a valid line, then mutate a few characters
        for (int m = static_cast<int>(g() % 4); m > 0; --m)
          text[text.size() - 1 - g() % 17] = alphabet[g() % alphabet.size()];
      } else {
        for (int c = static_cast<int>(g() % 40); c > 0; --c) text += alphabet[g() % alphabet.size()];
      }
      text += '\n';
    }
    for (const auto kind : {LabelKind::kGroundTruth, LabelKind::kPrediction}) {
      const LabelFile f = parse_labels(text, "fuzz.txt", {kind});
      for (const auto& b : f.boxes) {
        ASSERT_TRUE(std::isfinite(b.cx) && std::isfinite(b.w) && b.w > 0 && b.h > 0) << text;
        ASSERT_GE(b.cls, 0);
      }
      for (const auto& e : f.errors) ASSERT_EQ(e.to_string().rfind("fuzz.txt:", 0), 0u);
      // Every box line (anything but blanks before a '#') is a box or an error: none is dropped.
      size_t box_lines = 0, start = 0;
      while (start < text.size()) {
        size_t eol = text.find('\n', start);
        if (eol == std::string::npos) eol = text.size();
        const std::string line = text.substr(start, std::min(eol, text.find('#', start)) - start);
        if (line.find_first_not_of(" \t\r\v\f") != std::string::npos) ++box_lines;
        start = eol + 1;
      }
      size_t accounted = f.boxes.size();
      for (const auto& e : f.errors) accounted += static_cast<size_t>(e.malformed_lines());
      ASSERT_EQ(accounted, box_lines) << text;
    }
  }
}

TEST(LabelIo, GarbageStudyFilesGiveExitOneNotACrash) {
  test::TempDir d;
  std::mt19937 g(5);
  std::string junk;
  for (int k = 0; k < 4000; ++k) junk += static_cast<char>(g() % 256);
  test::write_text(d / "real/labels/a.txt", junk);
  test::write_text(d / "synth/labels/a.txt", "0 0.5 0.5 0.1 0.1\n");
  test::write_text(d / "real/predictions/m/a.txt", junk.substr(100));
  test::write_text(d / "synth/predictions/m/a.txt", "");
  auto r = test::run_ipd("table " + d.path());
  EXPECT_EQ(r.exit_code, 1) << r.err;
  r = test::run_ipd("table " + d.path() + " --skip-bad-lines");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  test::write_text(d / "pairs/real__synth/a.json", junk);
  r = test::run_ipd("table " + d.path() + " --skip-bad-lines");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find(d / "pairs/real__synth/a.json" + ": invalid JSON"), std::string::npos) << r.err;
  test::write_text(d / "study.yaml", junk.substr(0, 300));
  r = test::run_ipd("table " + d.path());
  EXPECT_EQ(r.exit_code, 1) << r.err;
}

// A negative or whole-unit tolerance would let values far outside the image through: refused by name.
TEST(LabelParseOptions, NameTheBadField) {
  LabelParseOptions o;
  EXPECT_EQ(o.validate(), "");
  o.range_tolerance = -0.01;
  EXPECT_EQ(o.validate(), "range_tolerance must be in [0, 1), got -0.01");
  o.range_tolerance = 1;
  try {
    parse_labels("0 0.5 0.5 0.1 0.1\n", "a.txt", o);
    FAIL() << "parse_labels accepted a tolerance of 1";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "label parse options: range_tolerance must be in [0, 1), got 1");
  }
}

}  // namespace
}  // namespace ipd
