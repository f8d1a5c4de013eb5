// The font an SVG figure embeds: only the glyphs it uses, each with the full font's advance width (so the
// text lays out exactly as measured when the figure was drawn).
#include <gtest/gtest.h>

#include "core/util/atomic_file.h"
#include "tests/support/test_support.h"
#include "ui/canvas/canvas.h"
#include "ui/canvas/font_subset.h"

namespace ipd {
namespace {

TEST(FontSubset, CodePointsOfUtf8) {
  std::set<char32_t> cps;
  ui::add_code_points("a\u2212\u00a0\xff", &cps);  // a, minus sign, no-break space, a stray byte
  EXPECT_EQ(cps, (std::set<char32_t>{U'a', 0x00A0, 0x2212, 0xFFFD}));
}

TEST(FontSubset, KeepsTheUsedGlyphsWithTheirWidths) {
  test::TempDir d;
  const std::string text = "scene IPD 0.2182 \u2212 |real \u2212 hapke|";
  std::set<char32_t> cps;
  ui::add_code_points(text, &cps);
  const std::string subset = ui::subset_font(ui::default_font_file(), cps);
  EXPECT_LT(subset.size(), 12000u);  // DejaVu Sans is 757 kB
  write_file_atomically(d / "subset.ttf", subset);
  const ui::FontMetrics full(ui::default_font_file()), cut(d / "subset.ttf");
  const ui::TextStyle st{8.0, ui::rgb(0, 0, 0), false};
  EXPECT_NEAR(cut.measure(st, text).x, full.measure(st, text).x, 1e-6);
  EXPECT_NEAR(cut.ascent(st), full.ascent(st), 1e-6);
  // A letter the figure did not use is not in the subset (it would be drawn as the missing glyph).
  EXPECT_NE(cut.measure(st, "W").x, full.measure(st, "W").x);
}

TEST(FontSubset, UnreadableFontIsNamed) {
  try {
    ui::subset_font("/nonexistent/font.ttf", {U'a'});
    FAIL() << "no exception";
  } catch (const std::runtime_error& e) {
    EXPECT_STREQ(e.what(), "/nonexistent/font.ttf: cannot read the font file");
  }
}

}  // namespace
}  // namespace ipd
