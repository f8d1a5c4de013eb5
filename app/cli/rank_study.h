// The ranking of a study's renderer settings as `ipd rank` and `ipd figure sweep` compute it: the study opened
// with the shared options, only the (reference, candidate) domain pairs registered (through the caches, so a new
// variant is the only one registered on a re-run), intervals as `ipd table`'s, then core/rank's ranking.
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "app/cli/study_options.h"
#include "core/rank/ranking.h"
#include "core/report/provenance.h"

namespace ipd::cli {

struct RankArgs {
  StudyOptions study;
  std::string ref;                      // --ref; empty: the study's first domain
  std::vector<std::string> candidates;  // --candidates; empty: every other domain
  double level = kSignificanceLevel;    // --level
  int permutations = 2000;              // --permutations
};

// Adds STUDY, the shared study options, --ref, --candidates, --level and --permutations.
void add_rank_options(CLI::App* cmd, RankArgs* args);

struct RankedStudy {
  LoadedStudy loaded;
  Ranking ranking;
  Provenance provenance;
};

// nullopt when the labels' errors are fatal (already reported). Throws StudyError for an unknown domain, a model
// that is not one (or several models), or nothing to rank. `check` (optional) sees the opened study before any
// work: a JSON output refuses names it can't write there (require_utf8_names), without opening it twice.
std::optional<RankedStudy> rank_study(const RankArgs& args, const std::function<void(const Study&)>& check = {});

}  // namespace ipd::cli
