#include "core/study/coco_import.h"

#include <fmt/format.h>
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "core/study/study.h"
#include "core/util/atomic_file.h"
#include "core/util/json_input.h"
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

// The "categories" array: YOLO class k is the k-th category by id, named by its "name" (or its id).
void read_categories(const json& gt, const std::string& file, std::map<long, int>* class_of,
                     std::vector<std::string>* classes) {
  std::vector<std::pair<long, std::string>> cats;
  std::map<long, size_t> category_at;  // id -> its index in "categories"
  for (const auto& c : gt["categories"]) {
    if (!c.is_object() || !c.contains("id") || !c["id"].is_number_integer())
      throw StudyError(fmt::format("{}: every category needs an integer \"id\", found {}", file, describe_json(c)));
    if (c.contains("name") && !c["name"].is_string())
      throw StudyError(fmt::format("{}: category {}: \"name\" must be a string, found {}", file, c["id"].get<long>(),
                                   describe_json(c["name"])));
    cats.emplace_back(c["id"].get<long>(), c.value("name", std::to_string(c["id"].get<long>())));
    // YOLO class k is the k-th category by id: an id given twice would shift every class after it (so
    // `rock_class: 0` would select another category), and which name it has would be a guess.
    const auto [first, fresh] = category_at.emplace(cats.back().first, cats.size() - 1);
    if (!fresh)
      throw StudyError(
          fmt::format("{}: categories[{}]: category id {} appears twice (also categories[{}]); every "
                      "category needs its own id, since YOLO class numbers follow the ids",
                      file, cats.size() - 1, cats.back().first, first->second));
  }
  std::sort(cats.begin(), cats.end());
  for (size_t k = 0; k < cats.size(); ++k) {
    (*class_of)[cats[k].first] = static_cast<int>(k);
    classes->push_back(cats[k].second);
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

// The study's label files, class names and pictures (hard links to the pictures the user named, or copies).
void write_study(const CocoImportOptions& o, const std::map<long, Image>& images, CocoImportReport* r) {
  const fs::path out(o.out_dir);
  for (const auto& [id, img] : images) {
    write_labels((out / "labels" / (img.stem + ".txt")).string(), img.gt, LabelKind::kGroundTruth);
    if (!o.results.empty())
      write_labels((out / "predictions" / o.model / (img.stem + ".txt")).string(), img.predictions,
                   LabelKind::kPrediction);
    const fs::path src = fs::absolute(fs::path(o.images_dir) / img.file);
    std::error_code ec;
    if (!o.images_dir.empty() && fs::exists(src, ec)) {
      const fs::path dst = out / "images" / fs::path(img.file).filename();
      fs::create_directories(dst.parent_path(), ec);
      fs::remove(dst, ec);
      // A hard link (or a copy across file systems), never a symbolic link: a study's symbolic links are not
      // followed when it is read, since a study received from someone else could point anywhere.
      fs::create_hard_link(src, dst, ec);
      if (ec) fs::copy_file(src, dst, ec);
      if (!ec) ++r->linked_images;
    }
  }
  std::string names;
  for (const auto& c : r->classes) names += c + "\n";
  write_file_atomically((out / "labels" / "classes.txt").string(), names);
  r->written = true;
}

CocoImportReport import_coco_checked(const CocoImportOptions& o) {
  CocoImportReport r;
  const json gt = parse_json_file(o.annotations, "a COCO object {\"images\": [...], \"annotations\": [...], ...}");
  for (const char* key : {"images", "annotations", "categories"})
    if (!gt.is_object() || !gt.contains(key) || !gt[key].is_array())
      throw StudyError(fmt::format("{}: expected a COCO object with an \"{}\" array", o.annotations, key));
  std::map<long, int> class_of;  // category id -> YOLO class
  read_categories(gt, o.annotations, &class_of, &r.classes);
  std::map<long, Image> images = read_images(gt, o.annotations, &r.errors);
  const BoxSink sink{&images, &class_of, &r};
  size_t k = 0;
  for (const auto& a : gt["annotations"]) sink.add(a, o.annotations, fmt::format("annotations[{}]", k++), false);
  if (!o.results.empty()) {
    const json res = parse_json_file(o.results, "a JSON list of detections [{image_id, category_id, bbox, score}]");
    if (!res.is_array())
      throw StudyError(o.results + ": expected a JSON list of detections [{image_id, category_id, bbox, score}]");
    k = 0;
    for (const auto& a : res) sink.add(a, o.results, fmt::format("[{}]", k++), true);
  }
  r.images = static_cast<int>(images.size());
  r.collisions = name_collisions(images, o.annotations);
  if (!r.collisions.empty() || (!r.errors.empty() && !o.skip_bad_entries)) return r;
  write_study(o, images, &r);
  return r;
}

}  // namespace

}  // namespace ipd
