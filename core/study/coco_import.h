// Turning COCO ground truth (instances JSON) and detection results (a JSON list) into the study layout:
// <domain>/labels/<stem>.txt, <domain>/images/<file> (links), <domain>/predictions/<model>/<stem>.txt.
#pragma once

#include <string>
#include <vector>

#include "core/io/label_io.h"

namespace ipd {

// The largest category id the import takes: the id is the YOLO class, and labels/classes.txt has a line per class.
constexpr long kMaxCocoCategoryId = 9999;

struct CocoImportOptions {
  std::string annotations;  // COCO GT: images, annotations, categories
  std::string results;      // optional: [{image_id, category_id, bbox, score}, ...]
  std::string images_dir;   // where file_name resolves; linked into <out>/images (empty: no pictures)
  std::string out_dir;      // the domain directory, e.g. STUDY/real
  std::string model = "coco-results";
  bool skip_bad_entries = false;
  // A domain folder that already holds files is refused (nothing written) unless this is set; then its labels,
  // pictures and the `model` prediction set are replaced whole: files of the old set the import does not
  // write are removed, so two imports never mix.
  bool replace = false;
  // Only the prediction set: `results` become <out_dir>/predictions/<model>/ of a domain already there (its
  // ground truth is not touched; `annotations` only says which picture each image id is). Every scene of the
  // domain the results have no image for gets an empty file (no detections).
  bool predictions_only = false;

  // Empty when usable; otherwise the field that is wrong and the accepted range, in one sentence.
  std::string validate() const;
  // Throws std::invalid_argument("COCO import options: " + validate()) when not usable.
  void check() const;
};

struct CocoImportReport {
  int images = 0, boxes = 0, detections = 0, linked_images = 0;
  int categories = 0;
  // Annotations and detections with a segmentation: polygons and run-length masks, written as YOLO-seg outlines.
  int polygons = 0, rle_masks = 0;
  // Run-length masks of several pieces keep the piece whose contour encloses the most: the masks that left
  // pieces out, and those pieces' pixels.
  int rle_masks_cut = 0;
  long long rle_pixels_left_out = 0;
  std::vector<std::string> classes;  // classes[k]: the name of category id k, the YOLO class k ("" for no category)
  std::vector<LabelError> errors;    // all of them; nothing is written when any is fatal
  // Images whose labels would overwrite each other's or the class names (same stem in two folders, an image
  // named classes.png): never skipped, nothing is written while there is one.
  std::vector<std::string> collisions;
  bool written = false;
  int no_detection_files = 0;                      // predictions_only: scenes without an image in the results
  int removed = 0;                                 // files of the replaced set the import did not write again
  std::vector<std::string> other_prediction_sets;  // predictions/<model>/ folders a replace left as they were
};

// Throws IoError / StudyError for unreadable or structurally wrong files, for a domain folder that already
// holds files (without `replace`) and for a class number a sibling domain's labels/classes.txt gives another
// category name (naming both files); entry-level problems are collected in the report (all of them) and,
// unless skipped, prevent writing anything.
CocoImportReport import_coco(const CocoImportOptions& options);

}  // namespace ipd
