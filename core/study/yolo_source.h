// A YOLO dataset as the tools that make one lay it out: an Ultralytics/YOLOv5 `data.yaml` (train/val/test
// folders or image lists, `names` as a list or a mapping), a dataset folder (images/<split>, labels/<split>), a
// CVAT "YOLO 1.1" export (obj.names, obj.data, obj_<subset>_data/), a Label Studio YOLO export (classes.txt,
// images/, labels/) or a Roboflow "YOLOv5 PyTorch" export (data.yaml, train|valid|test/{images,labels}).
//
// A source is someone else's folder: every file of it is reached below its root without following a symbolic
// link (contained_file.h), so a link in it (`labels/0001.txt -> /etc/passwd`) is refused, naming it, never read.
// Names the tools mangle are mapped back by one documented rule each (scene_stem_rules), and two files that
// would become one scene are refused, naming both.
#pragma once

#include <string>
#include <vector>

namespace ipd {

// One scene of a source: its label file and picture (paths below the source root; either may be empty).
struct SourceScene {
  std::string split;        // "train", "val", ...; "" for a source without splits
  std::string label;        // below root; "" when the picture has no label file (no objects)
  std::string picture;      // below root; "" when there is none
  std::string source_stem;  // the name as the tool wrote it (1a2b3c4d-0001, 0001_jpg.rf.<hash>)
  std::string stem;         // the scene's name in the study
};

struct YoloSource {
  std::string root;                      // the folder every path is below (absolute)
  std::string layout;                    // "data.yaml", "CVAT YOLO 1.1", "Label Studio YOLO", "dataset folder"
  std::string names_file;                // the file that named the classes (shown path); "" when none did
  std::vector<std::string> class_names;  // by class number; "" for a number the file leaves unnamed
  std::vector<std::string> splits;       // the splits found, in the order the source gives them
  std::vector<SourceScene> scenes;       // sorted by stem
  std::vector<std::string> renamings;    // the rules that renamed scenes, one sentence each (for the report)
};

// The study's name for a stem a tool wrote: Roboflow's "<name>_<ext>.rf.<32 hex digits>" is "<name>" (the
// extension and the export's hash are Roboflow's, not the picture's name); Label Studio's "<8 hex digits>-<name>"
// is "<name>" when `strip_upload_prefix` (every stem of the source carries such a prefix: an upload's id).
// Anything else is kept as it is.
std::string scene_stem(const std::string& source_stem, bool strip_upload_prefix);
// Whether `stem` starts with Label Studio's upload prefix: 8 lower-case hex digits and '-', then a name.
bool has_upload_prefix(const std::string& stem);

// Finds the dataset at `src` (a data.yaml or one of the folders above) and lists its scenes; `split` keeps
// one split ("" merges them all). Throws StudyError naming the file (and line) for a layout it does not know,
// a malformed or truncated data.yaml, a split folder that is not there, a symbolic link in the source, two
// pictures or label files that become one scene, and a split name the source does not have.
YoloSource find_yolo_source(const std::string& src, const std::string& split);

// When `folder` (named where a study was expected, as `shown`) holds what a YOLO dataset or a labelling tool's
// export holds (data.yaml, obj.names, classes.txt, labels/, train/labels/): "; it holds X, as ...: ipd import yolo
// SHOWN --out STUDY/<domain> brings it into a study (docs/import.md)", to end a "no domains found"; else "".
std::string yolo_dataset_hint(const std::string& folder, const std::string& shown);

// The image extensions a study reads (lower case, with the dot).
bool is_picture_name(const std::string& file_name);

}  // namespace ipd
