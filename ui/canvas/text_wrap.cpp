#include "ui/canvas/text_wrap.h"

#include <algorithm>
#include <cctype>

namespace ipd::ui {

namespace {
// Signs that bind the words on both sides: "p = 0.031", "unpaired 0 / 0".
bool is_relation(const std::string& w) {
  return w == "=" || w == "<" || w == ">" || w == "<=" || w == ">=" || w == "/";
}
// A whole count such as "8" or "1,000" (not "0.97", not "8," that ends a clause): it counts the word after it.
// An opening parenthesis before it is the count's too: "(12 pairs)".
bool is_count(const std::string& word) {
  const std::string w = !word.empty() && word.front() == '(' ? word.substr(1) : word;
  return !w.empty() && std::isdigit(static_cast<unsigned char>(w.front())) &&
         std::isdigit(static_cast<unsigned char>(w.back())) && std::all_of(w.begin(), w.end(), [](char ch) {
           return std::isdigit(static_cast<unsigned char>(ch)) || ch == ',';
         });
}
// Words whose value follows them: "IPD 0.0404", "score 0.0244", "confidence 0.94", "best so far 0.0385", and a
// registration's fit: "mean distance 0.0004", "soft inliers 16.8972", "mixture width 0.0003".
bool is_value_label(const std::string& w) {
  if (w.size() >= 3 && w.compare(w.size() - 3, 3, "IPD") == 0) return true;
  return w == "score" || w == "confidence" || w == "far" || w == "distance" || w == "inliers" || w == "width";
}
bool starts_with_letter(const std::string& w) { return !w.empty() && std::isalpha(static_cast<unsigned char>(w[0])); }
// Any number, "0.3", "-1.5", "1,000": the unit after it belongs to it.
bool is_number(const std::string& word) {
  // A clause's comma or semicolon after it is not part of it: "score 0.0244, confidence ...".
  const bool punctuated = !word.empty() && (word.back() == ',' || word.back() == ';');
  const std::string w = punctuated ? word.substr(0, word.size() - 1) : word;
  return !w.empty() && std::isdigit(static_cast<unsigned char>(w.back())) &&
         std::all_of(w.begin(), w.end(), [](char ch) {
           return std::isdigit(static_cast<unsigned char>(ch)) || ch == ',' || ch == '.' || ch == '-';
         });
}
bool is_unit(const std::string& w) {
  for (const char* unit : {"px", "px\u00b2", "px,", "px;", "px)", "ms", "ms,", "ms;", "ms)", "s", "%", "MB", "GB"})
    if (w == unit) return true;
  return false;
}
}  // namespace

std::vector<std::string> wrap_at_spaces(const std::string& text, float width,
                                        const std::function<float(const std::string&)>& measure) {
  std::vector<std::string> lines;
  if (text.empty()) return lines;
  size_t start = 0;
  while (true) {  // each paragraph (between newlines) on its own
    const size_t nl = text.find('\n', start);
    const std::string para = text.substr(start, nl == std::string::npos ? std::string::npos : nl - start);
    std::vector<std::string> words;
    bool after_relation = false, after_count = false, after_number = false, after_label = false, after_delta = false,
         after_scene = false;
    for (size_t p = 0; p <= para.size();) {
      size_t sp = para.find(' ', p);
      if (sp == std::string::npos) sp = para.size();
      std::string word = para.substr(p, sp - p);
      p = sp + 1;
      if (word.empty() && sp < para.size()) continue;  // runs of spaces
      // A label and its number stay together: "p = 0.031", "p < 0.0001" never break around the sign; so do a
      // count and the word it counts: "8 scenes", "(12 pairs)"; a number and its unit: "0.3 px", "12.5 ms"; "scene
      // IPD" and its value: "scene IPD 0.0404"; and "delta IPD", ΔIPD spelled in ASCII, is one symbol.
      const bool glue =
          !words.empty() && (is_relation(word) || after_relation || (after_count && starts_with_letter(word)) ||
                             (after_number && is_unit(word)) || (after_label && is_number(word)) ||
                             ((after_delta || after_scene) && word.rfind("IPD", 0) == 0));
      after_relation = is_relation(word);
      after_count = is_count(word);
      after_number = is_number(word);
      after_label = is_value_label(word);
      after_delta = word == "delta";
      after_scene = word == "scene";
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

}  // namespace ipd::ui
