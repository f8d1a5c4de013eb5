#include "core/session/scene_filter.h"

#include <cmath>
#include <cstdlib>
#include <sstream>

#include "core/util/number_text.h"

namespace ipd {

SceneFilter SceneFilter::parse(const std::string& text) {
  SceneFilter f;
  std::istringstream in(text);
  for (std::string w; in >> w;) {
    Term t;
    if (w == "suspect")
      t.kind = Term::Kind::kSuspect;
    else if (w == "edited")
      t.kind = Term::Kind::kEdited;
    else if (w == "ambiguous")
      t.kind = Term::Kind::kAmbiguous;
    else if (w == "reviewed")
      t.kind = Term::Kind::kReviewed;
    else if (w == "unreviewed")
      t.kind = Term::Kind::kUnreviewed;
    else if (w.rfind("ipd", 0) == 0 && w.size() > 3 && (w[3] == '<' || w[3] == '>' || w[3] == '=')) {
      t.kind = Term::Kind::kIpd;
      const size_t len = (w.size() > 4 && w[4] == '=') ? 2 : 1;
      t.op = w.substr(3, len);
      const std::string number = w.substr(3 + len);
      if (!parse_decimal(number, &t.value) || !std::isfinite(t.value)) {
        f.error = "'" + w + "': expected a number after " + t.op;
        continue;
      }
    } else {
      t.text = w;
    }
    f.terms.push_back(t);
  }
  return f;
}

bool SceneFilter::matches(const SceneSummary& s) const {
  for (const Term& t : terms) {
    switch (t.kind) {
      case Term::Kind::kText:
        if (s.stem.find(t.text) == std::string::npos) return false;
        break;
      case Term::Kind::kSuspect:
        if (s.suspects == 0) return false;
        break;
      case Term::Kind::kEdited:
        if (!s.edited) return false;
        break;
      case Term::Kind::kAmbiguous:
        if (!s.ambiguous) return false;
        break;
      case Term::Kind::kReviewed:
        if (!s.reviewed) return false;
        break;
      case Term::Kind::kUnreviewed:
        if (s.reviewed) return false;
        break;
      case Term::Kind::kIpd: {
        if (std::isnan(s.ipd)) return false;
        const bool ok = t.op == ">"    ? s.ipd > t.value
                        : t.op == ">=" ? s.ipd >= t.value
                        : t.op == "<"  ? s.ipd < t.value
                        : t.op == "<=" ? s.ipd <= t.value
                                       : s.ipd == t.value;
        if (!ok) return false;
        break;
      }
    }
  }
  return true;
}

}  // namespace ipd
