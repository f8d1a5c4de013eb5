// `ipd import yolo`: a YOLO dataset as a tool wrote it (yolo_source.h) into one domain of the study layout.
// The label files are copied as they are (after every line was read and checked), the class names go to
// labels/classes.txt, the pictures are hard-linked (or copied) into images/ under the scene's name, and
// <domain>/import.json records where each came from and every name that was mapped back. All or nothing: the
// domain is written into a folder beside it and renamed in (StagedFolder), so an error leaves the study as it was.
#pragma once

#include <string>
#include <vector>

#include "core/io/label_io.h"
#include "core/study/yolo_source.h"

namespace ipd {

struct YoloImportOptions {
  std::string source;    // a data.yaml or a dataset folder
  std::string out_dir;   // the domain directory, e.g. STUDY/real
  std::string split;     // one split only ("" merges every split)
  bool replace = false;  // a domain folder with files is refused unless this is set (then replaced whole)
  // Class names for a source without a names file (`--names rock,shadow`: class k is the k-th); refused beside
  // a source that names its classes itself.
  std::vector<std::string> names;
  // Malformed lines (and boxes of an unnamed class) are warnings: each is written as a comment ("# skipped by
  // ipd import yolo --skip-bad-lines: <the line>"), so the domain reads without them and nothing is lost. A
  // source whose skipped lines would be more than half of its box lines is still refused (what is left is not
  // the dataset).
  bool skip_bad_lines = false;

  // Empty when usable; otherwise the field that is wrong, in one sentence.
  std::string validate() const;
  void check() const;  // throws std::invalid_argument("YOLO import options: " + validate())
};

struct YoloImportReport {
  YoloSource source;
  int scenes = 0, boxes = 0, linked_images = 0;
  int without_label_file = 0;      // pictures without a label file: scenes without objects (an empty label file)
  std::vector<LabelError> errors;  // malformed lines, unnamed classes: nothing is written while there is one
                                   // (with skip_bad_lines: the lines skipped, unless a file can't be read)
  int skipped_lines = 0;           // with skip_bad_lines: lines written as comments
  // With skip_bad_lines, why the import still stopped: the skipped lines were more than half of the box lines.
  std::string most_skipped;
  bool written = false;
  std::vector<std::string> kept_prediction_sets;  // predictions/<model>/ of the replaced domain, kept as they were
};

// Throws StudyError for a source it cannot read (yolo_source.h), a domain folder that holds files (without
// `replace`) and class names the study's disagree with (naming both files); line problems are in the report.
YoloImportReport import_yolo(const YoloImportOptions& options);

// The study's class names a domain about to be imported into `domain_dir` must agree with: study.yaml's
// `classes` (every name of `names` among them) and each sibling domain's labels/classes.txt (the same number,
// the same name). Throws StudyError naming `names_file` and the file that disagrees.
void check_class_names(const std::string& domain_dir, const std::vector<std::string>& names,
                       const std::string& names_file);

}  // namespace ipd
