#include "core/study/yolo_source.h"

#include <yaml-cpp/yaml.h>

#include <fmt/format.h>
#include <sys/stat.h>

#include <algorithm>
#include <filesystem>
#include <map>
#include <optional>
#include <set>
#include <tuple>

#include "core/study/study_names.h"
#include "core/util/contained_file.h"
#include "core/util/errors.h"
#include "core/util/number_text.h"
#include "core/util/utf8.h"

namespace fs = std::filesystem;

namespace ipd {

namespace {

constexpr size_t kMaxDataYamlBytes = size_t{1} << 20;
constexpr int kMaxFolderDepth = 8;                   // images/<split>/<camera>/<day>/... is deep enough
constexpr size_t kMaxSourceFiles = 2000000;          // a listing past this is not a dataset folder
constexpr size_t kMaxListBytes = size_t{256} << 20;  // a list of 2,000,000 pictures' paths
constexpr const char* kPictureExtensions = ".png, .jpg, .jpeg, .tif, .tiff, .bmp or .webp";

bool is_hex(const std::string& s, size_t from, size_t count) {
  if (s.size() < from + count) return false;
  for (size_t k = from; k < from + count; ++k)
    if (!((s[k] >= '0' && s[k] <= '9') || (s[k] >= 'a' && s[k] <= 'f'))) return false;
  return true;
}

std::string shown(const std::string& root, const std::string& rel) {
  return rel.empty() ? root : (fs::path(root) / rel).string();
}

// The entries of root/rel; a symbolic link there (a file or a folder) is refused by name: a source's links
// are never followed, since one could lead anywhere (`labels -> /home/someone`).
std::vector<FolderEntry> list_source(const std::string& root, const std::string& rel) {
  std::vector<FolderEntry> entries;
  try {
    if (rel.empty()) {  // the root itself: listed from its parent (the user named it; it may be a link)
      const fs::path r = fs::canonical(root);
      entries = entries_beneath(r.parent_path().string(), r.filename().string());
    } else {
      entries = entries_beneath(root, rel);
    }
  } catch (const IoError& e) {
    throw StudyError(std::string(e.what()) + " (links in an import's source are never followed)");
  }
  for (const FolderEntry& e : entries) {
    if (e.folder) continue;
    struct stat st {};
    const std::string path = (fs::path(root) / rel / e.name).string();
    if (::lstat(path.c_str(), &st) == 0 && S_ISLNK(st.st_mode))
      throw StudyError(printable_name(path) +
                       ": is a symbolic link; links in an import's source are never followed (one could lead out "
                       "of it), so nothing is imported; copy the file it points to in its place");
  }
  return entries;
}

bool is_folder(const std::string& root, const std::string& rel) {
  std::error_code ec;
  const fs::file_status st = fs::symlink_status(fs::path(root) / rel, ec);
  if (fs::is_symlink(st))
    throw StudyError(printable_name(shown(root, rel)) +
                     ": is a symbolic link; links in an import's source are never followed (one could lead out of "
                     "it), so nothing is imported");
  return fs::is_directory(st);
}

bool is_file(const std::string& root, const std::string& rel) {
  std::error_code ec;
  return fs::exists(fs::symlink_status(fs::path(root) / rel, ec)) && !is_folder(root, rel);
}

// Every file below root/rel (paths below root), folders walked in name order.
void walk(const std::string& root, const std::string& rel, int depth, std::vector<std::string>* files) {
  if (depth > kMaxFolderDepth)
    throw StudyError(fmt::format("{}: folders nested more than {} deep; expected a dataset's images/ and labels/",
                                 shown(root, rel), kMaxFolderDepth));
  for (const FolderEntry& e : list_source(root, rel)) {
    const std::string path = rel.empty() ? e.name : rel + "/" + e.name;
    if (e.folder)
      walk(root, path, depth + 1, files);
    else
      files->push_back(path);
    if (files->size() > kMaxSourceFiles)
      throw StudyError(
          fmt::format("{}: more than {} files; expected a dataset folder", shown(root, rel), kMaxSourceFiles));
  }
}

std::string without_extension(const std::string& path) {
  const fs::path p(path);
  return (p.parent_path() / p.stem()).string();
}

// One split: pictures below `images` (when not empty) and label files below `labels`, paired by their path
// below each (images/train/a/0001.png with labels/train/a/0001.txt). Pictures without a label file are scenes
// without objects, as YOLO trains them; label files without a picture are scenes too.
void add_split(const std::string& root, const std::string& split, const std::string& images, const std::string& labels,
               std::vector<SourceScene>* scenes) {
  std::map<std::string, SourceScene> by_path;  // path below the split's folder, without extension
  std::vector<std::string> files;
  if (!images.empty()) walk(root, images, 0, &files);
  for (const std::string& f : files) {
    if (!is_picture_name(f) || (images == labels && ascii_lower(fs::path(f).extension().string()) == ".txt")) continue;
    const std::string key = without_extension(fs::path(f).lexically_relative(images.empty() ? "." : images).string());
    SourceScene& s = by_path[key];
    if (!s.picture.empty())
      throw StudyError(fmt::format("{}: {} is a picture of this scene too; keep one of them",
                                   printable_name(shown(root, f)), printable_name(shown(root, s.picture))));
    s.picture = f;
  }
  files.clear();
  if (is_folder(root, labels)) walk(root, labels, 0, &files);
  for (const std::string& f : files) {
    const fs::path p(f);
    if (p.extension() != ".txt" || p.filename() == "classes.txt") continue;
    SourceScene& s = by_path[without_extension(p.lexically_relative(labels.empty() ? "." : labels).string())];
    s.label = f;
  }
  // Pictures and labels pair by their path below images/ and labels/: in a split with pictures, a label file
  // with none at its path was moved or misplaced, and would become a scene without its picture.
  const bool has_pictures =
      std::any_of(by_path.begin(), by_path.end(), [](const auto& kv) { return !kv.second.picture.empty(); });
  for (const auto& [key, s] : by_path)
    if (has_pictures && s.picture.empty())
      throw StudyError(fmt::format(
          "{}: no picture for this label file at {}.* (labels and pictures pair by their path below {} and {}); "
          "move it beside its picture's path, or remove it",
          printable_name(shown(root, s.label)), printable_name(shown(root, (fs::path(images) / key).string())),
          printable_name(shown(root, labels)), printable_name(shown(root, images))));
  for (auto& [key, s] : by_path) {
    s.split = split;
    s.source_stem = fs::path(key).filename().string();
    scenes->push_back(s);
  }
}

// Class names of a names file: one a line (obj.names, classes.txt).
std::vector<std::string> names_lines(const std::string& root, const std::string& rel) {
  std::optional<std::string> text;
  try {
    text = read_file_beneath(root, rel, kMaxDataYamlBytes);
  } catch (const IoError& e) {
    throw StudyError(e.what());
  }
  std::vector<std::string> names;
  if (!text) return names;
  size_t at = 0;
  while (at < text->size()) {
    size_t end = std::min(text->find('\n', at), text->size());
    std::string line = text->substr(at, end - at);
    if (!line.empty() && line.back() == '\r') line.pop_back();
    names.push_back(line);
    at = end + 1;
  }
  while (!names.empty() && names.back().empty()) names.pop_back();
  return names;
}

// data.yaml's `names`: a list, or a mapping of class number to name.
std::vector<std::string> yaml_names(const YAML::Node& n, const std::string& file) {
  const int line = n.Mark().line + 1;
  std::vector<std::string> names;
  if (n.IsSequence()) {
    for (const auto& v : n) {
      if (!v.IsScalar())
        throw StudyError(fmt::format("{}:{}: names: expected a list of class names, found a list or mapping inside",
                                     file, v.Mark().line + 1));
      names.push_back(v.Scalar());
    }
    return names;
  }
  if (!n.IsMap())
    throw StudyError(fmt::format(
        "{}:{}: names: expected a list of class names ([rock, shadow]) or a mapping of class number to name", file,
        line));
  for (const auto& kv : n) {
    long long k = -1;
    if (!kv.first.IsScalar() || !parse_integer(kv.first.Scalar(), 0, 9999, &k) || !kv.second.IsScalar())
      throw StudyError(fmt::format("{}:{}: names: expected class number: name (0 to 9999), found '{}'", file,
                                   kv.first.Mark().line + 1,
                                   kv.first.IsScalar() ? quoted_for_message(kv.first.Scalar()) : "a list or mapping"));
    if (names.size() <= static_cast<size_t>(k)) names.resize(k + 1);
    names[k] = kv.second.Scalar();
  }
  return names;
}

std::string labels_of(const std::string& images);

// A split's folder as data.yaml gives it, below the dataset root. Roboflow's data.yaml says "../train/images"
// for the train/images beside it; Ultralytics reads that as "train/images" when "../train/images" is not
// there, and so does this.
std::string split_folder(const std::string& root, const std::string& given, const std::string& file, int line,
                         const std::string& key) {
  auto below = [&](const std::string& g) -> std::optional<std::string> {
    const fs::path p = fs::path(g).is_absolute() ? fs::path(g) : fs::path(root) / g;
    const fs::path rel = p.lexically_normal().lexically_relative(root);
    if (rel.empty() || *rel.begin() == "..") return std::nullopt;
    return rel == "." ? std::string() : rel.string();
  };
  std::optional<std::string> rel = below(given);
  std::error_code ec;
  const bool there = rel && fs::exists(fs::symlink_status(fs::path(root) / *rel, ec));
  if (!there && given.rfind("../", 0) == 0)
    if (auto stripped = below(given.substr(3)); stripped && fs::exists(fs::path(root) / *stripped, ec)) rel = stripped;
  if (!rel)
    throw StudyError(fmt::format("{}:{}: {}: '{}' leaves the dataset folder {}; expected a folder below it", file, line,
                                 key, quoted_for_message(given), root));
  if (!fs::exists(fs::symlink_status(fs::path(root) / *rel, ec)))
    throw StudyError(fmt::format("{}:{}: {}: {} is not there; expected the split's folder of pictures", file, line, key,
                                 (fs::path(root) / *rel).string()));
  if (!is_folder(root, *rel) && ascii_lower(fs::path(*rel).extension().string()) != ".txt")
    throw StudyError(
        fmt::format("{}:{}: {}: {} is not a folder; expected the split's folder of pictures or a .txt list of them",
                    file, line, key, (fs::path(root) / *rel).string()));
  return *rel;
}

// A split given as a list of pictures, one path a line (Ultralytics' `train: train.txt`, CVAT's train.txt): a
// path starting with "./" is below the list's folder, an absolute one must be below the dataset root, any other
// below the root (where Ultralytics, run from the dataset's folder, finds it); CVAT's "data/" prefix (Darknet's
// data folder, the export's root) is left out when the path is not there with it. A picture's label file is
// where Ultralytics looks for it (labels_of), and may be missing (no objects); a listed picture that is not there
// is refused with its line, unless its label file is (an export without its pictures).
void add_listed_split(const std::string& root, const std::string& split, const std::string& list,
                      std::vector<SourceScene>* scenes) {
  const std::string list_file = shown(root, list);
  std::optional<std::string> text;
  try {
    text = read_file_beneath(root, list, kMaxListBytes);
  } catch (const IoError& e) {
    throw StudyError(std::string(e.what()) + " (links in an import's source are never followed)");
  }
  if (!text) throw StudyError(list_file + ": no such file");
  size_t at = 0;
  for (int line = 1; at < text->size(); ++line) {
    const size_t end = std::min(text->find('\n', at), text->size());
    std::string given = text->substr(at, end - at);
    at = end + 1;
    while (!given.empty() && (given.back() == '\r' || given.back() == ' ' || given.back() == '\t')) given.pop_back();
    if (given.empty() || given[0] == '#') continue;
    const fs::path base = given.rfind("./", 0) == 0 ? fs::path(root) / fs::path(list).parent_path() : fs::path(root);
    auto below = [&](const std::string& g) -> std::optional<std::string> {
      const fs::path p = (fs::path(g).is_absolute() ? fs::path(g) : base / g).lexically_normal();
      const fs::path rel = p.lexically_relative(root);
      if (rel.empty() || rel == "." || *rel.begin() == "..") return std::nullopt;
      return rel.string();
    };
    std::error_code ec;
    const auto there = [&](const std::string& rel) { return fs::exists(fs::symlink_status(fs::path(root) / rel, ec)); };
    const auto label_of = [](const std::string& picture) {
      const fs::path pic(picture);
      return (fs::path(labels_of(pic.parent_path().string())) / pic.stem()).string() + ".txt";
    };
    std::optional<std::string> picture = below(given);
    if (given.rfind("data/", 0) == 0 && !(picture && (there(*picture) || there(label_of(*picture)))))
      if (const auto stripped = below(given.substr(5)); stripped && (there(*stripped) || there(label_of(*stripped))))
        picture = stripped;
    if (!picture)
      throw StudyError(fmt::format("{}:{}: '{}' leaves the dataset folder {}; expected a picture below it", list_file,
                                   line, quoted_for_message(given), root));
    if (!is_picture_name(*picture))
      throw StudyError(fmt::format("{}:{}: '{}' is not a picture ({}); expected one picture's path a line", list_file,
                                   line, quoted_for_message(given), kPictureExtensions));
    const std::string label = label_of(*picture);
    SourceScene x;
    x.split = split;
    x.source_stem = fs::path(*picture).stem().string();
    if (is_file(root, *picture)) x.picture = *picture;
    if (is_file(root, label)) x.label = label;
    if (x.picture.empty() && x.label.empty())
      throw StudyError(fmt::format("{}:{}: {} is not there, nor its label file {}; expected a picture of the split",
                                   list_file, line, printable_name(shown(root, *picture)),
                                   printable_name(shown(root, label))));
    scenes->push_back(x);
  }
}

// Ultralytics' rule: a picture's label is at the path with the last "images" folder named "labels".
std::string labels_of(const std::string& images) {
  std::vector<std::string> parts;
  for (const auto& p : fs::path(images)) parts.push_back(p.string());
  for (size_t k = parts.size(); k-- > 0;)
    if (parts[k] == "images") {
      parts[k] = "labels";
      fs::path out;
      for (const auto& p : parts) out /= p;
      return out.string();
    }
  return images;  // labels beside the pictures
}

YoloSource from_data_yaml(const fs::path& yaml) {
  const std::string file = yaml.string();
  std::optional<std::string> text;
  try {
    text = read_file_beneath(yaml.parent_path().string(), yaml.filename().string(), kMaxDataYamlBytes);
  } catch (const IoError& e) {
    throw StudyError(e.what());
  }
  if (!text) throw StudyError(file + ": no such file");
  YAML::Node doc;
  try {
    doc = YAML::Load(*text);
  } catch (const YAML::Exception& e) {
    throw StudyError(fmt::format("{}:{}: not YAML: {}; expected a dataset's data.yaml (path, train, val, names)", file,
                                 e.mark.line + 1, e.msg));
  }
  if (!doc.IsMap())
    throw StudyError(file + ": expected a mapping with train, val and names (a YOLO dataset's data.yaml)");
  YoloSource s;
  s.layout = doc["roboflow"] ? "Roboflow YOLOv5 PyTorch" : "data.yaml";
  fs::path root = yaml.parent_path();
  if (const YAML::Node p = doc["path"]; p && p.IsScalar() && !p.Scalar().empty())
    root = fs::path(p.Scalar()).is_absolute() ? fs::path(p.Scalar()) : root / p.Scalar();
  std::error_code ec;
  if (!fs::is_directory(root, ec))
    throw StudyError(fmt::format("{}:{}: path: {} is not a folder; expected the dataset's root", file,
                                 doc["path"] ? doc["path"].Mark().line + 1 : 1, root.string()));
  s.root = fs::absolute(root).lexically_normal().string();
  if (!s.root.empty() && s.root.size() > 1 && s.root.back() == '/') s.root.pop_back();
  const YAML::Node names = doc["names"];
  if (!names || names.IsNull())
    throw StudyError(file +
                     ": no names; expected the class names (names: [rock, shadow] or names: {0: rock}); a "
                     "data.yaml cut short ends before them");
  s.class_names = yaml_names(names, file);
  s.names_file = file;
  for (const char* key : {"train", "val", "test"}) {
    const YAML::Node v = doc[key];
    if (!v || v.IsNull()) continue;
    std::vector<std::string> folders;
    if (v.IsScalar()) {
      folders.push_back(v.Scalar());
    } else if (v.IsSequence()) {
      for (const auto& f : v)
        if (f.IsScalar()) folders.push_back(f.Scalar());
    }
    if (folders.empty())
      throw StudyError(
          fmt::format("{}:{}: {}: expected a folder of pictures (or a list of them)", file, v.Mark().line + 1, key));
    s.splits.push_back(key);
    for (const std::string& f : folders) {
      const std::string images = split_folder(s.root, f, file, v.Mark().line + 1, key);
      std::vector<SourceScene> scenes;
      if (is_folder(s.root, images))
        add_split(s.root, key, images, labels_of(images), &scenes);
      else
        add_listed_split(s.root, key, images, &scenes);
      s.scenes.insert(s.scenes.end(), scenes.begin(), scenes.end());
    }
  }
  if (s.splits.empty())
    throw StudyError(file + ": names no split (train, val or test); expected at least one folder of pictures");
  return s;
}

// obj.names, obj.data, obj_<subset>_data/ with each picture's label file beside it.
YoloSource from_cvat(const fs::path& dir) {
  YoloSource s;
  s.layout = "CVAT YOLO 1.1";
  s.root = dir.string();
  if (!is_file(s.root, "obj.names"))
    throw StudyError((dir / "obj.names").string() + ": not there; a CVAT YOLO 1.1 export names its classes there");
  s.class_names = names_lines(s.root, "obj.names");
  s.names_file = (dir / "obj.names").string();
  for (const FolderEntry& e : list_source(s.root, "")) {
    if (!e.folder || e.name.rfind("obj_", 0) != 0 || e.name.size() <= 9 ||
        e.name.compare(e.name.size() - 5, 5, "_data") != 0)
      continue;
    const std::string subset = e.name.substr(4, e.name.size() - 9), split = ascii_lower(subset);
    s.splits.push_back(split);
    if (!is_file(s.root, subset + ".txt")) {
      add_split(s.root, split, e.name, e.name, &s.scenes);
      continue;
    }
    // The subset's list (train.txt: data/obj_train_data/<frame>.<ext>) says which pictures it has, also when the
    // export holds only their label files (Save images not ticked). A label file it does not list is refused:
    // it would be left out without a word.
    std::vector<SourceScene> listed;
    add_listed_split(s.root, split, subset + ".txt", &listed);
    std::set<std::string> labels;
    for (const SourceScene& x : listed) labels.insert(x.label);
    std::vector<std::string> files;
    walk(s.root, e.name, 0, &files);
    for (const std::string& f : files)
      if (ascii_lower(fs::path(f).extension().string()) == ".txt" && !labels.count(f))
        throw StudyError(fmt::format("{}: a label file no line of {} names; add its picture to the list, or remove it",
                                     printable_name(shown(s.root, f)), shown(s.root, subset + ".txt")));
    s.scenes.insert(s.scenes.end(), listed.begin(), listed.end());
  }
  if (s.splits.empty())
    throw StudyError(s.root +
                     ": a CVAT YOLO 1.1 export without an obj_<subset>_data/ folder (obj_train_data/); "
                     "export again with the annotations");
  return s;
}

// images/ and labels/, flat (Label Studio, with classes.txt) or with a folder per split.
YoloSource from_folders(const fs::path& dir, const std::string& labels_root, const std::string& images_root) {
  YoloSource s;
  s.root = dir.string();
  bool flat = false;
  std::vector<std::string> split_names;
  for (const FolderEntry& e : list_source(s.root, labels_root)) {
    if (e.folder)
      split_names.push_back(e.name);
    else if (fs::path(e.name).extension() == ".txt" && e.name != "classes.txt")
      flat = true;
  }
  if (is_file(s.root, "classes.txt")) {
    s.class_names = names_lines(s.root, "classes.txt");
    s.names_file = (dir / "classes.txt").string();
  }
  if (flat) {
    s.layout = s.names_file.empty() ? "dataset folder" : "Label Studio YOLO";
    s.splits.push_back("");
    add_split(s.root, "", is_folder(s.root, images_root) ? images_root : "", labels_root, &s.scenes);
    return s;
  }
  s.layout = "dataset folder";
  for (const std::string& split : split_names) {
    const std::string images = images_root + "/" + split;
    s.splits.push_back(split);
    add_split(s.root, split, is_folder(s.root, images) ? images : "", labels_root + "/" + split, &s.scenes);
  }
  return s;
}

// Roboflow's (or any) train/valid/test folders, each with images/ and labels/.
YoloSource from_split_folders(const fs::path& dir, const std::vector<std::string>& splits) {
  YoloSource s;
  s.root = dir.string();
  s.layout = "dataset folder";
  for (const std::string& split : splits) {
    s.splits.push_back(split);
    add_split(s.root, split, is_folder(s.root, split + "/images") ? split + "/images" : "", split + "/labels",
              &s.scenes);
  }
  return s;
}

YoloSource locate(const std::string& src) {
  const fs::path p = fs::absolute(src).lexically_normal();
  const fs::path clean = p.has_filename() ? p : p.parent_path();
  std::error_code ec;
  if (!fs::exists(fs::symlink_status(clean, ec))) throw StudyError(src + ": no such file or folder");
  if (!fs::is_directory(clean, ec)) {
    const std::string ext = ascii_lower(clean.extension().string());
    if (ext == ".yaml" || ext == ".yml") return from_data_yaml(clean);
    throw StudyError(src + ": expected a dataset's data.yaml or its folder");
  }
  const std::string root = clean.string();
  for (const char* yaml : {"data.yaml", "data.yml", "dataset.yaml"})
    if (is_file(root, yaml)) return from_data_yaml(clean / yaml);
  if (is_file(root, "obj.names") || is_file(root, "obj.data")) return from_cvat(clean);
  if (is_folder(root, "labels")) return from_folders(clean, "labels", "images");
  std::vector<std::string> splits;
  for (const char* split : {"train", "valid", "val", "test"})
    if (is_folder(root, std::string(split) + "/labels")) splits.push_back(split);
  if (!splits.empty()) return from_split_folders(clean, splits);
  // An archive unzipped into a folder of its own: the dataset is one folder down.
  for (const FolderEntry& e : list_source(root, ""))
    if (e.folder)
      for (const char* marker : {"data.yaml", "data.yml", "obj.names", "labels", "train/labels"})
        if (fs::exists(fs::symlink_status(clean / e.name / marker, ec)))
          throw StudyError(fmt::format(
              "{}: not a YOLO dataset itself, but its folder {} holds {} (the dataset unzipped one folder down): "
              "ipd import yolo {} --out STUDY/<domain>",
              src, e.name, marker, (fs::path(src) / e.name).string()));
  throw StudyError(src +
                   ": not a YOLO dataset layout this import knows; expected a data.yaml, obj.names and "
                   "obj_train_data/ (CVAT YOLO 1.1), labels/ and images/ (a dataset folder, Label Studio), or "
                   "train/labels/ (Roboflow)");
}

}  // namespace

std::string yolo_dataset_hint(const std::string& folder, const std::string& shown) {
  std::error_code ec;
  for (const char* marker : {"data.yaml", "data.yml", "obj.names", "classes.txt", "labels", "train/labels"})
    if (fs::exists(fs::symlink_status(fs::path(folder) / marker, ec)))
      return fmt::format(
          "; it holds {}, as a YOLO dataset or a labelling tool's export does: ipd import yolo {} --out "
          "STUDY/<domain> brings it into a study (docs/import.md)",
          marker, shown);
  return {};
}

bool is_picture_name(const std::string& file_name) {
  static const std::set<std::string> kExtensions = {".png", ".jpg", ".jpeg", ".tif", ".tiff", ".bmp", ".webp"};
  return kExtensions.count(ascii_lower(fs::path(file_name).extension().string())) > 0;
}

bool has_upload_prefix(const std::string& stem) { return stem.size() > 9 && is_hex(stem, 0, 8) && stem[8] == '-'; }

std::string scene_stem(const std::string& source_stem, bool strip_upload_prefix) {
  std::string s = strip_upload_prefix && has_upload_prefix(source_stem) ? source_stem.substr(9) : source_stem;
  // <name>_<ext>.rf.<32 hex>
  const size_t rf = s.rfind(".rf.");
  if (rf == std::string::npos || s.size() != rf + 4 + 32 || !is_hex(s, rf + 4, 32)) return s;
  const size_t underscore = s.rfind('_', rf);
  if (underscore == std::string::npos || underscore == 0) return s;
  if (!is_picture_name("x." + s.substr(underscore + 1, rf - underscore - 1))) return s;
  return s.substr(0, underscore);
}

YoloSource find_yolo_source(const std::string& src, const std::string& chosen) {
  YoloSource s = locate(src);
  // "valid" (Roboflow's folder) and "val" (data.yaml's key) name one split: a Roboflow export read through its
  // data.yaml calls its valid/ folder val.
  std::string split = chosen;
  const auto has = [&](const std::string& x) {
    return std::find(s.splits.begin(), s.splits.end(), x) != s.splits.end();
  };
  if (split == "valid" && !has("valid") && has("val")) split = "val";
  if (split == "val" && !has("val") && has("valid")) split = "valid";
  if (!split.empty()) {
    if (std::find(s.splits.begin(), s.splits.end(), split) == s.splits.end()) {
      std::string have;
      for (const auto& x : s.splits) have += (have.empty() ? "" : ", ") + (x.empty() ? std::string("(none)") : x);
      throw StudyError(fmt::format("{}: no split '{}'; the {} has {}", src, quoted_for_message(split), s.layout, have));
    }
    s.scenes.erase(
        std::remove_if(s.scenes.begin(), s.scenes.end(), [&](const SourceScene& x) { return x.split != split; }),
        s.scenes.end());
  }
  const bool prefixed = !s.scenes.empty() && std::all_of(s.scenes.begin(), s.scenes.end(), [](const SourceScene& x) {
    return has_upload_prefix(x.source_stem);
  });
  int roboflow = 0;
  std::map<std::string, const SourceScene*> by_stem;
  for (SourceScene& x : s.scenes) {
    x.stem = scene_stem(x.source_stem, prefixed);
    const std::string unprefixed = prefixed ? x.source_stem.substr(9) : x.source_stem;
    if (x.stem != unprefixed) ++roboflow;
  }
  if (prefixed) s.renamings.push_back("Label Studio's upload prefix (8 hex digits and '-') left out of every name");
  if (roboflow > 0)
    s.renamings.push_back(fmt::format("{} Roboflow name(s) '<name>_<ext>.rf.<hash>' read as '<name>'", roboflow));
  std::sort(s.scenes.begin(), s.scenes.end(), [](const SourceScene& a, const SourceScene& b) {
    return std::tie(a.stem, a.split) < std::tie(b.stem, b.split);
  });
  auto file_of = [&](const SourceScene& x) { return shown(s.root, x.label.empty() ? x.picture : x.label); };
  for (const SourceScene& x : s.scenes) {
    if (const std::string why = file_name_problem(x.stem, kMaxStemBytes); !why.empty() || x.stem == "classes")
      throw StudyError(fmt::format("{}: scene name '{}' {}", printable_name(file_of(x)), printable_name(x.stem, 60),
                                   why.empty() ? "would write labels/classes.txt, which holds the class names" : why));
    const auto [it, fresh] = by_stem.emplace(x.stem, &x);
    if (!fresh)
      throw StudyError(
          fmt::format("{} and {} would both be scene '{}' of the study; rename one (or import one split with --split)",
                      printable_name(file_of(*it->second)), printable_name(file_of(x)), printable_name(x.stem, 60)));
  }
  return s;
}

}  // namespace ipd
