// The scene list's filter: words separated by spaces, every one must match. `ipd>0.1`, `ipd<=0.05`
// (also >=, <, =), `suspect` (a suspect pair not checked as correct), `edited` (pairs fixed by hand),
// `ambiguous` (registration could not decide), `reviewed` / `unreviewed` (marked as looked at or not,
// review_state.h), anything else: part of the scene's name.
#pragma once

#include <string>
#include <vector>

#include "core/session/session.h"

namespace ipd {

struct SceneFilter {
  struct Term {
    enum class Kind { kText, kIpd, kSuspect, kEdited, kAmbiguous, kReviewed, kUnreviewed } kind = Kind::kText;
    std::string text, op;  // op: ">", ">=", "<", "<=", "="
    double value = 0;
  };
  std::vector<Term> terms;
  std::string error;  // a word that looked like a comparison but isn't one, e.g. "ipd>abc"

  static SceneFilter parse(const std::string& text);
  bool matches(const SceneSummary& s) const;  // a scene without an IPD fails every ipd comparison
};

}  // namespace ipd
