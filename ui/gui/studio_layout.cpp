#include "ui/gui/studio_layout.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>

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
    if (browser_pref + stats_pref + centre_min <= usable) {
      c.left = browser_pref, c.right = stats_pref;
    } else {
      // Shrink both sides in proportion, then lift the one below its minimum at the other's expense.
      const float sides = std::max(kMinBrowserWidth + kMinStatsWidth, usable - centre_min);
      c.left = sides * browser_pref / (browser_pref + stats_pref);
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

namespace {
bool is_relation(const std::string& w) { return w == "=" || w == "<" || w == ">" || w == "<=" || w == ">="; }
// A whole count such as "8" or "1,000" (not "0.97", not "8," that ends a clause): it counts the word after it.
bool is_count(const std::string& w) {
  return !w.empty() && std::isdigit(static_cast<unsigned char>(w.front())) &&
         std::isdigit(static_cast<unsigned char>(w.back())) && std::all_of(w.begin(), w.end(), [](char ch) {
           return std::isdigit(static_cast<unsigned char>(ch)) || ch == ',';
         });
}
bool starts_with_letter(const std::string& w) { return !w.empty() && std::isalpha(static_cast<unsigned char>(w[0])); }
}  // namespace

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

std::vector<std::string> wrap_at_spaces(const std::string& text, float width,
                                        const std::function<float(const std::string&)>& measure) {
  std::vector<std::string> lines;
  if (text.empty()) return lines;
  size_t start = 0;
  while (true) {  // each paragraph (between newlines) on its own
    const size_t nl = text.find('\n', start);
    const std::string para = text.substr(start, nl == std::string::npos ? std::string::npos : nl - start);
    std::vector<std::string> words;
    bool after_relation = false, after_count = false, after_delta = false;
    for (size_t p = 0; p <= para.size();) {
      size_t sp = para.find(' ', p);
      if (sp == std::string::npos) sp = para.size();
      std::string word = para.substr(p, sp - p);
      p = sp + 1;
      if (word.empty() && sp < para.size()) continue;  // runs of spaces
      // A label and its number stay together: "p = 0.031", "p < 0.0001" never break around the sign; so do a
      // count and the word it counts: "8 scenes", "1,000 trials"; and "delta IPD", ΔIPD spelled in ASCII, is one
      // symbol.
      const bool glue =
          !words.empty() && (is_relation(word) || after_relation || (after_count && starts_with_letter(word)) ||
                             (after_delta && word.rfind("IPD", 0) == 0));
      after_relation = is_relation(word);
      after_count = is_count(word);
      after_delta = word == "delta";
      if (glue)
        words.back() += " " + word;
      else
        words.push_back(std::move(word));
    }
    std::string line;
    bool any = false;
    for (const std::string& word : words) {
      const std::string joined = line.empty() ? word : line + " " + word;
      if (!line.empty() && measure(joined) > width) {
        lines.push_back(line);
        line = word;
      } else {
        line = joined;
      }
      any = true;
    }
    if (any || nl != std::string::npos) lines.push_back(line);
    if (nl == std::string::npos) break;
    start = nl + 1;
  }
  return lines;
}

std::string counted(long n, const char* singular, const char* plural) {
  const std::string noun = n == 1 ? singular : plural ? plural : std::string(singular) + "s";
  return thousands(n) + " " + noun;
}

std::string thousands(long long n) {
  const bool negative = n < 0;
  std::string digits = std::to_string(negative ? -(n + 1) + 1ULL : static_cast<unsigned long long>(n));
  std::string out;
  for (size_t k = 0; k < digits.size(); ++k) {
    if (k > 0 && (digits.size() - k) % 3 == 0) out += ',';
    out += digits[k];
  }
  return negative ? "-" + out : out;
}

std::string fixed(double v, int decimals) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", decimals, v);
  std::string s = buf;
  if (s[0] == '-' && s.find_first_not_of("-0.") == std::string::npos) s.erase(0, 1);
  return s;
}

}  // namespace ipd::ui
