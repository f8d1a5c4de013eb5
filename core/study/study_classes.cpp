#include "core/study/study_classes.h"

#include <fmt/format.h>

#include <algorithm>
#include <filesystem>

#include "core/study/file_sets.h"
#include "core/study/study.h"
#include "core/util/errors.h"
#include "core/util/number_text.h"

namespace fs = std::filesystem;

namespace ipd {

std::string StudyClasses::name_of(int cls) const {
  if (cls >= 0 && static_cast<size_t>(cls) < names.size() && !names[cls].empty()) return names[cls];
  return fmt::format("class {}", cls);
}

std::string StudyClasses::describe(int cls) const {
  if (cls == kAllClasses) return "all classes";
  if (cls >= 0 && static_cast<size_t>(cls) < names.size() && !names[cls].empty())
    return fmt::format("{} (class {})", names[cls], cls);
  return fmt::format("class {}", cls);
}

int StudyClasses::resolve(const std::string& word) const {
  if (word == "all") return kAllClasses;
  for (size_t k = 0; k < names.size(); ++k)
    if (!names[k].empty() && names[k] == word) return static_cast<int>(k);
  std::string known;
  for (size_t k = 0; k < names.size(); ++k)
    if (!names[k].empty()) known += fmt::format("{}{} ({})", known.empty() ? "" : ", ", names[k], k);
  if (!word.empty() && word.size() <= 6 &&
      std::all_of(word.begin(), word.end(), [](char c) { return c >= '0' && c <= '9'; })) {
    const int cls = std::stoi(word);
    // Where the study names its classes, a number none names has no boxes: every cell would be empty.
    if (known.empty() || (static_cast<size_t>(cls) < names.size() && !names[cls].empty())) return cls;
    throw StudyError(fmt::format("no class {} among the study's classes {} ({}); or 'all' for a class-blind number",
                                 cls, known, named_by));
  }
  throw StudyError(fmt::format("no class named '{}'; {}; or 'all' for a class-blind number", quoted_for_message(word),
                               known.empty() ? "this study's label sets name no classes (give labels/classes.txt or "
                                               "study.yaml's classes), so choose a class number"
                                             : "the study's classes are " + known + ", by name or number"));
}

const std::vector<int>* StudyClasses::id_map(const std::string& domain, const std::string& model) const {
  const auto it = id_maps.find(model.empty() ? domain + "/labels" : domain + "/predictions/" + model);
  return it == id_maps.end() ? nullptr : &it->second;
}

std::string StudyClasses::map_key() const {
  std::string key;
  for (const auto& [set, map] : id_maps) {
    key += set + ":";
    for (int v : map) key += std::to_string(v) + ",";
    key += ";";
  }
  return key;
}

namespace {

// A classes.txt's names, a name given twice refused with its line (which of the two numbers is meant?).
std::vector<std::string> read_names_checked(const fs::path& file) {
  std::vector<std::string> names = read_class_names(file.string());
  for (size_t k = 0; k < names.size(); ++k) {
    if (names[k].empty()) continue;
    const auto first = std::find(names.begin(), names.begin() + static_cast<long>(k), names[k]);
    if (first != names.begin() + static_cast<long>(k))
      throw StudyError(
          fmt::format("{}:{}: class '{}' is named again (also line {}); each class once, on the line "
                      "of its number",
                      file.string(), k + 1, quoted_for_message(names[k]), first - names.begin() + 1));
  }
  return names;
}

std::string list_names(const std::vector<std::string>& names) {
  std::string out;
  for (size_t k = 0; k < names.size(); ++k)
    if (!names[k].empty()) out += fmt::format("{}{} {}", out.empty() ? "" : ", ", k, names[k]);
  return out.empty() ? "none" : out;
}

}  // namespace

StudyClasses read_study_classes(const std::string& root, const StudyConfig& config,
                                const std::vector<Domain>& domains) {
  StudyClasses c;
  const fs::path study(root);
  if (!config.class_names.empty()) {
    c.names = config.class_names;
    c.named_by = "study.yaml";
  }
  struct Set {
    std::string key, file;
    bool prediction;
  };
  std::vector<Set> sets;
  for (const Domain& d : domains) {
    sets.push_back({d.name + "/labels", (fs::path(d.name) / "labels" / "classes.txt").string(), false});
    for (const std::string& m : d.models)
      sets.push_back(
          {d.name + "/predictions/" + m, (fs::path(d.name) / "predictions" / m / "classes.txt").string(), true});
  }
  for (const Set& s : sets) {
    const std::vector<std::string> names = read_names_checked(study / s.file);
    if (names.empty()) continue;
    if (c.named_by.empty()) {  // the first set that names classes numbers them for the study
      c.names = names;
      c.named_by = s.file;
      continue;
    }
    std::vector<int> map(names.size(), -1);
    bool differs = false;
    std::string moved;
    for (size_t k = 0; k < names.size(); ++k) {
      if (names[k].empty()) continue;
      auto at = std::find(c.names.begin(), c.names.end(), names[k]);
      if (at == c.names.end()) {
        // A prediction set may only use classes the ground truth knows, and study.yaml's list is the whole list.
        if (s.prediction || c.named_by == "study.yaml")
          throw StudyError(fmt::format(
              "{}:{}: class '{}' is not among the study's classes ({}: {}); a class must have one name in every "
              "label set (rename it, or add it to {})",
              (study / s.file).string(), k + 1, quoted_for_message(names[k]), (study / c.named_by).string(),
              list_names(c.names), c.named_by == "study.yaml" ? "study.yaml's classes" : c.named_by));
        // Another domain's class the first did not list: it joins the study at its own number when that is free.
        size_t slot = k;
        if (slot < c.names.size() && !c.names[slot].empty()) slot = c.names.size();
        if (slot >= c.names.size()) c.names.resize(slot + 1);
        c.names[slot] = names[k];
        at = c.names.begin() + static_cast<long>(slot);
      }
      map[k] = static_cast<int>(at - c.names.begin());
      if (map[k] != static_cast<int>(k)) {
        differs = true;
        moved += fmt::format("{}{} {} -> {}", moved.empty() ? "" : ", ", names[k], k, map[k]);
      }
    }
    // A number the set leaves unnamed but the study names would be read as the study's class: it is unnamed here.
    for (size_t k = 0; k < names.size() && !differs; ++k)
      if (names[k].empty() && k < c.names.size() && !c.names[k].empty()) differs = true;
    if (!differs) continue;
    c.id_maps[s.key] = map;
    c.notes.push_back(fmt::format("{} numbers its classes differently from {} ({}): read by name", s.file, c.named_by,
                                  moved.empty() ? "unnamed numbers left out" : moved));
  }
  return c;
}

namespace {
constexpr size_t kMappedClasses = 1024;
}

void map_label_classes(LabelFile* file, const StudyClasses& classes, const std::vector<int>* map,
                       const std::string& names_file) {
  // Nothing to renumber and no names to check against (a study without classes.txt): every label file of it.
  if (!map && classes.named_by.empty()) return;
  size_t kept = 0;  // boxes are renumbered and compacted in place: no copy of a file whose classes are all named
  int listed = 0;
  for (size_t k = 0; k < file->boxes.size(); ++k) {
    Box& b = file->boxes[k];
    const int own = b.cls;
    if (map) b.cls = own >= 0 && static_cast<size_t>(own) < map->size() ? (*map)[own] : -1;
    const bool named = b.cls >= 0 && (classes.named_by.empty() || (static_cast<size_t>(b.cls) < classes.names.size() &&
                                                                   !classes.names[b.cls].empty()));
    if (named) {
      file->boxes[kept] = b;
      file->line_of_box[kept] = file->line_of_box[k];
      ++kept;
      continue;
    }
    // A number nobody named would be read as whatever class the study gives that number: refused, line by line.
    if (listed++ < kMaxListedErrors)
      file->errors.push_back(
          {file->path, file->line_of_box[k],
           map ? fmt::format("class {} is not named in {} (expected one of its named classes)", own, names_file)
               : fmt::format("class {} is a number the study's classes leave unnamed ({}: {}); give this label set "
                             "a classes.txt, or name the class there",
                             own, classes.named_by, list_names(classes.names))});
  }
  if (listed > kMaxListedErrors)
    file->errors.push_back({file->path, 0, "class numbers left unnamed", listed - kMaxListedErrors});
  file->boxes.resize(kept);
  file->line_of_box.resize(kept);
}

void apply_prediction_class_map(const std::map<int, int>& from_to, const std::vector<Domain>& domains,
                                StudyClasses* classes) {
  if (from_to.empty()) return;
  int largest = 0;
  for (const auto& [from, to] : from_to) largest = std::max(largest, from);
  for (const Domain& d : domains)
    for (const std::string& m : d.models) {
      const std::string key = d.name + "/predictions/" + m;
      if (classes->id_maps.count(key)) continue;  // its classes.txt says what its numbers are
      // Numbers beyond the map are unnamed (as for a classes.txt map): cover every number a study plausibly uses.
      std::vector<int> map(std::max<size_t>(static_cast<size_t>(largest) + 1, kMappedClasses));
      for (size_t k = 0; k < map.size(); ++k) map[k] = static_cast<int>(k);
      for (const auto& [from, to] : from_to) map[from] = to;
      classes->id_maps[key] = map;
    }
  std::string pairs;
  for (const auto& [from, to] : from_to) pairs += fmt::format("{}{}:{}", pairs.empty() ? "" : ",", from, to);
  classes->notes.push_back(fmt::format("prediction classes mapped by --class-map {}", pairs));
}

}  // namespace ipd
