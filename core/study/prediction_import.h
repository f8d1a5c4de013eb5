// `ipd import predictions`: one model's detections for a domain already in the study, from a YOLOv5/v8 run
// (`runs/detect/exp`, or its `labels/`: `class cx cy w h conf` files) or COCO results (`--gt` names the COCO file
// whose image ids they use). Only <domain>/predictions/<model>/ is written (the ground truth is never touched),
// as copies (never links), all or nothing (written beside and renamed in). Each scene of the domain the run wrote
// no file for gets an empty file: "no detections" (study-format.md), so it is not reported missing.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "core/io/label_io.h"

namespace ipd {

struct PredictionImportOptions {
  std::string source;             // a run folder, its labels/ folder, or a COCO results JSON
  std::string gt;                 // with COCO results: the COCO annotations whose image ids they use
  std::string out_dir;            // the domain directory, e.g. STUDY/real (its labels/ must be there)
  std::string model;              // the prediction set's name: predictions/<model>/
  bool no_conf = false;           // a run written without confidences is read with confidence 1 (said in import.json)
  bool replace = false;           // a prediction set with files is refused unless this is set (then replaced whole)
  bool skip_bad_entries = false;  // COCO results: malformed entries are skipped with a warning

  std::string validate() const;
  void check() const;  // throws std::invalid_argument("prediction import options: " + validate())
};

struct PredictionImportReport {
  std::string kind;    // "YOLO run" or "COCO results"
  std::string folder;  // where the run's label files were found
  int files = 0, detections = 0;
  int no_detection_files = 0;      // scenes of the domain without a file from the run: written empty
  int renamed = 0;                 // files whose tool-mangled name was mapped to the scene's (yolo_source.h)
  bool conf_one = false;           // read with confidence 1 (--no-conf)
  std::vector<LabelError> errors;  // nothing is written while there is one (COCO: unless skipped)
  bool written = false;
  int removed = 0;  // files of the replaced set the import did not write again
  // COCO results: run-length masks of several pieces cut to the piece that encloses the most, and the pixels
  // of the pieces left out.
  int rle_masks_cut = 0;
  long long rle_pixels_left_out = 0;
};

PredictionImportReport import_predictions(const PredictionImportOptions& options);

// The scenes of the domain at `out_dir`: the stems of its labels/*.txt (classes.txt aside). Throws StudyError
// when it has no labels/ folder (the ground truth is imported first).
std::vector<std::string> domain_scenes(const std::string& out_dir);

// Writes the set out_dir/predictions/<model>/ whole: `files` (scene -> text) and an empty file for every scene
// of `scenes` not among them, then `provenance` as import.json; beside it and renamed in. Returns the number of
// empty files written. A set that holds files is refused unless `replace` (its old .txt files then go).
int write_prediction_set(const std::string& out_dir, const std::string& model,
                         const std::map<std::string, std::string>& files, const std::vector<std::string>& scenes,
                         const std::string& provenance, bool replace, int* removed);

}  // namespace ipd
