// Class names are data: the numbering every number of a study is about, and how each label set's class ids map
// onto it.
//
// A study's classes are named by study.yaml (`classes: [rock, shadow]`), else by the first domain (in study order)
// whose labels/classes.txt exists. Every other classes.txt (a domain's labels/, a prediction set's
// predictions/<model>/) is read by *name*: a set that numbers "rock" 1 where the study numbers it 0 is mapped,
// and said once (CVAT's COCO export is 1-based, YOLO's 0-based). A name the study does not know is refused,
// naming both files, as is a class number that one set uses but the study's names leave unnamed (found when the
// label files are read: study_labels' class accounting). A set without classes.txt uses the study's numbers.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "core/io/label_io.h"

namespace ipd {

struct StudyConfig;
struct Domain;

// The class an IPD is about: a class number of the study, or one of these.
inline constexpr int kNoClassChosen = -1;  // none named: fine for a single-class study, refused for more
inline constexpr int kAllClasses = -2;     // asked for explicitly (`--class all`): a class-blind number

struct StudyClasses {
  std::vector<std::string> names;  // by study class number; "" where no file names that number
  std::string named_by;            // "study.yaml" or "<domain>/labels/classes.txt"; "" when nothing names them
  // Label sets ("<domain>/labels", "<domain>/predictions/<model>") whose numbers differ from the study's: the
  // set's class number -> the study's (-1: the set's classes.txt leaves that number unnamed).
  std::map<std::string, std::vector<int>> id_maps;
  std::vector<std::string> notes;  // each mapping by name, said once

  // "rock", or "class 3" for a number nothing names.
  std::string name_of(int cls) const;
  // "rock (class 0)", "class 3", "all classes" (kAllClasses).
  std::string describe(int cls) const;
  // The class a user's word means: a name, a class number, or "all" (kAllClasses). Throws StudyError naming the
  // classes there are when it is neither.
  int resolve(const std::string& word) const;
  // The map of one label set (model "" for ground truth), or nullptr when its numbers are the study's.
  const std::vector<int>* id_map(const std::string& domain, const std::string& model) const;
  // One text that changes whenever a map changes (a cache of mapped label files keys on it).
  std::string map_key() const;
};

// Reads the class names of the study at `root`: study.yaml's `classes` (in `config`), then every domain's
// labels/classes.txt and predictions/<model>/classes.txt. Throws StudyError naming both files when a set names a
// class the study doesn't, and FILE:LINE for a name given twice in one file.
StudyClasses read_study_classes(const std::string& root, const StudyConfig& config, const std::vector<Domain>& domains);

// Renumbers `file`'s boxes into the study's class numbers through `map` (the set's id_map, nullptr when its numbers
// are the study's). A box whose class no file names, where the study names its classes, is a LabelError of its
// line and is dropped (`names_file` is the set's classes.txt, for the message).
void map_label_classes(LabelFile* file, const StudyClasses& classes, const std::vector<int>* map,
                       const std::string& names_file);

// `--class-map FROM:TO` pairs: prediction class FROM is the study's class TO (for prediction sets without a
// classes.txt whose numbers are shifted). Applied to every prediction set that has no map of its own.
void apply_prediction_class_map(const std::map<int, int>& from_to, const std::vector<Domain>& domains,
                                StudyClasses* classes);

}  // namespace ipd
