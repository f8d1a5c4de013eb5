// `ipd import coco ANNOTATIONS.json [--results RESULTS.json] --images DIR --out STUDY/<domain>`,
// `ipd import yolo SRC --out STUDY/<domain> [--split NAME]` and
// `ipd import predictions SRC --out STUDY/<domain> --model M [--gt COCO.json] [--no-conf]`.
#include <fmt/format.h>

#include "app/cli/cli_common.h"
#include "app/cli/commands.h"
#include "core/study/coco_import.h"
#include "core/study/prediction_import.h"
#include "core/study/yolo_import.h"

namespace ipd::cli {

namespace {

Runner add_yolo(CLI::App* imp) {
  auto o = std::make_shared<YoloImportOptions>();
  CLI::App* cmd = imp->add_subcommand(
      "yolo", "A YOLO dataset (data.yaml, images/ + labels/, CVAT YOLO 1.1, Label Studio, Roboflow) as one domain");
  cmd->add_option("SRC", o->source, "data.yaml, or the dataset's folder")->required();
  cmd->add_option("--out", o->out_dir, "The domain directory to fill, e.g. STUDY/real")->required();
  cmd->add_option("--split", o->split, "Import this split only (train, val, test, ...); default: every split");
  cmd->add_flag("--replace", o->replace, "Replace the labels and pictures of a domain folder that already holds files");
  cmd->add_option("--names", o->names, "Class names of a dataset without a names file, class 0 first: rock,shadow")
      ->delimiter(',');
  cmd->add_flag("--skip-bad-lines", o->skip_bad_lines,
                "Warn about malformed label lines and write them as comments (stops when they are most lines)");
  return [o]() -> int {
    const YoloImportReport r = import_yolo(*o);
    for (const auto& e : r.errors)
      fmt::print(stderr, "{}{}\n", r.written && e.malformed_lines() > 0 ? "warning: " : "", e.to_string());
    if (!r.most_skipped.empty()) {
      fmt::print(stderr, "error: {}\n", r.most_skipped);
      return kBadInput;
    }
    if (!r.written) {
      fmt::print(stderr, "error: {} problem{} in the source's label files; nothing written{}\n", r.errors.size(),
                 r.errors.size() == 1 ? "" : "s",
                 o->skip_bad_lines ? "" : " (--skip-bad-lines writes malformed lines as comments)");
      return kBadInput;
    }
    if (r.skipped_lines > 0)
      fmt::print(stderr, "warning: {} malformed line(s) written as comments (--skip-bad-lines)\n", r.skipped_lines);
    for (const auto& m : r.kept_prediction_sets)
      fmt::print(stderr,
                 "warning: {}/predictions/{}/ is kept as it was; its predictions are of the labels before "
                 "this import\n",
                 o->out_dir, m);
    const YoloSource& s = r.source;
    for (const auto& n : s.renamings) fmt::print("{}\n", n);
    std::string splits;
    for (const auto& x : s.splits) splits += (splits.empty() ? "" : ", ") + (x.empty() ? std::string("-") : x);
    fmt::print(
        "{} ({}{}): {} scenes ({} without a label file: no objects), {} GT boxes, {} classes{}, {} pictures "
        "linked -> {}\n",
        s.layout, o->split.empty() ? "splits " : "split ", o->split.empty() ? splits : o->split, r.scenes,
        r.without_label_file, r.boxes, s.class_names.size(),
        s.names_file.empty() ? " (no names file)" : " from " + s.names_file, r.linked_images, o->out_dir);
    return kOk;
  };
}

Runner add_predictions(CLI::App* imp) {
  auto o = std::make_shared<PredictionImportOptions>();
  CLI::App* cmd = imp->add_subcommand(
      "predictions", "One model's detections for a domain already imported: a YOLOv5/v8 run or COCO results");
  cmd->add_option("SRC", o->source, "A run folder (runs/detect/exp), its labels/ folder, or a COCO results .json")
      ->required();
  cmd->add_option("--out", o->out_dir, "The domain directory, e.g. STUDY/real (its labels/ must be there)")->required();
  cmd->add_option("--model", o->model, "The prediction set's name: predictions/<model>/")->required();
  cmd->add_option("--gt", o->gt, "With COCO results: the COCO annotations file whose image ids they use");
  cmd->add_flag("--no-conf", o->no_conf, "Read a run written without confidences with confidence 1");
  cmd->add_flag("--skip-bad-lines", o->skip_bad_entries, "COCO results: warn about malformed entries and skip them");
  cmd->add_flag("--replace", o->replace, "Replace this model's prediction set of the domain");
  return [o]() -> int {
    const PredictionImportReport r = import_predictions(*o);
    for (const auto& e : r.errors) fmt::print(stderr, "{}{}\n", r.written ? "warning: " : "", e.to_string());
    if (!r.written) {
      fmt::print(stderr, "error: {} problem{} in the predictions; nothing written\n", r.errors.size(),
                 r.errors.size() == 1 ? "" : "s");
      return kBadInput;
    }
    if (r.rle_masks_cut > 0)
      fmt::print(stderr,
                 "note: {} run-length mask{} of several pieces kept the piece that encloses the most; {} pixels of "
                 "the others left out (an outline is one ring)\n",
                 r.rle_masks_cut, r.rle_masks_cut == 1 ? "" : "s", r.rle_pixels_left_out);
    if (r.conf_one)
      fmt::print(stderr, "warning: {}: no confidences in the run; every box is read with confidence 1 (--no-conf)\n",
                 r.folder);
    fmt::print(
        "{} {}: {} files, {} detections{}; {} scenes without a file written empty (no detections){} -> "
        "{}/predictions/{}\n",
        r.kind, r.folder, r.files, r.detections,
        r.renamed ? fmt::format(" ({} names mapped back to the scene's)", r.renamed) : "", r.no_detection_files,
        o->replace ? fmt::format(" ({} old files removed)", r.removed) : "", o->out_dir, o->model);
    return kOk;
  };
}

}  // namespace

Runner add_import_command(CLI::App& app) {
  auto o = std::make_shared<CocoImportOptions>();
  CLI::App* imp = app.add_subcommand("import", "Bring labels from other formats into the study layout");
  imp->require_subcommand(1);
  CLI::App* cmd = imp->add_subcommand("coco", "COCO ground truth (and detection results) to YOLO txt");
  cmd->add_option("ANNOTATIONS", o->annotations, "COCO instances JSON (images, annotations, categories)")->required();
  cmd->add_option("--results", o->results, "COCO detection results JSON [{image_id, category_id, bbox, score}]");
  cmd->add_option("--images", o->images_dir, "Directory the file_name entries resolve in (linked into images/)")
      ->required();
  cmd->add_option("--out", o->out_dir, "The domain directory to fill, e.g. STUDY/real")->required();
  cmd->add_option("--model", o->model, "Prediction set name for --results (default coco-results)");
  cmd->add_flag("--skip-bad-lines", o->skip_bad_entries, "Warn about malformed entries and skip them");
  cmd->add_flag("--replace", o->replace,
                "Replace the labels, pictures and this prediction set of a domain folder that already holds files");
  const Runner yolo = add_yolo(imp), predictions = add_predictions(imp);
  const std::vector<std::pair<CLI::App*, Runner>> others = {{imp->get_subcommand("yolo"), yolo},
                                                            {imp->get_subcommand("predictions"), predictions}};
  return [o, cmd, others]() -> int {
    for (const auto& [sub, run] : others)
      if (sub && sub->parsed()) return run();
    const CocoImportReport r = import_coco(*o);
    if (!r.collisions.empty()) {
      for (const auto& c : r.collisions) fmt::print(stderr, "{}\n", c);
      fmt::print(stderr, "error: {} image name collision{}; nothing written\n", r.collisions.size(),
                 r.collisions.size() == 1 ? "" : "s");
      return kBadInput;
    }
    // Entry problems name the JSON file and the entry, not a line (so report_label_errors, which takes a
    // line-less error for an unreadable file, would call them fatal even when they were skipped and written).
    const char* entries = r.errors.size() == 1 ? "y" : "ies";
    for (const auto& e : r.errors) fmt::print(stderr, "{}{}\n", r.written ? "warning: " : "", e.to_string());
    if (!r.written) {
      fmt::print(stderr, "error: {} malformed entr{}; nothing written (--skip-bad-lines skips them)\n", r.errors.size(),
                 entries);
      return kBadInput;
    }
    if (!r.errors.empty())
      fmt::print(stderr, "warning: {} malformed entr{} skipped (--skip-bad-lines)\n", r.errors.size(), entries);
    for (const auto& m : r.other_prediction_sets)
      fmt::print(stderr,
                 "warning: {}/predictions/{}/ is kept as it was; its predictions are of the labels before "
                 "this import\n",
                 o->out_dir, m);
    if (r.polygons + r.rle_masks > 0)
      fmt::print(stderr,
                 "note: {} polygon segmentations and {} run-length masks written as YOLO-seg outlines (a mask "
                 "traced along its pixels' edges at the image's resolution, holes filled)\n",
                 r.polygons, r.rle_masks);
    if (r.rle_masks_cut > 0)
      fmt::print(stderr,
                 "note: {} run-length mask{} of several pieces kept the piece that encloses the most; {} pixels of "
                 "the others left out (an outline is one ring)\n",
                 r.rle_masks_cut, r.rle_masks_cut == 1 ? "" : "s", r.rle_pixels_left_out);
    fmt::print("{} images, {} GT boxes, {} detections, {} classes, {} pictures linked -> {}{}\n", r.images, r.boxes,
               r.detections, r.categories, r.linked_images, o->out_dir,
               o->replace ? fmt::format(" ({} old files removed)", r.removed) : "");
    return kOk;
  };
}

}  // namespace ipd::cli
