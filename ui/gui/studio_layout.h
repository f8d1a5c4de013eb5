// Layout and wording rules of ipd-studio that need no ImGui, so tests can check them with hand-computed
// numbers: the main window's column widths at any window width, wrapping text at spaces only (never inside
// a number), counted nouns ("1 scene", "2 scenes") and plain numbers for UI text.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "ui/canvas/text_wrap.h"  // wrap_at_spaces, shared with the figures

namespace ipd::ui {

// The main window's columns. Wide windows: browser | centre | statistics, the side columns at their
// preferred widths while the centre keeps at least kCentreShare. Narrower: the browser gives way first, as long as it
// keeps kBrowserKeeps (the scene name, its IPD and flags; the rest scrolls sideways) and the statistics their
// width (the cross table is the result: 1280 px shows it whole); narrower still, the side columns shrink in
// proportion from there (kBrowserKeeps : the statistics' width, so no width jumps), down to kMinBrowserWidth /
// kMinStatsWidth. Below kTwoColumnsBelow the browser
// and the statistics share one tabbed column (40% of the width). A centre narrower than kTabbedCentreBelow shows the
// registration panel and the pair table as tabs instead of side by side.
constexpr float kMinBrowserWidth = 160, kMinStatsWidth = 200, kMinCentreWidth = 320, kBrowserKeeps = 260;
constexpr float kTwoColumnsBelow = 900, kTabbedCentreBelow = 560;
constexpr float kCentreShare = 0.45f;  // at 1600 px a 3,000-scene browser (420 px) and statistics (400) still fit
struct StudioColumns {
  bool tabbed_side = false;  // browser and statistics are tabs of the left column; right = 0
  float left = 0, centre = 0, right = 0;
  bool tabbed_centre = false;
};
// `width`: the window's content width; `splitter`: the width of each draggable gap between columns.
StudioColumns studio_columns(float width, float browser_pref, float stats_pref, float splitter);

// The focus view (key `Z`, View > Focus pictures): the browser and the statistics collapse to strips of
// kFocusStrip (a button each to bring them back) so the two pictures fill the centre column.
constexpr float kFocusStrip = 28;
StudioColumns focus_columns(float width, float splitter);

// The two pictures in a pane of `width` x `height` (below the toolbar): side by side, each under a caption line,
// or stacked, each under its own caption line, whichever shows the pictures (of `aspect` = width / height)
// larger. `pane_w` x `pane_h` is each picture's pane; `picture_w` x `picture_h` the picture fitted in it.
struct PicturePanes {
  bool stacked = false;
  float pane_w = 0, pane_h = 0;
  float picture_w = 0, picture_h = 0;
};
PicturePanes picture_panes(float width, float height, float aspect, float gap, float caption_line);

// `text` with what the GUI font has no glyph for (`has_glyph`: ImFont::FindGlyphNoFallback) spelled in ASCII:
// "ΔIPD" -> "delta IPD" without U+0394, the typographic minus "−" -> "-" without U+2212; kept otherwise.
std::string spell_missing_glyphs(std::string text, const std::function<bool(char32_t)>& has_glyph);

// "1 scene", "3 scenes", "0 scenes"; `plural` defaults to singular + "s".
std::string counted(long n, const char* singular, const char* plural = nullptr);
// An integer with thousands separators: 89700 -> "89,700", -1234567 -> "-1,234,567".
std::string thousands(long long n);
// A fixed-point number that never reads "-0.000": a value that rounds to zero prints unsigned.
std::string fixed(double v, int decimals);
// The confidence threshold a slider position sets: the two-decimal number the slider shows, as `--conf` and
// study.yaml would read it (0.3, not the 0.30000001 a float slider holds, which would drop predictions at 0.3).
double conf_slider_value(double v);

}  // namespace ipd::ui
