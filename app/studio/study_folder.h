// Which folders the Open dialog opens as a study: a study.yaml, or a <domain>/labels/ folder (the layout
// core/study reads). Its path field checks a typed or pasted path with this before asking the worker, so a
// typing error is said in the dialog, next to the path, rather than replacing the study on screen.
#pragma once

#include <string>

namespace ipd::studio {

// A leading "~/" (or a lone "~") is the user's home folder ($HOME); surrounding spaces and quotes, as a
// pasted path often has, are dropped.
std::string expand_typed_path(const std::string& typed);

bool looks_like_study(const std::string& dir);

// Empty when `dir` can be opened as a study; else why not, naming the path: "PATH: no such folder",
// "PATH: is a file, not a folder", "PATH: not a study (no study.yaml or <domain>/labels/ in it)".
std::string open_path_problem(const std::string& dir);

}  // namespace ipd::studio
