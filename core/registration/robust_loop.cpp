// The robust loop's option checks (the loop itself is a template in the header).
#include "core/registration/robust_loop.h"

#include <fmt/format.h>

#include <stdexcept>

namespace ipd {

std::string RobustLoopOptions::validate() const {
  if (max_trials < 0) return fmt::format("max_trials must be at least 0, got {}", max_trials);
  if (!(max_work >= 0)) return fmt::format("max_work must be >= 0 (0: no limit), got {}", max_work);
  if (!(work_per_model >= 0) || !std::isfinite(work_per_model))
    return fmt::format("work_per_model must be a number >= 0, got {}", work_per_model);
  return {};
}

void RobustLoopOptions::check() const {
  if (const std::string problem = validate(); !problem.empty())
    throw std::invalid_argument("robust loop options: " + problem);
}

}  // namespace ipd
