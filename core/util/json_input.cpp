#include "core/util/json_input.h"

#include <fmt/format.h>

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
      if (escaped) escaped = false;
      else if (c == '\\') escaped = true;
      else if (c == '"') in_string = false;
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
                                int max_depth) {
  const size_t deep = too_deep_at(text, max_depth);
  if (deep != std::string::npos)
    throw StudyError(fmt::format("{}: JSON nested deeper than {} levels at byte {}: expected {}", file, max_depth,
                                 deep + 1, expected));
  try {
    return nlohmann::json::parse(text);
  } catch (const nlohmann::json::parse_error& e) {
    throw StudyError(fmt::format("{}: invalid JSON at byte {}: expected {}", file, e.byte, expected));
  } catch (const nlohmann::json::exception& e) {  // e.g. 1e309: a number out of range
    std::string why = e.what();
    if (why.size() > 120) why = why.substr(0, 117) + "...";
    throw StudyError(fmt::format("{}: invalid JSON: {}", file, why));
  }
}

std::string describe_json(const nlohmann::json& value) {
  const std::string s = value.dump();
  return s.size() > 40 ? s.substr(0, 37) + "..." : s;
}

}  // namespace ipd
