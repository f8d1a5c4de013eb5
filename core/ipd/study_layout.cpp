#include "core/ipd/study_layout.h"

#include <fmt/format.h>

#include <algorithm>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <set>

#include "core/study/yolo_source.h"
#include "core/util/contained_file.h"
#include "core/util/number_text.h"

namespace fs = std::filesystem;

namespace ipd {

namespace {

constexpr int kLookDeeper = 3;
constexpr size_t kScenesLookedInto = 20;  // enough to name the classes the labels hold  // runs/detect/exp/labels is
                                          // three folders below a model's folder

std::string first_stems(const std::vector<std::string>& stems) {
  std::string out;
  for (size_t k = 0; k < std::min<size_t>(3, stems.size()); ++k) out += (k ? ", " : "") + stems[k];
  return fmt::format("{}{} ({} scene{})", out, stems.size() > 3 ? ", ..." : "",
                     grouped_thousands(static_cast<long long>(stems.size())), stems.size() == 1 ? "" : "s");
}

bool is_label_name(const FolderEntry& e) {
  return !e.folder && e.name != "classes.txt" && fs::path(e.name).extension() == ".txt";
}

// The label files directly in root/rel; none when it can't be listed (open_study says why).
int label_files_at(const std::string& root, const std::string& rel) {
  try {
    int n = 0;
    for (const FolderEntry& e : entries_beneath(root, rel)) n += is_label_name(e) ? 1 : 0;
    return n;
  } catch (const IoError&) {
    return 0;
  }
}

// The first folder below root/rel (in name order, at most `depth` levels down) that holds label files, and how
// many; never through a link.
std::optional<std::pair<std::string, int>> label_files_below(const std::string& root, const std::string& rel,
                                                             int depth) {
  std::vector<FolderEntry> entries;
  try {
    entries = entries_beneath(root, rel);
  } catch (const IoError&) {
    return std::nullopt;
  }
  for (const FolderEntry& e : entries) {
    if (!e.folder) continue;
    const std::string sub = rel + "/" + e.name;
    if (const int n = label_files_at(root, sub); n > 0) return std::make_pair(sub, n);
    if (depth > 1)
      if (auto deeper = label_files_below(root, sub, depth - 1)) return deeper;
  }
  return std::nullopt;
}

std::vector<std::string> sub_folders_with_labels(const std::string& root, const std::string& rel, int* files) {
  std::vector<std::string> out;
  try {
    for (const FolderEntry& e : entries_beneath(root, rel))
      if (e.folder)
        if (const int n = label_files_at(root, rel + "/" + e.name); n > 0) {
          out.push_back(e.name + "/");
          *files += n;
        }
  } catch (const IoError&) {
  }
  return out;
}

// A prediction set `ipd import predictions --no-conf` wrote (its import.json says so).
bool imported_without_confidences(const std::string& root, const std::string& set) {
  try {
    const auto text = read_file_beneath(root, set + "/import.json", size_t{1} << 20);
    if (!text) return false;
    const nlohmann::json j = nlohmann::json::parse(*text, nullptr, false);
    return j.is_object() && j.contains("confidence") && j["confidence"].is_string() &&
           j["confidence"].get<std::string>().rfind("none", 0) == 0;
  } catch (const IoError&) {
    return false;
  }
}

std::string joined(const std::vector<std::string>& v) {
  std::string out;
  for (const auto& s : v) out += (out.empty() ? "" : ", ") + s;
  return out;
}

// Two domains without a scene in common: their first names, and what tells them apart when it is a prefix or
// suffix one of them carries.
std::string no_shared_scene(const Domain& a, const Domain& b) {
  std::string hint;
  for (size_t i = 0; i < std::min<size_t>(a.stems.size(), 20) && hint.empty(); ++i)
    for (size_t j = 0; j < std::min<size_t>(b.stems.size(), 20) && hint.empty(); ++j) {
      const std::string& x = a.stems[i];
      const std::string& y = b.stems[j];
      if (const std::string d = name_difference(x, y); !d.empty())
        hint = fmt::format("; {}'s names are {}'s with {} ({} against {})", x.size() > y.size() ? a.name : b.name,
                           x.size() > y.size() ? b.name : a.name, d, x, y);
    }
  if (!hint.empty())
    hint += " (a tool's mark: ipd import yolo maps Label Studio's and Roboflow's names back, docs/import.md)";
  // Names a tool mangled (Roboflow's "<name>_jpg.rf.<hash>", Label Studio's "<id>-<name>"): its splits or its
  // export named as domains.
  for (const Domain* d : {&a, &b}) {
    if (!hint.empty() || d->stems.empty()) break;
    const std::string& first = d->stems.front();
    const std::string name = scene_stem(first, has_upload_prefix(first));
    if (name != first)
      hint = fmt::format(
          "; {}'s names are a tool's ({} is scene '{}' by the rules of docs/import.md): bring the "
          "export in with ipd import yolo, which maps them back and merges its splits",
          d->name, first, name);
  }
  return fmt::format(
      "'{}' and '{}' share no scene (scenes pair across domains by file stem): {} has {}, {} has {}{}; no IPD can "
      "be measured between them",
      a.name, b.name, a.name, first_stems(a.stems), b.name, first_stems(b.stems), hint);
}

// A domain's own problems: labels only in sub-folders, and each chosen model's set nested too deep or imported
// without confidences.
// Whether a set of label files read (GT, or a model's predictions) held a file: what was read answers it, with
// no second listing of a folder of 10,000 files.
bool holds_a_file(const std::map<std::string, LabelFile>* files) {
  return files && std::any_of(files->begin(), files->end(), [](const auto& f) { return f.second.exists; });
}

void domain_problems(const StudyLabels& labels, const Domain& d, const std::vector<ModelInfo>& models,
                     std::vector<LayoutProblem>* out) {
  const Study& study = labels.study;
  const std::string labels_dir = d.name + "/labels";
  const auto gt = labels.gt.find(d.name);
  if (!holds_a_file(gt == labels.gt.end() ? nullptr : &gt->second)) {
    int files = 0;
    const std::vector<std::string> subs = sub_folders_with_labels(study.root, labels_dir, &files);
    if (!subs.empty())
      out->push_back({fmt::format("{}/: no label files of its own, but {} in its sub-folder{} {}; a study reads "
                                  "<domain>/labels/<stem>.txt only, so domain '{}' has no ground truth (a dataset's "
                                  "splits: ipd import yolo brings them in, merged, docs/import.md)",
                                  (fs::path(study.root) / labels_dir).string(), files, subs.size() == 1 ? "" : "s",
                                  joined(subs), d.name),
                      true});
  }
  for (const ModelInfo& m : models) {
    if (std::find(d.models.begin(), d.models.end(), m.name) == d.models.end()) continue;
    const std::string set = d.name + "/predictions/" + m.name;
    const std::string shown = (fs::path(study.root) / set).string();
    if (imported_without_confidences(study.root, set))
      out->push_back({fmt::format("{}/: imported without confidences (--no-conf, {}/import.json): every box has "
                                  "confidence 1, so AP, --conf and the confidence breakdown say nothing about '{}'",
                                  shown, set, m.name),
                      false});
    const std::map<std::string, LabelFile>* predictions = nullptr;
    if (const auto in = labels.predictions.find(d.name); in != labels.predictions.end())
      if (const auto of = in->second.find(m.name); of != in->second.end()) predictions = &of->second;
    if (holds_a_file(predictions)) continue;
    if (const auto deeper = label_files_below(study.root, set, kLookDeeper)) {
      const std::string where = (fs::path(study.root) / deeper->first).string();
      out->push_back({fmt::format("{}/: no prediction files of its own; they are nested too deep, {} in {}/ (expected "
                                  "{}/<stem>.txt): every rock of '{}' would count as missed by '{}'; move them up, or "
                                  "bring the run in with ipd import predictions {} --out {} --model {}",
                                  shown, deeper->second, where, shown, d.name, m.name, where,
                                  (fs::path(study.root) / d.name).string(), m.name),
                      true});
    }
  }
}

// No GT box of the chosen class in the scenes `an` and `bn` share, with the classes their label files hold.
std::optional<LayoutProblem> class_problem(const StudyLabels& labels, const std::string& an, const std::string& bn,
                                           const SceneMatch& m) {
  const Study& study = labels.study;
  const int cls = study.config.rock_class;
  if (cls < 0) return std::nullopt;  // all classes, or none chosen (a one-class study's class is settled)
  for (const std::string& stem : m.common)
    for (const std::string* domain : {&an, &bn})
      for (const Box& box : labels.gt_of(*domain, stem).boxes)
        if (box.cls == cls) return std::nullopt;  // one box of the class is enough
  // What the label files hold instead (the class filter dropped it when they were read): the first scenes'.
  std::map<int, long> held;
  for (size_t k = 0; k < std::min<size_t>(m.common.size(), kScenesLookedInto); ++k)
    for (const std::string* domain : {&an, &bn}) {
      const LabelFile f = read_labels_beneath(study.root, *domain + "/labels/" + m.common[k] + ".txt", {});
      for (const Box& box : f.boxes) ++held[box.cls];
    }
  std::string others;
  for (const auto& [c, n] : held)
    others +=
        fmt::format("{}{}: {} box{}", others.empty() ? "" : ", ", study.classes.describe(c), n, n == 1 ? "" : "es");
  const std::string first =
      m.common.size() > kScenesLookedInto ? fmt::format(" (in the first {} scenes)", kScenesLookedInto) : std::string();
  return LayoutProblem{
      fmt::format("no ground-truth box of {} in the {} scenes '{}' and '{}' share{}: choose the class with --class or "
                  "study.yaml's rock_class",
                  study.classes.describe(cls), m.common.size(), an, bn,
                  others.empty() ? std::string("; their label files hold no boxes at all")
                                 : "; their label files hold " + others + first),
      true};
}

}  // namespace

std::string name_difference(const std::string& a, const std::string& b) {
  if (a.size() == b.size() || a.empty() || b.empty()) return {};
  const std::string& longer = a.size() > b.size() ? a : b;
  const std::string& shorter = a.size() > b.size() ? b : a;
  const size_t extra = longer.size() - shorter.size();
  if (longer.compare(extra, shorter.size(), shorter) == 0)
    return "the prefix '" + quoted_for_message(longer.substr(0, extra)) + "'";
  if (longer.compare(0, shorter.size(), shorter) == 0)
    return "the suffix '" + quoted_for_message(longer.substr(shorter.size())) + "'";
  return {};
}

std::vector<LayoutProblem> layout_problems(const StudyLabels& labels,
                                           const std::vector<std::pair<std::string, std::string>>& pairs,
                                           const std::vector<ModelInfo>& models) {
  const Study& study = labels.study;
  std::vector<LayoutProblem> out;
  std::set<std::string> in_pairs;
  for (const auto& [a, b] : pairs) {
    in_pairs.insert(a);
    in_pairs.insert(b);
  }
  for (const Domain& d : study.domains)
    if (in_pairs.count(d.name)) domain_problems(labels, d, models, &out);
  for (const auto& [an, bn] : pairs) {
    const Domain* a = study.domain(an);
    const Domain* b = study.domain(bn);
    if (!a || !b || a->stems.empty() || b->stems.empty()) continue;
    const SceneMatch m = match_scenes(*a, *b);
    if (m.common.empty()) {
      out.push_back({no_shared_scene(*a, *b), true});
      continue;
    }
    const size_t left_out = m.only_a.size() + m.only_b.size();
    if (left_out > m.common.size())
      out.push_back({fmt::format("'{}' and '{}' share only {} of their {} scenes: {} of {} and {} of {} have no "
                                 "counterpart (e.g. {}), so most of the study is in no IPD",
                                 an, bn, m.common.size(), m.common.size() + left_out, m.only_a.size(), an,
                                 m.only_b.size(), bn, m.only_a.empty() ? m.only_b.front() : m.only_a.front()),
                     true});
    if (auto p = class_problem(labels, an, bn, m)) out.push_back(std::move(*p));
  }
  return out;
}

}  // namespace ipd
