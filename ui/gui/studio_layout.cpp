#include "ui/gui/studio_layout.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>

#include "core/util/number_text.h"

namespace ipd::ui {

StudioColumns studio_columns(float width, float browser_pref, float stats_pref, float splitter) {
  StudioColumns c;
  if (width < kTwoColumnsBelow) {
    const float usable = width - splitter;
    c.tabbed_side = true;
    c.left = std::max(kMinBrowserWidth, std::min(0.4f * usable, std::max(browser_pref, stats_pref)));
    c.centre = usable - c.left;
  } else {
    const float usable = width - 2 * splitter;
    const float centre_min = std::max(kMinCentreWidth, kCentreShare * usable);
    const float sides = std::max(kMinBrowserWidth + kMinStatsWidth, usable - centre_min);
    if (browser_pref + stats_pref + centre_min <= usable) {
      c.left = browser_pref, c.right = stats_pref;
    } else if (const float keeps = std::min(browser_pref, kBrowserKeeps); sides >= stats_pref + keeps) {
      // The statistics first: the cross table is the study's result, while the scene list scrolls sideways
      // with the scene name frozen.
      c.right = stats_pref, c.left = sides - stats_pref;
    } else {
      // Shrink both sides in proportion from there (no jump at the boundary), then lift the one below its
      // minimum at the other's expense.
      c.left = sides * keeps / (keeps + stats_pref);
      c.right = sides - c.left;
      if (c.left < kMinBrowserWidth) c.left = kMinBrowserWidth, c.right = sides - c.left;
      if (c.right < kMinStatsWidth) c.right = kMinStatsWidth, c.left = sides - c.right;
    }
    c.centre = usable - c.left - c.right;
  }
  c.tabbed_centre = c.centre < kTabbedCentreBelow;
  return c;
}

StudioColumns focus_columns(float width, float splitter) {
  StudioColumns c;
  c.left = c.right = kFocusStrip;
  c.centre = std::max(0.0f, width - 2 * kFocusStrip - 2 * splitter);
  c.tabbed_centre = c.centre < kTabbedCentreBelow;
  return c;
}

PicturePanes picture_panes(float width, float height, float aspect, float gap, float caption_line) {
  if (!(aspect > 0)) aspect = 1.6f;
  auto fitted = [&](PicturePanes p) {
    p.pane_w = std::max(0.0f, p.pane_w), p.pane_h = std::max(0.0f, p.pane_h);
    p.picture_w = std::min(p.pane_w, p.pane_h * aspect);
    p.picture_h = p.picture_w / aspect;
    return p;
  };
  // Side by side: one caption line above both.
  const PicturePanes beside = fitted({false, (width - gap) / 2, height - caption_line});
  // Stacked: a caption line above each.
  const PicturePanes stacked = fitted({true, width, (height - gap) / 2 - caption_line});
  return stacked.picture_w * stacked.picture_h > beside.picture_w * beside.picture_h ? stacked : beside;
}

std::string spell_missing_glyphs(std::string text, const std::function<bool(char32_t)>& has_glyph) {
  struct Spelling {
    char32_t glyph;
    const char* utf8;
    const char* ascii;
  };
  for (const Spelling& s : {Spelling{U'\u0394', "\u0394IPD", "delta IPD"}, Spelling{U'\u2212', "\u2212", "-"}}) {
    if (has_glyph(s.glyph)) continue;
    const std::string from = s.utf8;
    for (size_t at = 0; (at = text.find(from, at)) != std::string::npos; at += std::char_traits<char>::length(s.ascii))
      text.replace(at, from.size(), s.ascii);
  }
  return text;
}

std::string counted(long n, const char* singular, const char* plural) {
  const std::string noun = n == 1 ? singular : plural ? plural : std::string(singular) + "s";
  return thousands(n) + " " + noun;
}

std::string thousands(long long n) { return grouped_thousands(n); }

double conf_slider_value(double v) { return std::clamp(std::round(v * 100), 0.0, 100.0) / 100; }

std::string fixed(double v, int decimals) { return fixed_decimals(v, decimals); }

}  // namespace ipd::ui
