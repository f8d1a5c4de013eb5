#include "core/util/json_input.h"

#include <fmt/format.h>
#include <string>
#include <unordered_set>
#include <vector>

#include "core/util/errors.h"

namespace ipd {

namespace {

// The byte offset where `text` nests arrays/objects deeper than `limit`, or npos.
size_t too_deep_at(const std::string& text, int limit) {
  int depth = 0;
  bool in_string = false, escaped = false;
  for (size_t k = 0; k < text.size(); ++k) {
    const char c = text[k];
    if (in_string) {
      if (escaped)
        escaped = false;
      else if (c == '\\')
        escaped = true;
      else if (c == '"')
        in_string = false;
    } else if (c == '"') {
      in_string = true;
    } else if (c == '[' || c == '{') {
      if (++depth > limit) return k;
    } else if (c == ']' || c == '}') {
      --depth;
    }
  }
  return std::string::npos;
}

}  // namespace

nlohmann::json parse_json_input(const std::string& text, const std::string& file, const std::string& expected,
                                int max_depth, size_t max_values) {
  const size_t deep = too_deep_at(text, max_depth);
  if (deep != std::string::npos)
    throw StudyError(fmt::format("{}: JSON nested deeper than {} levels at byte {}: expected {}", file, max_depth,
                                 deep + 1, expected));
  // nlohmann keeps the last of two equal keys: {"pairs": [...], "pairs": [...]} would silently drop the first
  // list. The keys of each open object are collected (nesting is capped above) and a repeat is an error.
  std::vector<std::unordered_set<std::string>> keys;
  size_t values = 0;
  auto no_duplicate_keys = [&](int, nlohmann::json::parse_event_t event, nlohmann::json& parsed) {
    using Event = nlohmann::json::parse_event_t;
    const bool value = event == Event::object_start || event == Event::array_start || event == Event::value;
    if (value && max_values > 0 && ++values > max_values)
      throw StudyError(fmt::format("{}: holds more than {} JSON values, the limit for this kind of file: expected {}",
                                   file, max_values, expected));
    if (event == Event::object_start) {
      keys.emplace_back();
    } else if (event == Event::object_end) {
      if (!keys.empty()) keys.pop_back();
    } else if (event == Event::key && !keys.empty()) {
      const std::string& key = parsed.get_ref<const std::string&>();
      if (!keys.back().insert(key).second)
        throw StudyError(
            fmt::format("{}: duplicate key {} in one object (a JSON reader keeps only one of them); "
                        "expected {}",
                        file, describe_json(parsed), expected));
    }
    return true;
  };
  try {
    return nlohmann::json::parse(text, no_duplicate_keys);
  } catch (const nlohmann::json::parse_error& e) {
    throw StudyError(fmt::format("{}: invalid JSON at byte {}: expected {}", file, e.byte, expected));
  } catch (const nlohmann::json::exception& e) {  // e.g. 1e309: a number out of range
    std::string why = e.what();
    if (why.size() > 120) why = why.substr(0, 117) + "...";
    throw StudyError(fmt::format("{}: invalid JSON: {}", file, why));
  }
}

std::string describe_json(const nlohmann::json& value) {
  // A string that is not UTF-8 (built from bytes, never parsed) is shown with U+FFFD, not thrown on.
  const std::string s = value.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
  return s.size() > 40 ? s.substr(0, 37) + "..." : s;
}

}  // namespace ipd
