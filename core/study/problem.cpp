#include "core/study/problem.h"

#include <fmt/format.h>

namespace ipd {

std::string Problem::to_string() const {
  if (file.empty()) return message;
  if (line > 0) return fmt::format("{}:{}: {}", file, line, message);
  return fmt::format("{}: {}", file, message);
}

Problem label_problem(const LabelError& e, const std::string& domain, const std::string& stem) {
  Problem p;
  p.file = e.file;
  p.line = e.line;
  p.domain = domain;
  p.scene = stem;
  // A summary line has no message of its own: say what it counts.
  p.message = e.line == 0 && e.more > 0 ? fmt::format("{} more malformed line(s) not listed", e.more) : e.message;
  return p;
}

}  // namespace ipd
