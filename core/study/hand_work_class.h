// The class a piece of hand work is of: hand pairs files and review marks name the class their rocks were chosen
// under ("class": N, or "all" for class-blind work), so work done for rocks is never read as shadows' work. One
// rule for both: work without "class" holds for every class; work of another class than the one chosen is that
// class's, kept as it is and neither applied nor reported.
#pragma once

#include <nlohmann/json_fwd.hpp>
#include <optional>
#include <string>

namespace ipd {

struct Study;

// The class hand work written now is of: the chosen class in a study where another could be chosen (more than
// one named class, a class number above 0, or class-blind), else none (the work holds for every class).
std::optional<int> hand_work_class(const Study& study);

// True when work of `work_class` is another class's than `chosen` (study.config.rock_class).
bool is_other_class_work(std::optional<int> work_class, int chosen);

// Reads a "class" value: a class number >= 0 or "all" (kAllClasses). Throws StudyError "FILE: <where> must be
// ..." otherwise.
int parse_hand_work_class(const nlohmann::json& value, const std::string& file, const std::string& where);
// The "class" value of `cls` (a number, or "all").
nlohmann::json hand_work_class_json(int cls);

}  // namespace ipd
