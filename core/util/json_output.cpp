#include "core/util/json_output.h"

#include <fmt/format.h>

#include "core/util/errors.h"
#include "core/util/utf8.h"

namespace ipd {

namespace {

// The first string (key or value) in `j` that is not UTF-8; false when there is none.
template <typename Json>
bool first_non_utf8(const Json& j, std::string* out) {
  if (j.is_string()) {
    const auto& s = j.template get_ref<const std::string&>();
    if (is_utf8(s)) return false;
    *out = s;
    return true;
  }
  if (j.is_object()) {
    for (auto it = j.begin(); it != j.end(); ++it) {
      if (!is_utf8(it.key())) {
        *out = it.key();
        return true;
      }
      if (first_non_utf8(it.value(), out)) return true;
    }
  } else if (j.is_array()) {
    for (const auto& v : j)
      if (first_non_utf8(v, out)) return true;
  }
  return false;
}

template <typename Json>
std::string dump_checked(const Json& j, int indent) {
  std::string bad;
  if (first_non_utf8(j, &bad))
    throw StudyError(
        fmt::format("cannot write JSON: '{}' is not UTF-8 text, and JSON holds only UTF-8; rename the "
                    "file or directory it comes from (text and CSV output take it as it is)",
                    escape_non_utf8(bad.size() > 80 ? bad.substr(0, 77) + "..." : bad)));
  return j.dump(indent);
}

}  // namespace

std::string dump_json_output(const nlohmann::json& j, int indent) { return dump_checked(j, indent); }
std::string dump_json_output(const nlohmann::ordered_json& j, int indent) { return dump_checked(j, indent); }

}  // namespace ipd
