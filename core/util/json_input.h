// Parsing JSON from files we don't control (pairs files, COCO annotations): nesting depth capped before
// parsing (nothing downstream may recurse through a hostile file), every error naming the file, and values
// quoted in messages at most 40 characters long.
#pragma once

#include <cstddef>
#include <nlohmann/json.hpp>
#include <string>

namespace ipd {

// Parses `text` read from `file`; throws StudyError "FILE: invalid JSON at byte N: expected <expected>",
// "FILE: JSON nested deeper than <max_depth> levels at byte N: ...", "FILE: duplicate key "k" in one object
// ..." (nlohmann would keep the last one silently) or "FILE: invalid JSON: <why>" (numbers out of range such
// as 1e309).
// `max_values` > 0 caps the JSON values (objects, arrays, strings, numbers, ...) a document may hold: the
// parsed document costs memory per value (about 80 bytes for an empty object), so a file of a few MB of `{}`
// would take hundreds of MB; past the cap parsing stops with "FILE: holds more than N JSON values, the limit
// for this kind of file: expected ...".
nlohmann::json parse_json_input(const std::string& text, const std::string& file, const std::string& expected,
                                int max_depth, size_t max_values = 0);

// A value for an error message: its JSON text, shortened to 40 characters.
std::string describe_json(const nlohmann::json& value);

}  // namespace ipd
