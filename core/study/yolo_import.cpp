#include "core/study/yolo_import.h"

#include <fmt/format.h>

#include <algorithm>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <set>
#include <stdexcept>
#include <string_view>

#include "core/study/file_sets.h"
#include "core/study/study.h"
#include "core/util/contained_file.h"
#include "core/util/json_output.h"
#include "core/util/number_text.h"

namespace fs = std::filesystem;

namespace ipd {

std::string YoloImportOptions::validate() const {
  if (source.empty()) return "source must name a data.yaml or a dataset folder, got an empty path";
  if (out_dir.empty()) return "out_dir must name the domain directory to fill, got an empty path";
  return {};
}

void YoloImportOptions::check() const {
  if (const std::string problem = validate(); !problem.empty())
    throw std::invalid_argument("YOLO import options: " + problem);
}

void check_class_names(const std::string& domain_dir, const std::vector<std::string>& names,
                       const std::string& names_file) {
  const fs::path domain = fs::path(domain_dir).lexically_normal();
  const fs::path mine = domain.filename().empty() ? domain.parent_path() : domain;
  const fs::path study = mine.parent_path().empty() ? fs::path(".") : mine.parent_path();
  std::optional<std::string> yaml;
  try {
    yaml = read_file_beneath(study.string(), "study.yaml", kMaxStudyYamlBytes);
  } catch (const IoError& e) {
    throw StudyError(e.what());
  }
  if (yaml) {
    const std::string yaml_file = (study / "study.yaml").string();
    const StudyConfig config = parse_study_config(*yaml, yaml_file);
    if (!config.class_names.empty())
      for (size_t k = 0; k < names.size(); ++k)
        if (!names[k].empty() &&
            std::find(config.class_names.begin(), config.class_names.end(), names[k]) == config.class_names.end())
          throw StudyError(fmt::format(
              "{}: class {} \"{}\" is not among the study's classes in {}; a class must have one name in every "
              "label set (rename it, or add it to study.yaml's classes), so nothing is written",
              names_file, k, quoted_for_message(names[k]), yaml_file));
  }
  if (const std::string conflict = class_name_conflict(domain_dir, names); !conflict.empty())
    throw StudyError(
        fmt::format("{}: {}; a class number must be the same class in every domain of a study "
                    "(rock_class picks one number for all), so nothing is written",
                    names_file, conflict));
}

namespace {

// `text` with the lines of `bad` (1-based) written as comments, so the study reads it without them and the
// line is still there to see.
std::string with_lines_commented(const std::string& text, const std::set<int>& bad) {
  std::string out;
  size_t at = 0;
  for (int line = 1; at < text.size(); ++line) {
    const size_t end = std::min(text.find('\n', at), text.size());
    if (bad.count(line)) out += "# skipped by ipd import yolo --skip-bad-lines: ";
    out.append(text, at, end - at);
    if (end < text.size()) out += '\n';
    at = end + 1;
  }
  return out;
}

// Reads and checks one label file of the source: every line a box (label_io's rules), every class named. With
// skip_bad_lines, the bad lines are commented out of the text returned.
std::string checked_label(const YoloSource& s, const SourceScene& x, bool skip_bad_lines, YoloImportReport* r,
                          long* box_lines) {
  const std::string shown = (fs::path(s.root) / x.label).string();
  std::optional<std::string> text;
  try {
    text = read_file_beneath(s.root, x.label, kMaxLabelFileBytes);
  } catch (const IoError& e) {
    throw StudyError(std::string(e.what()) + " (links in an import's source are never followed)");
  }
  if (!text) throw StudyError(shown + ": vanished while the source was read");
  LabelParseOptions po;
  po.kind = LabelKind::kGroundTruth;
  LabelFile f = parse_labels(*text, shown, po);
  r->errors.insert(r->errors.end(), f.errors.begin(), f.errors.end());
  std::set<int> good(f.line_of_box.begin(), f.line_of_box.end());
  int unnamed = 0;
  for (size_t k = 0; k < f.boxes.size(); ++k) {
    const int cls = f.boxes[k].cls;
    if (!s.class_names.empty() &&
        (cls < 0 || static_cast<size_t>(cls) >= s.class_names.size() || s.class_names[cls].empty())) {
      r->errors.push_back({shown, f.line_of_box[k],
                           fmt::format("class {} is not among the classes {} names ({} of them); expected a named "
                                       "class number",
                                       cls, s.names_file, s.class_names.size())});
      good.erase(f.line_of_box[k]);
      ++unnamed;
    }
  }
  int malformed = unnamed;
  for (const LabelError& e : f.errors) malformed += e.malformed_lines();
  r->boxes += static_cast<int>(f.boxes.size()) - unnamed;
  *box_lines += static_cast<long>(f.boxes.size()) + malformed - unnamed;
  if (!skip_bad_lines || malformed == 0) return *text;
  // Every line that is neither a box kept, nor blank, nor a comment was refused by the reader (the list of
  // errors stops at kMaxListedErrors a file, so the lines are found here, not from it).
  std::set<int> bad;
  size_t at = 0;
  for (int line = 1; at < text->size(); ++line) {
    const size_t end = std::min(text->find('\n', at), text->size());
    std::string_view v(text->data() + at, end - at);
    if (line == 1 && v.substr(0, 3) == "\xEF\xBB\xBF") v.remove_prefix(3);
    const std::string_view fields = v.substr(0, v.find('#'));  // the reader's fields end at a comment
    if (fields.find_first_not_of(" \t\r\v\f") != std::string_view::npos && !good.count(line)) bad.insert(line);
    at = end + 1;
  }
  r->skipped_lines += static_cast<int>(bad.size());
  return with_lines_commented(*text, bad);
}

// <domain>/import.json: where the domain came from and which names were mapped back, so nothing is lost.
std::string provenance(const YoloSource& s, const YoloImportOptions& o) {
  nlohmann::ordered_json j;
  j["imported_with"] = "ipd import yolo";
  j["source"] = fs::absolute(o.source).lexically_normal().string();
  j["layout"] = s.layout;
  j["splits"] = s.splits;
  nlohmann::ordered_json renamed = nlohmann::ordered_json::object();
  for (const SourceScene& x : s.scenes)
    if (x.stem != x.source_stem) renamed[x.stem] = x.label.empty() ? x.picture : x.label;
  j["renamed"] = renamed;
  return dump_json_output(j, 1) + "\n";
}

void write_domain(const YoloImportOptions& o, const std::vector<std::string>& texts, YoloImportReport* r) {
  const YoloSource& s = r->source;
  StagedFolder staged(o.out_dir);
  const std::string& root = staged.parent();
  for (size_t k = 0; k < s.scenes.size(); ++k) {
    const SourceScene& x = s.scenes[k];
    write_new_file_beneath(root, staged.inside("labels/" + x.stem + ".txt"), texts[k]);
    if (x.picture.empty()) continue;
    link_file_beneath(root, staged.inside("images/" + x.stem + fs::path(x.picture).extension().string()),
                      (fs::path(s.root) / x.picture).string());
    ++r->linked_images;
  }
  if (!s.class_names.empty()) {
    std::string names;
    for (const auto& c : s.class_names) names += c + "\n";
    write_new_file_beneath(root, staged.inside("labels/classes.txt"), names);
  }
  write_new_file_beneath(root, staged.inside("import.json"), provenance(s, o));
  // A replaced domain keeps its prediction sets (they are of the labels before: said) and files of other kinds.
  if (staged.target_exists()) {
    for (const FolderEntry& e : entries_beneath(root, staged.target_name()))
      if (e.name != "labels" && e.name != "images" && e.name != "import.json")
        rename_beneath(root, staged.target_inside(e.name), staged.inside(e.name));
    for (const FolderEntry& e : entries_beneath(root, staged.inside("predictions")))
      if (e.folder) r->kept_prediction_sets.push_back(e.name);
  }
  staged.commit();
  r->written = true;
}

}  // namespace

YoloImportReport import_yolo(const YoloImportOptions& o) {
  o.check();
  check_domain_folder(o.out_dir, o.replace, "ipd import yolo");
  YoloImportReport r;
  r.source = find_yolo_source(o.source, o.split);
  const YoloSource& s = r.source;
  if (s.scenes.empty())
    throw StudyError(fmt::format("{}: the {} holds no label files or pictures{}; nothing is written", o.source,
                                 s.layout, o.split.empty() ? "" : " in split '" + o.split + "'"));
  if (!o.names.empty()) {
    if (!s.names_file.empty())
      throw StudyError(
          fmt::format("--names: {} names the classes of this source already; --names is for a dataset "
                      "without a names file",
                      s.names_file));
    r.source.class_names = o.names;
    r.source.names_file = "--names";
  }
  if (!s.class_names.empty()) check_class_names(o.out_dir, s.class_names, s.names_file);
  std::vector<std::string> texts;
  long box_lines = 0;
  for (const SourceScene& x : s.scenes) {
    if (x.label.empty()) ++r.without_label_file;
    texts.push_back(x.label.empty() ? std::string() : checked_label(s, x, o.skip_bad_lines, &r, &box_lines));
  }
  r.scenes = static_cast<int>(s.scenes.size());
  const bool unusable =
      std::any_of(r.errors.begin(), r.errors.end(), [](const LabelError& e) { return e.unusable_file(); });
  if (!r.errors.empty() && (!o.skip_bad_lines || unusable)) return r;
  long skipped = 0;
  for (const LabelError& e : r.errors) skipped += e.malformed_lines();
  if (2 * skipped > box_lines) {
    r.most_skipped = fmt::format(
        "{}: --skip-bad-lines would leave out {} of its {} box lines, more than half: what is left is not the "
        "dataset; fix the lines (or the layout that makes them wrong), nothing is written",
        o.source, skipped, box_lines);
    return r;
  }
  write_domain(o, texts, &r);
  return r;
}

}  // namespace ipd
