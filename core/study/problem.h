// One problem the engine found in a study's data: a malformed label line, a file that can't be read, a scene
// without a counterpart, a pairs file that is ignored. Every part of the product reports from this one list:
// the CLI prints it on stderr, the studio shows it in its Problems window (and prints it in scripted runs).
#pragma once

#include <string>
#include <vector>

#include "core/io/label_io.h"

namespace ipd {

struct Problem {
  std::string file;          // the file at fault; empty when the problem is not one file's (a missing scene)
  int line = 0;              // 1-based line in `file`; 0 when it concerns the whole file
  std::string domain;        // the domain the file or scene belongs to; empty when none
  std::string other_domain;  // with `domain`, the domain pair it concerns (a pairs file); else empty
  std::string scene;         // the scene's stem, so a viewer can go to it; empty when not one scene's
  std::string message;
  // A pairs file whose hand pairs can't be used (a stored rock is gone): registration counts instead, and
  // `ipd table` stops unless --skip-bad-lines.
  bool unusable_pairs = false;
  // A problem of a scene's hand-pairs file: the studio lists these files' problems as they are now (a reset
  // discards a stale file; a reload can find one stale), not as they were at opening.
  bool pairs_file = false;
  // "FILE:LINE: message", "FILE: message" or "message", as the CLI prints it after "warning: ".
  std::string to_string() const;
};

// A label file's problem (malformed line, unreadable file, summary of unlisted lines) as a Problem of the
// scene `stem` in `domain`.
Problem label_problem(const LabelError& e, const std::string& domain, const std::string& stem);

}  // namespace ipd
