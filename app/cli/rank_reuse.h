// A ranking run again from what the last one kept (core/rank/rank_cache.h): the reference and the new or changed
// candidates read and computed, the other candidates' cells, and their comparisons with a best that did not change,
// taken as they were kept. Whatever the domains read say besides numbers (a warning, a label error, a class or task
// note, a class or an outline that changes what the whole study is about) sends the run back to the whole study,
// which says it as a first run would.
#pragma once

#include <map>
#include <optional>
#include <string>

#include "app/cli/rank_study.h"
#include "core/rank/rank_cache.h"

namespace ipd::cli {

// What a ranking run knows before it reads a label file: the options as they apply, every domain's stamps now and
// the digest each candidate's cell would be kept under.
struct RankReusePlan {
  const Study* study = nullptr;
  const StudyOptions* options = nullptr;
  RankOptions rank;
  RegistrationOptions registration;
  DomainStampsMap now;
  // candidate -> rank_cell_inputs
  std::map<std::string, std::string> inputs;
};

// The plan for `study` (nullopt when the files can't be examined: the run then reads them and says why).
std::optional<RankReusePlan> plan_rank_reuse(const Study& study, const StudyOptions& options, const RankOptions& rank,
                                             const RegistrationOptions& registration, const std::string& settings);

// The ranking with every kept cell that still applies; nullopt when none applies or the run must read the whole
// study (see above). `reused` gets the candidates taken as kept.
std::optional<RankedStudy> rank_from_kept(const RankReusePlan& plan, const RankCache& cache,
                                          std::vector<std::string>* reused);

// Keeps a ranking of the whole study for the next run, when it said nothing but numbers.
void keep_whole_ranking(const RankReusePlan& plan, const RankCache& cache, const RankedStudy& ranked);

}  // namespace ipd::cli
