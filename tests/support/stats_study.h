// A generated labels-only study for the statistics tests: 12 scenes of 10 rocks, domains real, principled,
// hapke, one model "det" trained on real. Detections are offset from the GT by a fraction of the box
// width that depends on the domain (hapke misses small rocks badly), so the IPDs are known in shape.
#pragma once

#include <string>

namespace ipd::test {

enum class StatsStudyVariant {
  kDistinct,           // three different domains
  kHapkeIsPrincipled,  // hapke's files are principled's (b is a)
  kPrincipledIsReal,   // principled's files are real's (a equals the reference)
};

void write_stats_study(const std::string& root, StatsStudyVariant variant);

}  // namespace ipd::test
