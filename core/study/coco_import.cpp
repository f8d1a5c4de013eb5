#include "core/study/coco_import.h"

#include <fmt/format.h>
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <set>
#include <stdexcept>

#include "core/study/coco_segmentation.h"
#include "core/study/file_sets.h"
#include "core/study/prediction_import.h"
#include "core/study/study.h"
#include "core/util/atomic_file.h"
#include "core/util/contained_file.h"
#include "core/util/json_input.h"
#include "core/util/json_output.h"
#include "core/util/number_text.h"

namespace fs = std::filesystem;
using nlohmann::json;

namespace ipd {

namespace {

// COCO nests at most 5 deep (segmentation polygons); 64 leaves room and stops a 66k-deep file.
json parse_json_file(const std::string& path, const char* expected) {
  return parse_json_input(read_file(path), path, expected, 64);
}

struct Image {
  size_t index = 0;  // position in the "images" array, for messages
  std::string file, stem;
  double w = 0, h = 0;
  std::vector<Box> gt, predictions;
};

// A COCO [x, y, w, h] box in pixels to a normalised YOLO box; empty string when fine, else what's wrong.
std::string to_box(const json& bbox, const Image& img, Box* out) {
  if (!bbox.is_array() || bbox.size() != 4 ||
      !std::all_of(bbox.begin(), bbox.end(), [](const json& v) { return v.is_number(); }))
    return fmt::format("expected bbox [x, y, w, h] of numbers, found {}", describe_json(bbox));
  const double x = bbox[0], y = bbox[1], w = bbox[2], h = bbox[3];
  if (!std::isfinite(x) || !std::isfinite(y) || !std::isfinite(w) || !std::isfinite(h) || w <= 0 || h <= 0)
    return fmt::format("expected bbox with w > 0 and h > 0, found {}", describe_json(bbox));
  const double tol = 1.0;  // a pixel of rounding beyond the border is fine
  if (x < -tol || y < -tol || x + w > img.w + tol || y + h > img.h + tol)
    return fmt::format("expected bbox inside the {}x{} image, found {}", img.w, img.h, describe_json(bbox));
  out->cx = std::clamp((x + w / 2) / img.w, 0.0, 1.0);
  out->cy = std::clamp((y + h / 2) / img.h, 0.0, 1.0);
  out->w = std::min(w / img.w, 1.0);
  out->h = std::min(h / img.h, 1.0);
  // The label file could not hold it (it would read "0.000000", which ipd refuses): said here, by its entry.
  if (out->w < kMinBoxSide || out->h < kMinBoxSide)
    return fmt::format("expected bbox of at least a millionth of the {}x{} image a side, found {}", img.w, img.h,
                       describe_json(bbox));
  return {};
}

// Images whose labels would land in one file: the same stem in two folders (cam1/0001.png, cam2/0001.png) or
// with two extensions, a stem of "classes" (labels/classes.txt holds the class names) or none at all. Each
// would silently lose its boxes to another, so the import refuses them all, by name.
std::vector<std::string> name_collisions(const std::map<long, Image>& images, const std::string& file) {
  std::vector<std::string> out;
  std::map<std::string, const Image*> by_stem;
  auto quoted = [](const std::string& s) { return describe_json(nlohmann::json(s)); };
  for (const auto& [id, img] : images) {
    if (img.stem.empty() || img.stem == "." || img.stem == "..") {
      out.push_back(
          fmt::format("{}: images[{}] {}: no file name to write its labels under", file, img.index, quoted(img.file)));
    } else if (img.stem == "classes") {
      out.push_back(
          fmt::format("{}: images[{}] {} would write labels/classes.txt, which holds the class names; "
                      "rename the image",
                      file, img.index, quoted(img.file)));
    } else if (const auto [it, fresh] = by_stem.emplace(img.stem, &img); !fresh) {
      const Image& other = *it->second;
      out.push_back(fmt::format(
          "{}: images[{}] {} and images[{}] {} would both write labels/{}.txt; give the images "
          "distinct names (or import each folder into a domain of its own)",
          file, other.index, quoted(other.file), img.index, quoted(img.file), quoted_for_message(img.stem)));
    }
  }
  return out;
}

}  // namespace

namespace {
CocoImportReport import_coco_checked(const CocoImportOptions& o);
}

std::string CocoImportOptions::validate() const {
  if (annotations.empty()) return "annotations must name the COCO instances file, got an empty path";
  if (out_dir.empty()) return "out_dir must name the domain directory to fill, got an empty path";
  if (!results.empty() && model.empty()) return "model must name the prediction set when results are given, got \"\"";
  if (predictions_only && results.empty()) return "predictions_only needs the results file, got an empty path";
  return {};
}

void CocoImportOptions::check() const {
  if (const std::string problem = validate(); !problem.empty())
    throw std::invalid_argument("COCO import options: " + problem);
}

CocoImportReport import_coco(const CocoImportOptions& o) {
  o.check();
  try {
    return import_coco_checked(o);
  } catch (const json::exception& e) {  // a case the checks below missed still names the file
    std::string why = e.what();
    if (why.size() > 120) why = why.substr(0, 117) + "...";
    throw StudyError(fmt::format("{}: {}", o.annotations, why));
  }
}

namespace {

// The "categories" array: each category's YOLO class is its own id, named by its "name" (or its id), so a
// category has the same class number in every domain whatever else each file lists (numbered by rank, "rock"
// id 2 was class 1 beside {1: shadow} and class 0 alone, and `rock_class` then picked different things).
void read_categories(const json& gt, const std::string& file, std::map<long, int>* class_of,
                     std::vector<std::string>* classes) {
  std::map<long, size_t> category_at;  // id -> its index in "categories"
  for (const auto& c : gt["categories"]) {
    const size_t at = category_at.size();
    if (!c.is_object() || !c.contains("id") || !c["id"].is_number_integer())
      throw StudyError(fmt::format("{}: every category needs an integer \"id\", found {}", file, describe_json(c)));
    const long id = c["id"].get<long>();
    if (c.contains("name") && !c["name"].is_string())
      throw StudyError(
          fmt::format("{}: category {}: \"name\" must be a string, found {}", file, id, describe_json(c["name"])));
    if (id < 0 || id > kMaxCocoCategoryId)
      throw StudyError(
          fmt::format("{}: categories[{}]: category id {} is not a class number from 0 to {} (the "
                      "category id becomes the YOLO class, one line of labels/classes.txt each)",
                      file, at, id, kMaxCocoCategoryId));
    // An id given twice would make one class two categories, and which name it has would be a guess.
    const auto [first, fresh] = category_at.emplace(id, at);
    if (!fresh)
      throw StudyError(
          fmt::format("{}: categories[{}]: category id {} appears twice (also categories[{}]); every "
                      "category needs its own id, since YOLO class numbers are the ids",
                      file, at, id, first->second));
    (*class_of)[id] = static_cast<int>(id);
    if (classes->size() <= static_cast<size_t>(id)) classes->resize(id + 1);
    (*classes)[id] = c.value("name", std::to_string(id));
  }
}

// The "images" array by id; a malformed or repeated entry is an error of the report, not of the import.
std::map<long, Image> read_images(const json& gt, const std::string& file, std::vector<LabelError>* errors) {
  std::map<long, Image> images;
  size_t k = 0;
  for (const auto& im : gt["images"]) {
    const std::string where = fmt::format("images[{}]", k++);
    if (!im.is_object() || !im.contains("id") || !im["id"].is_number_integer() || !im.contains("file_name") ||
        !im["file_name"].is_string() || !im.contains("width") || !im.contains("height") || !im["width"].is_number() ||
        !im["height"].is_number() || !(im["width"].get<double>() > 0) || !(im["height"].get<double>() > 0)) {
      errors->push_back(
          {file, 0, where + ": expected {id, file_name, width > 0, height > 0}, found " + describe_json(im)});
      continue;
    }
    Image img;
    img.index = k - 1;
    img.file = im["file_name"].get<std::string>();
    // Below --images only: "../x.png" or "/etc/x.png" would take a picture from anywhere into the study.
    const fs::path name(img.file);
    if (name.is_absolute() || std::any_of(name.begin(), name.end(), [](const fs::path& p) { return p == ".."; })) {
      errors->push_back({file, 0,
                         fmt::format("{}: file_name '{}' leaves the pictures folder; expected a path below --images",
                                     where, quoted_for_message(img.file))});
      continue;
    }
    img.stem = fs::path(img.file).stem().string();
    img.w = im["width"];
    img.h = im["height"];
    if (!images.emplace(im["id"].get<long>(), img).second)
      errors->push_back({file, 0, fmt::format("{}: image id {} appears twice", where, im["id"].get<long>())});
  }
  return images;
}

// An entry as its messages name it: its place in the file's array, and its id when it has one
// ("annotations[3] (id 17)"), the two ways a user finds it again.
std::string entry_name(const std::string& array, size_t k, const json& entry) {
  std::string name = fmt::format("{}[{}]", array, k);
  if (entry.is_object())
    if (const auto id = entry.find("id"); id != entry.end() && id->is_number_integer())
      name += fmt::format(" (id {})", id->get<long long>());
  return name;
}

// Where imported boxes go: each image's GT or predictions, counted in the report.
struct BoxSink {
  std::map<long, Image>* images;
  const std::map<long, int>* class_of;
  CocoImportReport* report;

  // One annotation (GT) or detection (prediction, with a score) of `file`; a bad one is a report error.
  void add(const json& a, const std::string& file, const std::string& where, bool prediction) const {
    auto& errors = report->errors;
    if (!a.is_object() || !a.contains("image_id") || !a["image_id"].is_number_integer() || !a.contains("category_id") ||
        !a["category_id"].is_number_integer()) {
      errors.push_back({file, 0, where + ": expected image_id and category_id integers, found " + describe_json(a)});
      return;
    }
    const auto im = images->find(a["image_id"].get<long>());
    if (im == images->end()) {
      errors.push_back(
          {file, 0, fmt::format("{}: image_id {} is not among the images", where, a["image_id"].get<long>())});
      return;
    }
    const auto cls = class_of->find(a["category_id"].get<long>());
    if (cls == class_of->end()) {
      errors.push_back(
          {file, 0,
           fmt::format("{}: category_id {} is not among the categories", where, a["category_id"].get<long>())});
      return;
    }
    Box b;
    b.cls = cls->second;
    const std::string why = to_box(a.contains("bbox") ? a["bbox"] : json(), im->second, &b);
    if (!why.empty()) {
      errors.push_back({file, 0, where + ": " + why});
      return;
    }
    CocoSegmentation shape;
    if (a.contains("segmentation"))
      if (const std::string bad = read_coco_segmentation(a["segmentation"], im->second.w, im->second.h, &shape);
          !bad.empty()) {
        errors.push_back({file, 0, where + ": " + bad});
        return;
      }
    if (!shape.polygons.empty()) {
      // Written as its YOLO-seg line (several parts, or a mask's pieces, joined into one contour); read back, the
      // box is its bounds.
      const std::vector<double> merged = merge_polygon_parts(shape.polygons);
      std::vector<Eigen::Vector2d> points;
      for (size_t k = 0; k + 1 < merged.size(); k += 2) points.emplace_back(merged[k], merged[k + 1]);
      // The box keeps the entry's bbox (set_outline would make it the outline's bounds, as reading the line back
      // does): only the outline is taken.
      Box outlined = b;
      if (std::string why = set_outline(std::move(points), &outlined); !why.empty()) {
        errors.push_back({file, 0, where + ": segmentation: " + why});
        return;
      }
      b.outline = std::move(outlined.outline);
      ++(shape.rle ? report->rle_masks : report->polygons);
      report->rle_masks_cut += shape.pieces_left_out > 0 ? 1 : 0;
      report->rle_pixels_left_out += shape.pixels_left_out;
    }
    if (!prediction) {
      im->second.gt.push_back(b);
      ++report->boxes;
      return;
    }
    if (!a.contains("score") || !a["score"].is_number() ||
        !(a["score"].get<double>() >= 0 && a["score"].get<double>() <= 1)) {
      errors.push_back({file, 0,
                        where + ": expected a score in [0, 1], found " +
                            (a.contains("score") ? describe_json(a["score"]) : "none")});
      return;
    }
    b.conf = a["score"];
    im->second.predictions.push_back(b);
    ++report->detections;
  }
};

// What the folder being replaced holds besides the new set, moved into the new folder as it is (other
// prediction sets, a picture the import names but could not find, files of other kinds), and the old set's
// files the import did not write again, counted (they go with the old folder). The import replaces its own
// set, nothing else; a folder of the set that is a link is replaced, never listed or written through.
void carry_over(const CocoImportOptions& o, const StagedFolder& staged, const std::set<std::string>& written_labels,
                const std::set<std::string>& pictures, const std::set<std::string>& written_pictures,
                CocoImportReport* r) {
  const auto entries = [&](const std::string& rel) {
    try {
      return entries_beneath(staged.parent(), rel.empty() ? staged.target_name() : staged.target_inside(rel));
    } catch (const IoError&) {
      return std::vector<FolderEntry>{};  // a link (or unreadable): replaced whole
    }
  };
  const auto carry = [&](const std::string& rel) {
    rename_beneath(staged.parent(), staged.target_inside(rel), staged.inside(rel));
  };
  const std::string own_predictions = o.results.empty() ? std::string() : "predictions/" + o.model;
  for (const FolderEntry& e : entries(""))
    if (e.name != "labels" && e.name != "images" && e.name != "predictions") carry(e.name);
  for (const FolderEntry& e : entries("predictions")) {
    if ("predictions/" + e.name == own_predictions) continue;
    r->other_prediction_sets.push_back(e.name);
    carry("predictions/" + e.name);
  }
  struct Set {
    std::string folder;
    const std::set<std::string>* keep;
    const std::set<std::string>* written;
    std::string suffix;
  };
  std::vector<Set> sets = {{"labels", &written_labels, &written_labels, ".txt"},
                           {"images", &pictures, &written_pictures, ""}};
  if (!own_predictions.empty()) sets.push_back({own_predictions, &written_labels, &written_labels, ".txt"});
  for (const Set& set : sets)
    for (const FolderEntry& e : entries(set.folder)) {
      if (set.written->count(e.name)) continue;  // the new file replaces it
      const bool has_suffix = e.name.size() >= set.suffix.size() &&
                              e.name.compare(e.name.size() - set.suffix.size(), set.suffix.size(), set.suffix) == 0;
      if (!e.folder && !set.keep->count(e.name) && has_suffix)
        ++r->removed;  // the old set's: it goes with the old folder
      else
        carry(set.folder + "/" + e.name);
    }
}

// The study's label files, class names and pictures (hard links to the pictures the user named, or copies),
// written into a new folder beside the domain folder and renamed in (StagedFolder): nothing is written into
// the folder being replaced, so none of its links is written through. Scores and boxes are written in full
// (LabelDigits::kExact): they came as doubles and the thresholds and AP of every command must see the same
// numbers pycocotools sees.
void write_study(const CocoImportOptions& o, const std::map<long, Image>& images, CocoImportReport* r) {
  StagedFolder staged(o.out_dir);
  const std::string& root = staged.parent();
  std::set<std::string> labels = {"classes.txt"}, pictures, written_pictures;
  for (const auto& [id, img] : images) {
    labels.insert(img.stem + ".txt");
    write_new_file_beneath(root, staged.inside("labels/" + img.stem + ".txt"),
                           labels_text(img.gt, LabelKind::kGroundTruth, LabelDigits::kExact));
    if (!o.results.empty())
      write_new_file_beneath(root, staged.inside("predictions/" + o.model + "/" + img.stem + ".txt"),
                             labels_text(img.predictions, LabelKind::kPrediction, LabelDigits::kExact));
    if (o.images_dir.empty()) continue;
    const std::string name = fs::path(img.file).filename().string();
    pictures.insert(name);
    const fs::path src = fs::absolute(fs::path(o.images_dir) / img.file);
    std::error_code ec;
    if (!fs::exists(src, ec)) continue;
    // A hard link (or a copy across file systems), never a symbolic link: a study's symbolic links are not
    // followed when it is read, since a study received from someone else could point anywhere.
    try {
      link_file_beneath(root, staged.inside("images/" + name), src.string());
      written_pictures.insert(name);
      ++r->linked_images;
    } catch (const IoError&) {
    }
  }
  std::string names;
  for (const auto& c : r->classes) names += c + "\n";
  write_new_file_beneath(root, staged.inside("labels/classes.txt"), names);
  if (staged.target_exists()) carry_over(o, staged, labels, pictures, written_pictures, r);
  std::sort(r->other_prediction_sets.begin(), r->other_prediction_sets.end());
  staged.commit();
  r->written = true;
}

// A model's results joining a domain that is there: only predictions/<model>/ is written, a file per scene.
void write_prediction_set_only(const CocoImportOptions& o, const std::map<long, Image>& images, CocoImportReport* r) {
  const std::vector<std::string> scenes = domain_scenes(o.out_dir);
  const std::set<std::string> known(scenes.begin(), scenes.end());
  std::map<std::string, std::string> files;
  std::vector<std::string> unknown;
  for (const auto& [id, img] : images) {
    if (!known.count(img.stem)) {
      unknown.push_back(img.file);
      continue;
    }
    files[img.stem] = labels_text(img.predictions, LabelKind::kPrediction, LabelDigits::kExact);
  }
  if (!unknown.empty())
    throw StudyError(
        fmt::format("{}: {} image(s) are no scene of {} (e.g. '{}'); expected the COCO file the "
                    "domain was imported from, so nothing is written",
                    o.annotations, unknown.size(), o.out_dir, quoted_for_message(unknown.front())));
  nlohmann::ordered_json j;
  j["imported_with"] = "ipd import predictions";
  j["source"] = fs::absolute(o.results).lexically_normal().string();
  j["kind"] = "COCO results";
  j["image_ids_from"] = fs::absolute(o.annotations).lexically_normal().string();
  j["confidence"] = "the results' scores";
  std::vector<std::string> empty;
  for (const std::string& s : scenes)
    if (!files.count(s)) empty.push_back(s);
  j["no_detections"] = empty;
  r->no_detection_files =
      write_prediction_set(o.out_dir, o.model, files, scenes, dump_json_output(j, 1) + "\n", o.replace, &r->removed);
  r->written = true;
}

CocoImportReport import_coco_checked(const CocoImportOptions& o) {
  CocoImportReport r;
  if (!o.predictions_only) check_domain_folder(o.out_dir, o.replace, "ipd import coco");
  const json gt = parse_json_file(o.annotations, "a COCO object {\"images\": [...], \"annotations\": [...], ...}");
  for (const char* key : {"images", "annotations", "categories"})
    if (!gt.is_object() || !gt.contains(key) || !gt[key].is_array())
      throw StudyError(fmt::format("{}: expected a COCO object with an \"{}\" array", o.annotations, key));
  std::map<long, int> class_of;  // category id -> YOLO class
  read_categories(gt, o.annotations, &class_of, &r.classes);
  r.categories = static_cast<int>(class_of.size());
  if (const std::string conflict = o.predictions_only ? std::string() : class_name_conflict(o.out_dir, r.classes);
      !conflict.empty())
    throw StudyError(
        fmt::format("{}: {}; a class number must be the same category in every domain of a study "
                    "(rock_class picks one number for all), so nothing is written",
                    o.annotations, conflict));
  std::map<long, Image> images = read_images(gt, o.annotations, &r.errors);
  const BoxSink sink{&images, &class_of, &r};
  size_t k = 0;
  for (const auto& a : gt["annotations"]) sink.add(a, o.annotations, entry_name("annotations", k++, a), false);
  if (!o.results.empty()) {
    const json res = parse_json_file(o.results, "a JSON list of detections [{image_id, category_id, bbox, score}]");
    if (!res.is_array())
      throw StudyError(o.results + ": expected a JSON list of detections [{image_id, category_id, bbox, score}]");
    k = 0;
    for (const auto& a : res) sink.add(a, o.results, entry_name("", k++, a), true);
  }
  r.images = static_cast<int>(images.size());
  r.collisions = name_collisions(images, o.annotations);
  if (!r.collisions.empty() || (!r.errors.empty() && !o.skip_bad_entries)) return r;
  if (o.predictions_only)
    write_prediction_set_only(o, images, &r);
  else
    write_study(o, images, &r);
  return r;
}

}  // namespace

}  // namespace ipd
