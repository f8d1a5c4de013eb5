#include "core/study/prediction_import.h"

#include <fmt/format.h>

#include <algorithm>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <set>
#include <stdexcept>

#include "core/study/coco_import.h"
#include "core/study/file_sets.h"
#include "core/study/study.h"
#include "core/study/study_names.h"
#include "core/study/yolo_source.h"
#include "core/util/contained_file.h"
#include "core/util/json_output.h"
#include "core/util/number_text.h"

namespace fs = std::filesystem;

namespace ipd {

std::string PredictionImportOptions::validate() const {
  if (source.empty()) return "source must name a run folder or a COCO results file, got an empty path";
  if (out_dir.empty()) return "out_dir must name the domain directory, got an empty path";
  if (model.empty()) return "model must name the prediction set, got an empty name";
  if (const std::string why = file_name_problem(model, kMaxModelNameBytes); !why.empty())
    return "model '" + printable_name(model, 60) + "' " + why;
  return {};
}

void PredictionImportOptions::check() const {
  if (const std::string problem = validate(); !problem.empty())
    throw std::invalid_argument("prediction import options: " + problem);
}

namespace {

std::string absolute(const std::string& p) {
  const fs::path a = fs::absolute(p).lexically_normal();
  return (a.has_filename() ? a : a.parent_path()).string();
}

// The entries of the folder `dir` (a path the user named: it may itself be a link), none of them followed.
std::vector<FolderEntry> entries_of(const std::string& dir) {
  try {
    std::error_code ec;
    const fs::path r = fs::canonical(dir, ec);
    if (ec) throw StudyError(dir + ": " + ec.message());
    return entries_beneath(r.parent_path().string(), r.filename().string());
  } catch (const IoError& e) {
    throw StudyError(e.what());
  }
}

void refuse_link(const std::string& path, const char* what) {
  std::error_code ec;
  if (fs::is_symlink(fs::symlink_status(path, ec)))
    throw StudyError(path + ": is a symbolic link; " + what + " is never written through a link");
}

}  // namespace

std::vector<std::string> domain_scenes(const std::string& out_dir) {
  const std::string dir = absolute(out_dir);
  std::error_code ec;
  if (!fs::is_directory(fs::symlink_status(fs::path(dir) / "labels", ec)))
    throw StudyError(out_dir +
                     ": no labels/ folder; a model's predictions join a domain that is there: import its ground "
                     "truth first (ipd import yolo, ipd import coco)");
  std::vector<std::string> scenes;
  for (const std::string& f : label_files_in((fs::path(dir) / "labels").string()))
    if (f != "classes.txt") scenes.push_back(fs::path(f).stem().string());
  if (scenes.empty()) throw StudyError(out_dir + "/labels: no label files; import the domain's ground truth first");
  return scenes;
}

int write_prediction_set(const std::string& out_dir, const std::string& model,
                         const std::map<std::string, std::string>& files, const std::vector<std::string>& scenes,
                         const std::string& provenance, bool replace, int* removed) {
  const std::string domain = absolute(out_dir);
  refuse_link(domain, "a domain");
  refuse_link((fs::path(domain) / "predictions").string(), "a prediction folder");
  const std::string target = (fs::path(domain) / "predictions" / model).string();
  const std::vector<std::string> old = label_files_in(target);
  if (!old.empty() && !replace)
    throw StudyError(fmt::format(
        "{}: already holds {} label files (e.g. {}); the predictions of two runs would mix, so nothing is written "
        "(--replace replaces the whole set)",
        target, old.size(), old.front()));
  StagedFolder staged(target);
  int empty = 0;
  std::set<std::string> written;
  for (const std::string& stem : scenes) {
    const auto f = files.find(stem);
    if (f == files.end()) ++empty;
    write_new_file_beneath(staged.parent(), staged.inside(stem + ".txt"), f == files.end() ? std::string() : f->second);
    written.insert(stem + ".txt");
  }
  write_new_file_beneath(staged.parent(), staged.inside("import.json"), provenance);
  int gone = 0;
  for (const std::string& name : old)
    if (!written.count(name)) ++gone;
  staged.commit();
  if (removed) *removed = gone;
  return empty;
}

namespace {

// The label files (*.txt) directly in root/rel; 0 when it can't be listed.
size_t label_files_in(const std::string& root, const std::string& rel) {
  try {
    const std::vector<FolderEntry> entries = entries_beneath(root, rel);
    return static_cast<size_t>(std::count_if(entries.begin(), entries.end(), [](const FolderEntry& e) {
      return !e.folder && fs::path(e.name).extension() == ".txt";
    }));
  } catch (const IoError&) {
    return 0;
  }
}

// The first folder below root/rel, at most `depth` levels down (in name order, never through a link), that holds
// labels/ with label files: a run; "" when there is none.
std::string run_below(const std::string& root, const std::string& rel, int depth) {
  if (depth <= 0) return {};
  std::vector<FolderEntry> entries;
  try {
    entries = entries_beneath(root, rel);
  } catch (const IoError&) {
    return {};
  }
  for (const FolderEntry& e : entries) {
    if (!e.folder) continue;
    const std::string sub = rel + "/" + e.name;
    if (label_files_in(root, sub + "/labels") > 0) return sub;
    if (const std::string deeper = run_below(root, sub, depth - 1); !deeper.empty()) return deeper;
  }
  return {};
}

// Where a run's label files are: SRC/labels/ (a run folder: runs/detect/exp), or SRC itself when it holds them.
std::string run_labels_folder(const std::string& src) {
  const std::string dir = absolute(src);
  std::error_code ec;
  if (!fs::is_directory(fs::symlink_status(dir, ec)))
    throw StudyError(src + ": expected a run folder (runs/detect/exp), its labels/ folder, or a COCO results .json");
  if (fs::is_directory(fs::symlink_status(fs::path(dir) / "labels", ec))) return dir + "/labels";
  const std::vector<FolderEntry> entries = entries_of(dir);
  std::vector<std::string> runs;
  for (const FolderEntry& e : entries) {
    if (!e.folder && fs::path(e.name).extension() == ".txt") return dir;
    if (e.folder && fs::is_directory(fs::symlink_status(fs::path(dir) / e.name / "labels", ec))) runs.push_back(e.name);
  }
  if (runs.empty()) {
    // A run kept one or more folders down (an archive unzipped into a folder of its own, runs/detect/exp kept
    // whole): said with where it is, rather than "no label files".
    const fs::path canon = fs::canonical(dir, ec);
    const std::string parent = canon.parent_path().string(), name = canon.filename().string();
    if (const std::string run = ec ? std::string() : run_below(parent, name, 3); !run.empty()) {
      const std::string shown = dir + run.substr(name.size());
      throw StudyError(
          fmt::format("{}: no label files here or in labels/, but {} holds a run's labels/ ({} label "
                      "files): name that run, ipd import predictions {} --out ... --model ...",
                      src, shown, label_files_in(parent, run + "/labels"), shown));
    }
    throw StudyError(src +
                     ": no label files here or in labels/; expected a run of yolov5 detect.py --save-txt "
                     "--save-conf or yolo predict save_txt=True save_conf=True (runs/detect/exp)");
  }
  std::string list;
  for (const auto& r : runs) list += (list.empty() ? "" : ", ") + r + "/";
  throw StudyError(fmt::format("{}: holds the run folder{} {}, not a run's files; name the run, e.g. {}", src,
                               runs.size() == 1 ? "" : "s", list, (fs::path(dir) / runs.front()).string()));
}

// The scene a run's file belongs to: its own stem, the name the domain's import mapped (import.json), or the
// stem a tool's mangling rule gives back (yolo_source.h).
class SceneNames {
 public:
  SceneNames(const std::string& out_dir, const std::vector<std::string>& scenes)
      : scenes_(scenes.begin(), scenes.end()) {
    const std::string domain = absolute(out_dir);
    std::optional<std::string> text;
    try {
      text = read_file_beneath(domain, "import.json", 64 << 20);
    } catch (const IoError&) {
    }
    if (!text) return;
    const nlohmann::json j = nlohmann::json::parse(*text, nullptr, false);
    if (!j.is_object() || !j.contains("renamed") || !j["renamed"].is_object()) return;
    for (const auto& [stem, file] : j["renamed"].items())
      if (file.is_string()) by_source_[fs::path(file.get<std::string>()).stem().string()] = stem;
  }
  std::string scene_of(const std::string& stem, bool* renamed) const {
    *renamed = false;
    if (scenes_.count(stem)) return stem;
    *renamed = true;
    if (const auto it = by_source_.find(stem); it != by_source_.end()) return it->second;
    return scene_stem(stem, has_upload_prefix(stem));
  }
  bool has(const std::string& stem) const { return scenes_.count(stem) > 0; }

 private:
  std::set<std::string> scenes_;
  std::map<std::string, std::string> by_source_;
};

std::string first_few(const std::vector<std::string>& v) {
  std::string out;
  for (size_t k = 0; k < std::min<size_t>(3, v.size()); ++k) out += (k ? ", " : "") + v[k];
  return v.size() > 3 ? out + ", ..." : out;
}

// Each line with " 1" added: a run written without confidences, read as sure of every box (--no-conf).
std::string with_conf_one(const std::string& text) {
  std::string out;
  size_t at = 0;
  while (at < text.size()) {
    size_t end = std::min(text.find('\n', at), text.size());
    std::string line = text.substr(at, end - at);
    const bool cr = !line.empty() && line.back() == '\r';
    if (cr) line.pop_back();
    if (line.find_first_not_of(" \t") != std::string::npos && line.find_first_not_of(" \t") != line.find('#'))
      line += " 1";
    out += line + (cr ? "\r\n" : "\n");
    at = end + 1;
  }
  return out;
}

// A run's label file, read as predictions and, when that fails, as boxes without a confidence.
struct RunFile {
  std::string name, text;
  LabelFile as_prediction, as_gt;
};

std::vector<RunFile> read_run_files(const std::string& folder) {
  std::vector<RunFile> files;
  for (const FolderEntry& e : entries_of(folder)) {
    if (e.folder || fs::path(e.name).extension() != ".txt" || e.name == "classes.txt") continue;
    const std::string shown = (fs::path(folder) / e.name).string();
    std::optional<std::string> text;
    try {
      text = read_file_beneath(folder, e.name, kMaxLabelFileBytes);
    } catch (const IoError& err) {
      throw StudyError(std::string(err.what()) + " (links in an import's source are never followed)");
    }
    RunFile f{e.name, text.value_or(""), {}, {}};
    f.as_prediction = parse_labels(f.text, shown, {LabelKind::kPrediction});
    if (!f.as_prediction.errors.empty()) f.as_gt = parse_labels(f.text, shown, {LabelKind::kGroundTruth});
    files.push_back(std::move(f));
  }
  if (files.empty()) throw StudyError(folder + ": no label files (*.txt); nothing is written");
  return files;
}

// A run saved without confidences: some file has boxes of 5 columns, every file that fails as predictions
// reads as such boxes, and none carries a confidence (a run of empty files is a run that found nothing).
bool without_confidences(const std::vector<RunFile>& files) {
  bool any_conf = false, all_plain = true, any_plain = false;
  for (const RunFile& f : files) {
    if (f.as_prediction.errors.empty() && !f.as_prediction.boxes.empty()) any_conf = true;
    if (f.as_prediction.errors.empty()) continue;
    if (f.as_gt.errors.empty())
      any_plain = true;
    else
      all_plain = false;
  }
  return any_plain && all_plain && !any_conf;
}

PredictionImportReport import_run(const PredictionImportOptions& o) {
  PredictionImportReport r;
  r.kind = "YOLO run";
  const std::vector<std::string> scenes = domain_scenes(o.out_dir);
  r.folder = run_labels_folder(o.source);
  const SceneNames names(o.out_dir, scenes);
  std::vector<RunFile> files = read_run_files(r.folder);
  const bool no_conf = without_confidences(files);
  if (no_conf && !o.no_conf)
    throw StudyError(fmt::format(
        "{}: the run wrote no confidences (5 columns: class cx cy w h); IPD and AP rank detections by them. Run "
        "the detector again with them: yolov5 `python detect.py --save-txt --save-conf ...` or Ultralytics `yolo "
        "predict save_txt=True save_conf=True ...`; or give --no-conf to read every box with confidence 1 "
        "(import.json then says so)",
        r.folder));
  if (!no_conf && o.no_conf)
    throw StudyError(r.folder + ": --no-conf was given but the run's files carry confidences; leave it out");
  r.conf_one = no_conf;
  std::map<std::string, std::string> out;
  std::map<std::string, std::string> from;  // scene -> the run's file, for collisions
  std::vector<std::string> unknown;
  for (RunFile& f : files) {
    const LabelFile& parsed = no_conf ? f.as_gt : f.as_prediction;
    r.errors.insert(r.errors.end(), parsed.errors.begin(), parsed.errors.end());
    r.detections += static_cast<int>(parsed.boxes.size());
    bool renamed = false;
    const std::string stem = names.scene_of(fs::path(f.name).stem().string(), &renamed);
    if (!names.has(stem)) {
      unknown.push_back(f.name);
      continue;
    }
    if (const auto [it, fresh] = from.emplace(stem, f.name); !fresh)
      throw StudyError(fmt::format("{} and {} are both predictions of scene '{}'; nothing is written",
                                   (fs::path(r.folder) / it->second).string(), (fs::path(r.folder) / f.name).string(),
                                   stem));
    if (renamed) ++r.renamed;
    out[stem] = no_conf ? with_conf_one(f.text) : f.text;
    ++r.files;
  }
  if (!unknown.empty())
    throw StudyError(fmt::format(
        "{}: {} of the run's {} files name no scene of {} (e.g. {}); its scenes are {}; was the run made on this "
        "domain's pictures? Nothing is written",
        r.folder, unknown.size(), files.size(), o.out_dir, first_few(unknown), first_few(scenes)));
  if (!r.errors.empty()) return r;
  nlohmann::ordered_json j;
  j["imported_with"] = "ipd import predictions";
  j["source"] = r.folder;
  j["kind"] = r.kind;
  j["confidence"] =
      no_conf ? "none in the run's files: every box read with confidence 1 (--no-conf)" : "from the run's files";
  std::vector<std::string> empty;
  for (const std::string& s : scenes)
    if (!out.count(s)) empty.push_back(s);
  j["no_detections"] = empty;
  r.no_detection_files =
      write_prediction_set(o.out_dir, o.model, out, scenes, dump_json_output(j, 1) + "\n", o.replace, &r.removed);
  r.written = true;
  return r;
}

PredictionImportReport import_coco_results(const PredictionImportOptions& o) {
  if (o.gt.empty())
    throw StudyError(o.source +
                     ": COCO results name their pictures by image id; give --gt with the COCO annotations file "
                     "those ids come from");
  if (o.no_conf) throw StudyError(o.source + ": --no-conf is for YOLO runs; COCO results carry a score");
  CocoImportOptions c;
  c.annotations = o.gt;
  c.results = o.source;
  c.out_dir = o.out_dir;
  c.model = o.model;
  c.replace = o.replace;
  c.skip_bad_entries = o.skip_bad_entries;
  c.predictions_only = true;
  const CocoImportReport cr = import_coco(c);
  PredictionImportReport r;
  r.kind = "COCO results";
  r.folder = o.source;
  if (!cr.collisions.empty()) {
    std::string all;
    for (const std::string& col : cr.collisions) all += (all.empty() ? "" : "\n") + col;
    throw StudyError(all + "\n(image name collisions; nothing written)");
  }
  r.errors = cr.errors;
  r.files = cr.images;
  r.detections = cr.detections;
  r.no_detection_files = cr.no_detection_files;
  r.removed = cr.removed;
  r.rle_masks_cut = cr.rle_masks_cut;
  r.rle_pixels_left_out = cr.rle_pixels_left_out;
  r.written = cr.written;
  return r;
}

}  // namespace

PredictionImportReport import_predictions(const PredictionImportOptions& o) {
  o.check();
  std::string ext = fs::path(o.source).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char ch) { return std::tolower(ch); });
  if (ext == ".json") return import_coco_results(o);
  return import_run(o);
}

}  // namespace ipd
