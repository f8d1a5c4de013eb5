// Which renderer setting is closest to reality: every candidate domain's IPD(ref, candidate) for one model, with
// the table's scene-bootstrap interval, sorted best (lowest) first; each candidate's paired ΔIPD against the best
// (ipd compare's comparison: the same paired interval and sign-flip test, compare_renderers), its p-value
// Holm-corrected over the candidates compared with the best; and the group of candidates not distinguishable
// from the best at the chosen level (compare's verdict rule, significant_difference, on the Holm p-value).
//
// The numbers come from a CrossTable whose (ref, candidate) cells were computed (TableOptions::only_pairs =
// ranked_pairs registers those and no candidate-vs-candidate pair), so a cell's IPD and interval are `ipd table`'s.
#pragma once

#include <functional>
#include <limits>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/ipd/ipd.h"
#include "core/stats/study_statistics.h"

namespace ipd {

// The names a ranking is about, checked against the study: the reference and the candidates in the order asked
// for (every other domain, in study order, when none are named).
struct RankDomains {
  std::string ref;
  std::vector<std::string> candidates;
};
// Throws StudyError naming an unknown domain (and the study's domains), the reference among the candidates, a
// candidate named twice, or a study with no other domain than the reference.
RankDomains resolve_rank_domains(const Study& study, const std::string& ref,
                                 const std::vector<std::string>& candidates);
// The domain pairs a ranking reads, (ref, candidate) for each candidate: what it registers
// (TableOptions::only_pairs), never a candidate against another.
DomainPairFilter ranked_pairs(const RankDomains& domains);

struct RankOptions {
  std::string model;
  RankDomains domains;
  CompareOptions compare;             // the bootstrap (as the table's intervals) and the permutations of each test
  double level = kSignificanceLevel;  // significance level of the Holm-corrected tests, in (0, 1)
  int threads = 0;  // the comparisons with the best run on this many cores (0: every one); the result is the same
  // Empty when usable; otherwise the field that is wrong and the accepted range, in one sentence.
  std::string validate() const;
};

struct RankedCandidate {
  std::string domain;
  std::vector<std::pair<std::string, double>> params;  // study.yaml's domains.<name>.params
  // IPD(ref, candidate) as the table's cell has it: its scene-bootstrap interval, pairs and scenes.
  double ipd = std::numeric_limits<double>::quiet_NaN();
  double ci_low = std::numeric_limits<double>::quiet_NaN(), ci_high = std::numeric_limits<double>::quiet_NaN();
  double se = std::numeric_limits<double>::quiet_NaN();
  long pairs = 0;
  int scenes = 0;
  int rank = 0;  // 1 = best
  // Δ = IPD(ref, candidate) − IPD(ref, best) over the scenes of ref, the candidate and the best; none for the best.
  std::optional<RendererComparison> vs_best;
  double p_holm = std::numeric_limits<double>::quiet_NaN();  // vs_best's p-value, Holm-corrected
  bool in_best_group = false;                                // the best, or not distinguishable from it at the level
  // The candidate has no prediction left at the threshold: its IPD is a number (every rock there counts as
  // missed, the table's rule), and the ranking says so beside it.
  bool no_predictions_at_threshold = false;
};

// A candidate with no IPD to rank, and why ("shares no scenes with real ...").
struct UnrankedCandidate {
  std::string domain, reason;
};

struct Ranking {
  std::string model, trained_on, ref;
  std::vector<RankedCandidate> ranked;  // best first; ties keep the candidates' order
  std::vector<UnrankedCandidate> unranked;
  int tests = 0;  // comparisons with the best that were tested (Holm's m)
  RankOptions options;
  const RankedCandidate* best() const { return ranked.empty() ? nullptr : &ranked.front(); }
};

// Ranks the candidates of `options` from `table` (its (ref, candidate) cells for options.model, intervals
// added). A candidate without a number is unranked with its reason and the rest are ranked; throws StudyError
// when no candidate can be ranked (every reason listed) or the model is not in the table.
Ranking rank_candidates(const StudyLabels& labels, const CrossTable& table, const RankOptions& options);

// rank_candidates in its two steps, for a ranking whose cells and comparisons may come from an earlier run
// (rank_cache.h). First the order: each candidate's cell (no scenes needed), best first, the unranked with their
// reasons; `without_predictions(candidate)` says whether it has no prediction left at the threshold.
Ranking order_candidates(const Study& study, const CrossTable& table, const RankOptions& options,
                         const std::function<bool(const std::string& candidate)>& without_predictions);
// Then each candidate's comparison with the best (`compare(candidate, best)`, called on options.threads cores),
// the Holm correction over them and the group not distinguishable from the best.
using CompareWithBest = std::function<RendererComparison(const std::string& candidate, const std::string& best)>;
void compare_with_best(Ranking* ranking, const CompareWithBest& compare);

}  // namespace ipd
