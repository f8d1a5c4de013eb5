// How a demo study's files reach the disk. A demo is a new study in a new (or empty) folder that nobody reads
// while it is written, so its thousands of label files go without a temp file and a sync each (a sync a file made a
// 10,000-scene labels-only demo take minutes); study.yaml, which makes the folder a study, is written last, after
// one sync of everything before it.
#pragma once

#include <string>
#include <vector>

#include "core/io/label_io.h"

namespace ipd {

// Writes DIR/relative (a new file; its folders are created, none may be a link). Throws IoError naming it.
void write_demo_file(const std::string& dir, const std::string& relative, const std::string& contents);
void write_demo_labels(const std::string& dir, const std::string& relative, const std::vector<Box>& boxes,
                       LabelKind kind);
// Syncs what was written, then writes study.yaml and README.md (each atomically; no README when `readme` is empty):
// the study is there whole or has no study.yaml.
void finish_demo_study(const std::string& dir, const std::string& study_yaml, const std::string& readme);

}  // namespace ipd
