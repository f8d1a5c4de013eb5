#include "core/study/hand_work_class.h"

#include <algorithm>
#include <climits>
#include <nlohmann/json.hpp>

#include "core/study/study.h"
#include "core/study/study_classes.h"
#include "core/util/errors.h"

namespace ipd {

std::optional<int> hand_work_class(const Study& study) {
  const int cls = study.config.rock_class;
  if (cls == kNoClassChosen) return std::nullopt;
  const auto& names = study.classes.names;
  const long named = std::count_if(names.begin(), names.end(), [](const std::string& n) { return !n.empty(); });
  if (cls == kAllClasses || cls > 0 || named > 1) return cls;
  return std::nullopt;
}

bool is_other_class_work(std::optional<int> work_class, int chosen) {
  return work_class && chosen != kNoClassChosen && *work_class != chosen;
}

int parse_hand_work_class(const nlohmann::json& c, const std::string& file, const std::string& where) {
  if (c.is_string() && c.get<std::string>() == "all") return kAllClasses;
  if (c.is_number_integer() && c.get<long long>() >= 0 && c.get<long long>() <= INT_MAX) return c.get<int>();
  throw StudyError(file + ": " + where + " must be a class number >= 0 or \"all\" (the class its rocks are of)");
}

nlohmann::json hand_work_class_json(int cls) {
  return cls == kAllClasses ? nlohmann::json("all") : nlohmann::json(cls);
}

}  // namespace ipd
