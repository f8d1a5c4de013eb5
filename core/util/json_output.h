// Writing JSON for the user (ipd table/export/breakdown/compare/metrics/register --json). JSON holds only
// UTF-8 text; a file or directory name in another encoding (Latin-1 from an old share, a damaged name) made
// nlohmann refuse the whole output with a bare "invalid UTF-8 byte at index 3: 0xE9".
#pragma once

#include <nlohmann/json.hpp>

#include <cmath>
#include <string>

#include "core/util/utf8.h"

namespace ipd {

// j.dump(indent); a string that is not UTF-8 is a StudyError quoting it (escaped) and saying what to do,
// never nlohmann's bare message and never a silently altered name. Callers that know which file a name
// comes from check it first (require_utf8_names in core/study/study.h) so the message names the file.
std::string dump_json_output(const nlohmann::json& j, int indent = -1);
std::string dump_json_output(const nlohmann::ordered_json& j, int indent = -1);

// A number, or null where there is none (NaN: no pairs, no predictions): JSON has no NaN, and 0 would read as a
// perfect score.
inline nlohmann::ordered_json json_number(double v) {
  return std::isfinite(v) ? nlohmann::ordered_json(v) : nlohmann::ordered_json(nullptr);
}

}  // namespace ipd
