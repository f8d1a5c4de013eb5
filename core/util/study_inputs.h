// Which paths of a study are its inputs, so that no output (`--out`, a figure the studio exports) replaces one.
//
// A table written to `STUDY/real/labels/scene_01.txt` or an export to `STUDY/pairs/real__synth/s1.json` would
// replace the file, and the next table would be computed from it: such a write is refused. The inputs are the study's
// layout (study-format.md): `study.yaml`, everything under `pairs/`, `review/` and `.ipd-cache/`, and everything under
// a top-level folder's `labels/`, `images/` and `predictions/` (a domain's, or one such a write would create).
#pragma once

#include <string>

namespace ipd {

// "" when `path` may take an output; otherwise "PATH: is one of the study's inputs (WHAT); ..." saying why
// and where outputs go. Checked on the path as given and on its resolved form (a link of the user's, outside
// the study, that points into it is seen through); links below the study are refused when writing anyway.
std::string study_input_problem(const std::string& root, const std::string& path);

}  // namespace ipd
