// A TrueType font cut down to the glyphs a figure uses (HarfBuzz's subsetter), for files that embed their
// font: an SVG figure carries a few kB of DejaVu Sans instead of the whole 700 kB face.
#pragma once

#include <set>
#include <string>

namespace ipd::ui {

// The Unicode code points of UTF-8 text (a malformed byte counts as U+FFFD).
void add_code_points(const std::string& utf8, std::set<char32_t>* out);

// The font file's glyphs for `code_points` (plus .notdef), without hinting, as a TrueType file's bytes.
// Throws std::runtime_error naming the file when it can't be read or subset.
std::string subset_font(const std::string& font_file, const std::set<char32_t>& code_points);

}  // namespace ipd::ui
