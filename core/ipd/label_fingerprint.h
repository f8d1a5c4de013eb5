// The fingerprint of a study's label set that every table, figure and export prints (provenance.h).
#pragma once

#include <string>

#include "core/study/study.h"

namespace ipd {

// The first 12 hex digits of SHA-256 over every GT label file of the study, in sorted order of its path
// below the study ("<domain>/labels/<stem>.txt"): each file contributes its path, a 0 byte, its size in
// decimal, a 0 byte and its bytes, so renaming, moving or editing any label file changes it. Predictions,
// pictures, study.yaml and pairs files are not covered (the hand-pair counts speak for the pairs). Each domain's
// labels/ is opened once beneath the study and its files read through it, never through a link. Throws IoError
// naming the file for a symbolic link or an unreadable file.
std::string label_set_fingerprint(const Study& study);

}  // namespace ipd
