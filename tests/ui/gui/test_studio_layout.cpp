// ipd-studio's window layout and UI wording rules (ui/gui/studio_layout.h), with hand-computed numbers.
#include <gtest/gtest.h>

#include <cstdio>

#include <algorithm>
#include <cmath>

#include "ui/gui/rank_view.h"
#include "ui/gui/stats_panels.h"
#include "ui/gui/studio_layout.h"
#include "ui/gui/views.h"

namespace ipd::ui {
namespace {

// The pictures stack when that shows them larger: a centre 880 x 760 px with 16:10 pictures (gap 6, caption
// lines 20): side by side each pane is 437 x 740, the picture 437 x 273.1 (119,355 px²); stacked each pane is
// 880 x ((760 - 6) / 2 - 20 = 357), the picture 571.2 x 357 (203,918 px²). A 1584 px wide focus view puts them
// side by side: panes 789 x 740, pictures 789 x 493.1 (389,076 px², against the same 203,918 stacked).
TEST(PicturePanes, TheLargerOfSideBySideAndStacked) {
  const PicturePanes centre = picture_panes(880, 760, 1.6f, 6, 20);
  EXPECT_TRUE(centre.stacked);
  EXPECT_FLOAT_EQ(centre.pane_w, 880);
  EXPECT_FLOAT_EQ(centre.pane_h, 357);
  EXPECT_FLOAT_EQ(centre.picture_w, 571.2f);
  EXPECT_FLOAT_EQ(centre.picture_h, 357);
  const PicturePanes focus = picture_panes(1584, 760, 1.6f, 6, 20);
  EXPECT_FALSE(focus.stacked);
  EXPECT_FLOAT_EQ(focus.pane_w, 789);
  EXPECT_FLOAT_EQ(focus.pane_h, 740);
  EXPECT_FLOAT_EQ(focus.picture_w, 789);
  EXPECT_FLOAT_EQ(focus.picture_h, 493.125f);
  const PicturePanes tiny = picture_panes(10, 10, 1.6f, 6, 20);  // nothing fits: empty, never negative
  EXPECT_GE(tiny.picture_w, 0);
  EXPECT_GE(tiny.picture_h, 0);
}

// Columns that don't fit are never cut: the font shrinks to fit in steps of 5% (each step a table of its own, as a
// table sets its column widths once), down to 80% of its size, then the table scrolls sideways at that size.
TEST(StudioColumns, ATableTooWideShrinksItsFontBeforeItScrolls) {
  // 100 px of cell padding, which the font does not shrink, and 300 px of text at the normal size.
  auto needed = [](float s) { return 100 + 300 * s; };
  EXPECT_FLOAT_EQ(table_font_scale(needed, 420), 1.0f);  // fits: the normal font
  EXPECT_FLOAT_EQ(table_font_scale(needed, 370), 0.9f);
  EXPECT_FLOAT_EQ(table_font_scale(needed, 360), 0.85f);               // 0.8667: the step below, so it fits
  EXPECT_FLOAT_EQ(table_font_scale(needed, 300), kMinTableFontScale);  // past it: scrolls at 80%
  EXPECT_FLOAT_EQ(kMinTableFontScale, 0.8f);
  EXPECT_EQ(scaled_table_id("scenes", 0.85f), "scenes##85");
  EXPECT_EQ(scaled_table_id("pairs", 1.0f), "pairs##100");
}

TEST(StudioColumns, WideWindowKeepsPreferredSideWidths) {
  // 1600 - 2*6 = 1588 usable; 380 + 400 + max(320, 0.45 * 1588 = 714.6) = 1494.6 fits.
  const StudioColumns c = studio_columns(1600, 380, 400, 6);
  EXPECT_FALSE(c.tabbed_side);
  EXPECT_FLOAT_EQ(c.left, 380);
  EXPECT_FLOAT_EQ(c.right, 400);
  EXPECT_FLOAT_EQ(c.centre, 808);
  EXPECT_FALSE(c.tabbed_centre);
}

TEST(StudioColumns, AtTwelveEightyTheBrowserGivesWayToTheStatistics) {
  // 1280: usable 1268, the centre keeps 0.45 * 1268 = 570.6; the sides have 697.4 for 500 + 400. The statistics
  // keep 400 (the cross table whole) and the browser takes the 297.4 left, over its 260 floor.
  const StudioColumns c = studio_columns(1280, 500, 400, 6);
  EXPECT_FLOAT_EQ(c.right, 400);
  EXPECT_NEAR(c.left, 297.4, 1e-3);
  EXPECT_NEAR(c.centre, 570.6, 1e-3);
  EXPECT_FALSE(c.tabbed_centre);
  // 1200: usable 1188, the centre keeps 534.6 and the sides 653.4, so 253.4 would be left for the browser, under
  // 260: both shrink in proportion from 260 : 400.
  EXPECT_NEAR(studio_columns(1200, 500, 400, 6).right, 653.4 * 400 / 660, 1e-3);
  // No jump at the boundary (the statistics fell from 400 to 300 px between 1236 and 1228 px): each pixel of
  // window costs the statistics less than a pixel.
  for (float w = 1000; w < 1600; w += 1)
    EXPECT_LE(std::abs(studio_columns(w + 1, 500, 400, 6).right - studio_columns(w, 500, 400, 6).right), 1.0f) << w;
}

TEST(StudioColumns, NarrowerWindowShrinksSidesInProportion) {
  // 1000: usable 988, the centre keeps 0.45 * 988 = 444.6; the sides' 543.4 can't hold 400 + 260, so they share
  // it as 260:400 (the browser's floor to the statistics) -> 214.08 and 329.33.
  const StudioColumns c = studio_columns(1000, 380, 400, 6);
  EXPECT_FALSE(c.tabbed_side);
  EXPECT_NEAR(c.left, 543.4 * 260 / 660, 1e-3);
  EXPECT_NEAR(c.right, 543.4 * 400 / 660, 1e-3);
  EXPECT_NEAR(c.centre, 444.6, 1e-3);
  EXPECT_TRUE(c.tabbed_centre);  // 444.6 < 560: registration and pairs as tabs
}

TEST(StudioColumns, SideMinimumsHoldWhenOnePreferenceIsSmall) {
  // 1000, prefs 100 and 700: proportional 543.4 / 8 = 67.9 is under 160, so the browser gets 160 and the
  // statistics 543.4 - 160 = 383.4.
  const StudioColumns c = studio_columns(1000, 100, 700, 6);
  EXPECT_FLOAT_EQ(c.left, 160);
  EXPECT_NEAR(c.right, 383.4, 1e-3);
  EXPECT_NEAR(c.centre, 444.6, 1e-3);
}

TEST(StudioColumns, BelowNineHundredTheSidesShareOneTabbedColumn) {
  // 700: usable 694; the tabbed column takes 40% (277.6), the centre 416.4.
  const StudioColumns c = studio_columns(700, 380, 400, 6);
  EXPECT_TRUE(c.tabbed_side);
  EXPECT_NEAR(c.left, 277.6, 1e-3);
  EXPECT_FLOAT_EQ(c.right, 0);
  EXPECT_NEAR(c.centre, 416.4, 1e-3);
  EXPECT_TRUE(c.tabbed_centre);
  // Never wider than either side wants, never under the browser's minimum.
  EXPECT_FLOAT_EQ(studio_columns(880, 200, 250, 6).left, 250);
  EXPECT_FLOAT_EQ(studio_columns(300, 380, 400, 6).left, 160);
}

float chars(const std::string& s) { return 10.0f * static_cast<float>(s.size()); }  // 10 px per character

TEST(WrapAtSpaces, NeverInsideANumber) {
  // 150 px = 15 characters: "confidence 0.97" is exactly 15 and stays whole.
  EXPECT_EQ(wrap_at_spaces("score 16.8972, confidence 0.97", 150, chars),
            (std::vector<std::string>{"score 16.8972,", "confidence 0.97"}));
  // 140 px: the numbers stay whole (ImGui's own wrap broke one after the point), "0.97" with its label.
  EXPECT_EQ(wrap_at_spaces("confidence 0.97 delta -0.064", 140, chars),
            (std::vector<std::string>{"confidence 0.97", "delta -0.064"}));
  // 100 px: "x 16.8972" has no label to keep, so the number alone moves down whole.
  EXPECT_EQ(wrap_at_spaces("abcdefg x 16.8972", 100, chars), (std::vector<std::string>{"abcdefg x", "16.8972"}));
}

TEST(WrapAtSpaces, NeverBetweenALabelAndItsNumber) {
  // 150 px: "delta -0.0799 p" is 15 characters and would fit, leaving "= 0.031" alone on the next line; the
  // label goes down with its number instead.
  EXPECT_EQ(wrap_at_spaces("delta -0.0799 p = 0.031", 150, chars),
            (std::vector<std::string>{"delta -0.0799", "p = 0.031"}));
  EXPECT_EQ(wrap_at_spaces("x p < 0.0001 y", 100, chars), (std::vector<std::string>{"x", "p < 0.0001", "y"}));
}

TEST(WrapAtSpaces, NeverBetweenANumberAndItsUnit) {
  // 230 px: "pairs: typical residual 0.3" is 27 characters and would fit, leaving "px" alone (the studio's pair
  // header at 1920 px); the number goes down with its unit.
  EXPECT_EQ(wrap_at_spaces("pairs: typical residual 0.3 px", 270, chars),
            (std::vector<std::string>{"pairs: typical residual", "0.3 px"}));
  EXPECT_EQ(wrap_at_spaces("took 12.5 ms, then", 90, chars), (std::vector<std::string>{"took", "12.5 ms,", "then"}));
  // An IPD and its value: the single-column scene figure's title broke "scene IPD" / "0.0404".
  EXPECT_EQ(wrap_at_spaces("model det-real, scene IPD 0.0404 (12 pairs)", 250, chars),
            (std::vector<std::string>{"model det-real,", "scene IPD 0.0404", "(12 pairs)"}));
  // Nor a score or a confidence from its value (the registration panel at 1236 px).
  EXPECT_EQ(wrap_at_spaces("15 inliers, score 0.0244, confidence 0.11", 200, chars),
            (std::vector<std::string>{"15 inliers,", "score 0.0244,", "confidence 0.11"}));
  // Nor "0 / 0" (the studio's "unpaired 0 / 0" at 1024 px).
  EXPECT_EQ(wrap_at_spaces("17 pairs, unpaired 0 / 0", 200, chars),
            (std::vector<std::string>{"17 pairs, unpaired", "0 / 0"}));
  // A word that merely follows a number is free to wrap.
  EXPECT_EQ(wrap_at_spaces("0.3 pixels", 50, chars), (std::vector<std::string>{"0.3", "pixels"}));
}

TEST(WrapAtSpaces, NeverBetweenACountAndTheWordItCounts) {
  // 120 px: "(exact), 8" is 10 characters and would fit, leaving "scenes" alone (ipd-studio's compare sentence
  // at 1000 px); the count goes down with its word.
  EXPECT_EQ(wrap_at_spaces("p = 0.0078 (exact), 8 scenes", 120, chars),
            (std::vector<std::string>{"p = 0.0078", "(exact),", "8 scenes"}));
  EXPECT_EQ(wrap_at_spaces("tried 1,000 trials", 110, chars), (std::vector<std::string>{"tried", "1,000 trials"}));
  // Not counts: a decimal ("0.97 delta" may part), a number ending its clause ("8,"), a count before a sign.
  EXPECT_EQ(wrap_at_spaces("x 0.97 delta", 60, chars), (std::vector<std::string>{"x 0.97", "delta"}));
  EXPECT_EQ(wrap_at_spaces("n 8, scenes", 40, chars), (std::vector<std::string>{"n 8,", "scenes"}));
  EXPECT_EQ(wrap_at_spaces("8 -1", 30, chars), (std::vector<std::string>{"8", "-1"}));
}

TEST(WrapAtSpaces, NeverInsideDeltaIpd) {
  // 590 px = 59 characters: "principled is closer to real than hapke for det-real: delta" is exactly 59 and
  // would fit, leaving "IPD = -0.0802 ..." to start the next line (ipd-studio's compare sentence at 1600 px
  // in ASCII). "delta IPD" goes down whole, with its number.
  const std::string s = "principled is closer to real than hapke for det-real: delta IPD = -0.0802 [-0.094, -0.066]";
  EXPECT_EQ(wrap_at_spaces(s, 590, chars),
            (std::vector<std::string>{"principled is closer to real than hapke for det-real:",
                                      "delta IPD = -0.0802 [-0.094, -0.066]"}));
  EXPECT_EQ(wrap_at_spaces("x delta IPD y", 70, chars), (std::vector<std::string>{"x", "delta IPD", "y"}));
  // Only "delta" before "IPD": "delta" before a number may part, as may "IPD" after another word.
  EXPECT_EQ(wrap_at_spaces("x delta -0.08", 70, chars), (std::vector<std::string>{"x delta", "-0.08"}));
  EXPECT_EQ(wrap_at_spaces("x deltas IPD", 80, chars), (std::vector<std::string>{"x deltas", "IPD"}));
}

TEST(UiWording, GlyphsTheFontLacksAreSpelledInAscii) {
  const std::string s = "a is closer: \u0394IPD = \u22120.0802 [\u22120.094, \u22120.066]";
  auto has = [](std::vector<char32_t> glyphs) {
    return [glyphs](char32_t g) { return std::find(glyphs.begin(), glyphs.end(), g) != glyphs.end(); };
  };
  EXPECT_EQ(spell_missing_glyphs(s, has({U'\u0394', U'\u2212'})), s);  // DejaVu Sans, as ipd-studio loads it
  EXPECT_EQ(spell_missing_glyphs(s, has({})), "a is closer: delta IPD = -0.0802 [-0.094, -0.066]");  // ImGui's own
  EXPECT_EQ(spell_missing_glyphs(s, has({U'\u0394'})), "a is closer: \u0394IPD = -0.0802 [-0.094, -0.066]");
  EXPECT_EQ(spell_missing_glyphs("\u0394 alone", has({})), "\u0394 alone");  // only the symbol ΔIPD is spelled out
}

TEST(UiWording, CompareNumbersLineWritesDeltaIpdAsTheSentenceDoes) {
  // The 8-scene demo's compare panel: the line above the sentence writes ΔIPD and the typographic minus as the
  // sentence under it does, not "delta -0.0802 [-0.094, -0.066]   p = 0.0078" in ASCII.
  Comparison r;
  r.delta.estimate = -0.08021, r.delta.low = -0.09412, r.delta.high = -0.06561;
  r.p_value = 0.0078125, r.scenes = 8;
  const std::string line = compare_delta_line(r);
  EXPECT_EQ(line, "\u0394IPD = \u22120.0802 [\u22120.094, \u22120.066]   p = 0.0078");
  EXPECT_EQ(spell_missing_glyphs(line, [](char32_t) { return false; }),
            "delta IPD = -0.0802 [-0.094, -0.066]   p = 0.0078");  // ImGui's own font
  // "ΔIPD" never parts from its number, nor "p" from its value.
  auto bytes = [](const std::string& t) { return 10.0f * static_cast<float>(t.size()); };
  EXPECT_EQ(wrap_at_spaces(line, 190, bytes),
            (std::vector<std::string>{"\u0394IPD = \u22120.0802", "[\u22120.094,", "\u22120.066]", "p = 0.0078"}));
  // A number rounding to zero has no minus; a tiny p is never in scientific notation.
  r.delta.estimate = -0.00001, r.delta.low = -0.0004, r.delta.high = 0.02, r.p_value = 0.00001;
  EXPECT_EQ(compare_delta_line(r), "\u0394IPD = 0.0000 [0.000, 0.020]   p < 0.0001");
  // Fewer than two scenes: neither interval nor test; no interval or no p: left out, never "nan".
  r.scenes = 1, r.delta.estimate = 0.02;
  EXPECT_EQ(compare_delta_line(r), "\u0394IPD = 0.0200, 1 scene: no interval, no test");
  r.scenes = 5, r.delta.low = r.delta.high = r.p_value = std::nan("");
  EXPECT_EQ(compare_delta_line(r), "\u0394IPD = 0.0200");
}

TEST(WrapAtSpaces, LongWordOnItsOwnLineAndNewlinesKept) {
  // (A decimal: a whole number would keep "b" as the word it counts.)
  EXPECT_EQ(wrap_at_spaces("a 1234567890.12 b", 50, chars), (std::vector<std::string>{"a", "1234567890.12", "b"}));
  EXPECT_EQ(wrap_at_spaces("a 1234567 scenes", 50, chars), (std::vector<std::string>{"a", "1234567 scenes"}));
  EXPECT_EQ(wrap_at_spaces("one\ntwo three", 1000, chars), (std::vector<std::string>{"one", "two three"}));
  EXPECT_EQ(wrap_at_spaces("", 100, chars), std::vector<std::string>{});
}

TEST(UiWording, CountedNounsThousandsAndNoNegativeZero) {
  EXPECT_EQ(counted(1, "trial"), "1 trial");
  EXPECT_EQ(counted(0, "scene"), "0 scenes");
  EXPECT_EQ(counted(5982, "hypothesis", "hypotheses"), "5,982 hypotheses");
  EXPECT_EQ(counted(1, "hypothesis", "hypotheses"), "1 hypothesis");
  EXPECT_EQ(thousands(89700), "89,700");
  EXPECT_EQ(thousands(999), "999");
  EXPECT_EQ(thousands(-1234567), "-1,234,567");
  EXPECT_EQ(thousands(0), "0");
  // The slider's threshold is the decimal it shows, exactly as `--conf 0.3` reads it.
  EXPECT_EQ(conf_slider_value(0.3f), 0.3);
  EXPECT_EQ(conf_slider_value(0.30000001), 0.3);
  EXPECT_EQ(conf_slider_value(0.7049), 0.7);
  EXPECT_EQ(conf_slider_value(0.705), 0.71);
  EXPECT_EQ(conf_slider_value(1.2), 1.0);
  EXPECT_EQ(conf_slider_value(-0.1), 0.0);
  EXPECT_EQ(problems_label(1), "1 problem");
  EXPECT_EQ(problems_label(12345), "12,345 problems");
  EXPECT_EQ(fixed(-0.000001, 5), "0.00000");
  EXPECT_EQ(fixed(-0.0000051, 5), "-0.00001");
  EXPECT_EQ(fixed(-0.064, 3), "-0.064");
  EXPECT_EQ(fixed(0.0, 2), "0.00");
}

TEST(RegistrationWords, SingularCountsPlainNumbersOneStepNumber) {
  RegistrationReport r;
  r.method = RegistrationMethod::kConsensus;
  r.samples = 1, r.hypotheses = 1, r.inliers = 17, r.fit = {FitMeasure::kSoftInliers, 16.89721}, r.confidence = 0.8449;
  EXPECT_EQ(registration_summary("real", "principled", r),
            "real -> principled: consensus, 1 trial, 1 hypothesis, 17 inliers, soft inliers 16.8972, confidence 0.84");
  r.samples = 40, r.hypotheses = 5982, r.inliers = 1, r.fit.value = -0.0000001, r.confidence = -0.000001;
  EXPECT_EQ(registration_summary("a", "b", r),
            "a -> b: consensus, 40 trials, 5,982 hypotheses, 1 inlier, soft inliers 0.0000, confidence 0.00");
  // Identical layouts need no search: nothing is scored, and no 0 is printed that reads as a perfect fit.
  r.samples = 0, r.hypotheses = 0, r.fit = {};
  EXPECT_EQ(registration_summary("a", "b", r),
            "a -> b: consensus, 0 trials, 0 hypotheses, 1 inlier, not scored, confidence 0.00");
  // cpd counts EM iterations, never trials or hypotheses, and measures its fit as the mixture's width.
  r.method = RegistrationMethod::kCpd;
  r.samples = 0, r.em_iterations = 22, r.hypotheses = 22, r.inliers = 17, r.confidence = 1;
  r.fit = {FitMeasure::kMixtureWidth, 0.00031};
  EXPECT_EQ(registration_summary("real", "principled", r),
            "real -> principled: cpd, 22 EM iterations, 17 inliers, mixture width 0.0003, confidence 1.00");
  r.em_iterations = 1;
  EXPECT_EQ(registration_summary("a", "b", r).substr(0, 28), "a -> b: cpd, 1 EM iteration,");
  TraceStep st;
  st.kind = TraceStepKind::kHypothesis;
  st.fit = 0.5, st.best_fit = 0.75, st.inliers_a = {3};
  // k = 349 is the 350th step: the scrubber reads "step 350 of 5,000" too.
  EXPECT_EQ(replay_step_line(st, FitMeasure::kMeanDistance, 349, 5000),
            "step 350 of 5,000 (hypothesis): mean distance 0.5000, best so far 0.7500, 1 inlier");
  // Consensus' last step is the fit that goes out, judged among the polished, the searched and plain least
  // squares (or the second look's pick): "polish" would name only the first of them.
  st.kind = TraceStepKind::kPolish, st.fit = st.best_fit = 16.89719, st.inliers_a.assign(17, 0);
  EXPECT_EQ(replay_step_line(st, FitMeasure::kSoftInliers, 3, 4),
            "step 4 of 4 (final fit): soft inliers 16.8972, best so far 16.8972, 17 inliers");
  EXPECT_EQ(
      trace_cap_note(5000, 5982),
      "the replay holds the first 5,000 steps of 5,982 hypotheses tried (the recording stops at 5,000; the search "
      "went on)");
}

// A registration the time budget ended says "time budget spent" once, in its stop reason; the note's
// sentences (the registration's own words, as ipd register prints them) then say where it ran out and what was
// left out. Any other stop keeps the note whole.
TEST(RegistrationWords, TheBudgetsStopIsSaidOnce) {
  RegistrationReport r;
  r.stop = StopReason::kTimeBudget;
  r.note =
      "time budget spent while setting up the search: identity used; time budget spent before the rocks were "
      "paired: paired greedily (heaviest overlap first), not by the optimal assignment";
  EXPECT_EQ(registration_stop_line(r),
            "stopped: time budget spent; while setting up the search: identity used; before the rocks were paired: "
            "paired greedily (heaviest overlap first), not by the optimal assignment");
  r.note = "time budget spent: EM's alignment, not judged against rival placements";
  EXPECT_EQ(registration_stop_line(r),
            "stopped: time budget spent; EM's alignment, not judged against rival placements");
  r.note.clear();
  EXPECT_EQ(registration_stop_line(r), "stopped: time budget spent");
  EXPECT_EQ(no_steps_line(r, true), "no search recorded: the time budget was spent before it began");
  r.ambiguous = true, r.ambiguity = Ambiguity::kFewPairs;
  EXPECT_EQ(ambiguity_line(r),
            "ambiguous: fewer than 3 rocks are paired: too few to fix an alignment, another fits as well; check the "
            "pairs, or re-run with a larger time budget, which may settle it");
  EXPECT_EQ(no_steps_line(r, false), "recording the search...");
  // The search converged; only the final pairing ran out of time: the note says so in full.
  r.stop = StopReason::kConverged;
  r.note = "time budget spent before the rocks were paired: paired greedily";
  EXPECT_EQ(registration_stop_line(r),
            "stopped: converged; time budget spent before the rocks were paired: paired greedily");
  EXPECT_EQ(no_steps_line(r, true), "no search recorded for this method");
  EXPECT_EQ(ambiguity_line(r),
            "ambiguous: fewer than 3 rocks are paired: too few to fix an alignment, another fits as well; check the "
            "pairs");
}

TEST(RegistrationCanvas, PlotClipStopsAboveTheLegendAndHoldsThePictureBox) {
  // Canvas at (100, 200), 300 x 200, 15 px lines: the legend's three lines start at 200 + 200 - 45 - 4 = 351;
  // the plot (and its clip) is (100, 200)-(400, 349); the picture box has 10 px margins: 280 x 129.
  const RegistrationCanvas c = registration_canvas({100, 200}, {300, 200}, 15);
  EXPECT_FLOAT_EQ(c.legend_top, 351);
  EXPECT_FLOAT_EQ(c.plot_min.x, 100);
  EXPECT_FLOAT_EQ(c.plot_min.y, 200);
  EXPECT_FLOAT_EQ(c.plot_max.x, 400);
  EXPECT_FLOAT_EQ(c.plot_max.y, 349);
  EXPECT_FLOAT_EQ(c.box_min.x, 110);
  EXPECT_FLOAT_EQ(c.box_min.y, 210);
  EXPECT_FLOAT_EQ(c.box_size.x, 280);
  EXPECT_FLOAT_EQ(c.box_size.y, 129);
  // A canvas too short for the legend: the plot collapses to nothing rather than reaching above the canvas.
  const RegistrationCanvas t = registration_canvas({0, 50}, {100, 40}, 15);
  EXPECT_FLOAT_EQ(t.plot_max.y, 50);
  EXPECT_FLOAT_EQ(t.box_size.y, 0);
}

// A rock-view selection narrows the list; the scatter keeps the list before it, so a second box selects among
// every pair the first was drawn on, and the filter still applies.
TEST(BrowserOrder, TheScatterKeepsTheListBeforeTheSelection) {
  std::vector<SceneSummary> sums(4);
  for (int k = 0; k < 4; ++k) sums[k].stem = std::string(1, char('a' + k));
  UiState ui;
  ui.sort_column = kByStem, ui.sort_descending = false;
  update_browser_order(sums, ui);
  EXPECT_EQ(ui.order, (std::vector<int>{0, 1, 2, 3}));
  EXPECT_TRUE(ui.order_without_selection.empty());
  ui.selection_scenes = {1, 3};
  update_browser_order(sums, ui);
  EXPECT_EQ(ui.order, (std::vector<int>{1, 3}));
  EXPECT_EQ(ui.order_without_selection, (std::vector<int>{0, 1, 2, 3}));
  EXPECT_EQ(ui.selection_scenes, (std::vector<int>{1, 3}));  // the selection itself is kept
  std::snprintf(ui.filter, sizeof ui.filter, "c");
  update_browser_order(sums, ui);
  EXPECT_EQ(ui.order, (std::vector<int>{}));
  EXPECT_EQ(ui.order_without_selection, (std::vector<int>{2}));
}

TEST(BrowserOrder, AmbiguousScenesSortOnTheirOwnColumn) {
  std::vector<SceneSummary> sums(3);
  sums[0].stem = "a", sums[0].suspects = 2;
  sums[1].stem = "b", sums[1].ambiguous = true;
  sums[2].stem = "c";
  UiState ui;
  ui.sort_column = kByAmbiguous, ui.sort_descending = true;
  EXPECT_EQ(browser_order(sums, ui), (std::vector<int>{1, 0, 2}));  // ambiguity, not suspects
  ui.sort_column = kBySuspects;
  EXPECT_EQ(browser_order(sums, ui), (std::vector<int>{0, 1, 2}));
}

// The IPD comes right after the frozen scene name (in a 700 px window the list is cut after about four
// columns: the IPD must not be the one at the edge), and a click on each header sorts by what it shows.
TEST(BrowserColumns, IpdRightAfterTheNameAndEachHeaderSortsByItsOwnValue) {
  std::vector<std::string> headers;
  for (const auto& c : browser_columns()) headers.push_back(c.text.header);
  EXPECT_EQ(headers, (std::vector<std::string>{"scene", "IPD", "amb.", "susp.", "ed.", "pairs", "unp.", "rev."}));
  // Four scenes that each value ranks differently (descending; ties keep the scenes' order).
  std::vector<SceneSummary> sums(4);
  sums[0].stem = "z", sums[0].ipd = 0.01, sums[0].pairs = 1;
  sums[1].stem = "b", sums[1].ipd = 0.09, sums[1].pairs = 2;
  sums[2].stem = "c", sums[2].ipd = 0.02, sums[2].pairs = 9, sums[2].unpaired_a = 1, sums[2].suspects = 3;
  sums[3].stem = "d", sums[3].ipd = 0.03, sums[3].pairs = 3, sums[3].unpaired_b = 4;
  sums[3].edited = sums[3].ambiguous = true;
  sums[1].reviewed = true;
  const std::vector<std::vector<int>> expected = {{0, 3, 2, 1}, {1, 3, 2, 0}, {3, 0, 1, 2}, {2, 0, 1, 3},
                                                  {3, 0, 1, 2}, {2, 3, 1, 0}, {3, 2, 0, 1}, {1, 0, 2, 3}};
  UiState ui;
  ui.sort_descending = true;
  for (size_t k = 0; k < expected.size(); ++k) {
    ui.sort_column = browser_columns()[k].sort_key;
    EXPECT_EQ(browser_order(sums, ui), expected[k]) << headers[k];
  }
}

TEST(EmptyHistogram, SaysWhyThereIsNoBar) {
  SceneSummary none;  // no pairs at all
  EXPECT_EQ(empty_histogram_text({none, none}), "no scene with pairs");
  // Pairs, but at the threshold neither domain has a prediction left: that, not "no scene with pairs".
  SceneSummary paired;
  paired.pairs = 12;
  paired.ipd = std::nan("");
  paired.no_value_reason = "no predictions at or above 0.98 in real and principled";
  EXPECT_EQ(empty_histogram_text({none, paired}),
            "no per-scene IPD: no predictions at or above 0.98 in real and principled");
  SceneSummary plain;
  plain.pairs = 3;
  EXPECT_EQ(empty_histogram_text({plain, paired}),
            "no per-scene IPD: no predictions at or above 0.98 in real and principled");
  EXPECT_EQ(empty_histogram_text({plain}), "no scene with an IPD");
}

// The panel's count of scenes and the histogram's agree: both count the scenes with pairs (a scene whose rocks
// all went unpaired has no IPD and no bar), and the panel names the rest.
TEST(IpdPanel, CountsTheScenesWithPairsAsTheHistogramDoes) {
  SceneSummary a, b, none;
  a.pairs = 40, b.pairs = 29;
  EXPECT_EQ(cell_totals_line(0.0295, 69, {a, none, b}),
            "0.0295 over 69 pairs in 2 scenes with pairs (1 scene without pairs)");
  EXPECT_EQ(cell_totals_line(0.0295, 69, {a, b}), "0.0295 over 69 pairs in 2 scenes with pairs");
  EXPECT_EQ(histogram_scenes_text(2), "2 scenes with pairs");
  EXPECT_EQ(cell_totals_line(std::nan(""), 0, {none}),
            "n/a over 0 pairs in 0 scenes with pairs (1 scene without pairs)");
}

// The Rank window writes a negative number with the typographic minus, as ipd rank and the compare panel do.
TEST(RankWindow, ARowWritesNegativeNumbersWithTheTypographicMinus) {
  RankedCandidate r;
  r.rank = 2;
  r.domain = "w030";
  r.params = {{"w", 0.3}};
  r.ipd = 0.0412;
  r.ci_low = 0.031;
  r.ci_high = 0.052;
  r.pairs = 78;
  RendererComparison c;
  c.result.ipd_a = 0.0412;
  c.result.ipd_b = 0.0289;
  c.result.delta.low = -0.004;
  c.result.delta.high = 0.021;
  r.vs_best = c;
  r.p_holm = 0.0312;
  r.in_best_group = true;
  EXPECT_EQ(rank_row_cells(r), (std::vector<std::string>{"2", "w030", "w=0.3", "0.0412 [0.031, 0.052]", "78",
                                                         "+0.0123 [\u22120.004, 0.021]", "0.0312", "\u2248 best"}));
}

}  // namespace
}  // namespace ipd::ui
