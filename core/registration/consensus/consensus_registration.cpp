// The default registration: consensus of plausible affines from guided hypotheses.
//
// The roles are separate types, as in COLMAP's RANSAC: the sampler (guided_sampler.h) proposes hypotheses
// cheapest first, each carrying the rock it grew from; the support measurer (support_measurer.h) scores one by a
// soft inlier count with every B rock claimed at most once, so shrinking A onto a few rocks earns nothing; the
// local optimisers (local_optimisers.h) refine promising ones by least squares on their inliers (LO-RANSAC); the
// scorer (consensus_scorer.h) keeps the confirmations of the best and asks the pure stop rule (consensus_stop.h)
// whether the consensus can still reasonably be beaten. This file runs the search, then the stages after it
// (rival placements, soft refinement, the judged final fit, the second look), and pairs the rocks by an optimal
// (Hungarian) assignment on the IoU of the aligned boxes.
#include <fmt/format.h>
#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <numeric>

#include "core/geometry/affine_estimator.h"
#include "core/registration/consensus/consensus_scorer.h"
#include "core/registration/consensus/consensus_second_look.h"
#include "core/registration/consensus/consensus_tuning.h"
#include "core/registration/consensus/guided_sampler.h"
#include "core/registration/consensus/local_optimisers.h"
#include "core/registration/consensus/shifted_placements.h"
#include "core/registration/consensus/support_measurer.h"
#include "core/registration/pairing.h"
#include "core/registration/registration_frame.h"
#include "core/registration/registration_recorder.h"

namespace ipd::detail {

namespace {

// A triple of nearby rocks carries their labelling noise into its affine (several degrees, tens of percent of
// scale), so hypotheses are held to the user's bounds with that much slack.
Bounds hypothesis_bounds(const RegistrationOptions& o) {
  const ConsensusParams& c = o.consensus;
  return Bounds{c.min_scale / kTuning.bound_slack_scale, c.max_scale * kTuning.bound_slack_scale,
                (c.max_rotation_deg + kTuning.bound_slack_deg) * M_PI / 180.0, c.max_anisotropy};
}

// Whether the second look runs: an unconfirmed search on a set small enough to enumerate its rock pairs.
bool second_look_applies(const RegistrationFrame& f, StopReason stop) {
  const double na = static_cast<double>(f.a.size()), nb = static_cast<double>(f.b.size());
  if (stop == StopReason::kCannotBeBeaten) return false;
  return !(na < 2 || nb < 2 || na * (na - 1) / 2 * nb * (nb - 1) > kTuning.max_edge_pairs);
}

// The second look (consensus_second_look.h) when the search ended unconfirmed (it ran out of hypotheses or
// trials) on a small set: its candidates and the search's best are judged on the pairing each produces, and
// the best judged wins. Confirmed searches keep their answer: looking again there changed nothing on the
// benchmark.
void second_look(const RegistrationFrame& f, const std::vector<Box>& boxes_a, const std::vector<Box>& boxes_b,
                 const RegistrationOptions& o, const Bounds& bounds, SupportMeasurer* support, SearchRecorder* recorder,
                 MethodOutcome* out) {
  if (!second_look_applies(f, out->stop)) return;
  EdgeSearch edges = edge_candidates(f, bounds, support, kTuning.edge_candidates);
  out->hypotheses += edges.hypotheses;
  out->work += edges.work;
  std::vector<Affine2> pool{out->affine_normalised};
  for (const auto& m : edges.candidates)
    if (std::none_of(pool.begin(), pool.end(), [&](const Affine2& p) { return recorder->agree(p, m); }))
      pool.push_back(m);
  std::vector<Judgement> judged;
  for (const auto& m : pool)
    judged.push_back(judge_candidate(f, boxes_a, boxes_b, m, support->score(m), pairing_rule(o)));
  size_t best = 0;
  for (size_t k = 1; k < pool.size(); ++k)
    if (judged[k].total > judged[best].total) best = k;
  double rival = -INFINITY;
  for (size_t k = 0; k < pool.size(); ++k)
    if (k != best) rival = std::max(rival, judged[k].total);
  // Replays show the candidates the second look judged, then the one it kept (when not the search's best).
  for (size_t k = 1; k < pool.size(); ++k)
    recorder->add_step(TraceStepKind::kRefinement, pool[k], judged[k].consensus, out->fit, false);
  out->note += fmt::format("{}second look: {} similarities from rock pairs, {} candidates judged; ",
                           out->note.empty() ? "" : "; ", edges.hypotheses, pool.size() - 1);
  if (best != 0) {
    out->affine_normalised = pool[best];
    out->fit = judged[best].consensus;
    recorder->add_step(TraceStepKind::kPolish, pool[best], out->fit, out->fit, true);
    out->note += "one of them replaced the search's best";
  } else {
    out->note += "the search's best kept";
  }
  // The judged pool now holds the rivals: confidence compares the best judgement with the next distinct one.
  out->confidence = confidence_from_scores(judged[best].total, rival);
}

// Large sets first register their largest rocks alone. Both labellings see the large rocks, which are few
// and far apart, so a few hypotheses find their alignment; proposed first on the whole set, it is refined and
// usually ends the search at once (a dense layout of 500 rocks a side otherwise needs ~100 hypotheses, each
// anchored on a third of B, and under a large misalignment mostly fails).
std::vector<Affine2> coarse_hypotheses(const RegistrationFrame& f, const std::vector<Box>& boxes_a,
                                       const std::vector<Box>& boxes_b, const RegistrationOptions& o,
                                       const Deadline& deadline) {
  const size_t rocks = kTuning.coarse_rocks;
  if (boxes_a.size() < kTuning.coarse_above || boxes_b.size() < kTuning.coarse_above) return {};
  auto largest = [&](const std::vector<Box>& boxes) {
    std::vector<int> order(boxes.size());
    std::iota(order.begin(), order.end(), 0);
    // Ties by index, so the subset never depends on the sort's implementation.
    std::partial_sort(order.begin(), order.begin() + rocks, order.end(), [&](int x, int y) {
      const double ax = boxes[x].w * boxes[x].h, ay = boxes[y].w * boxes[y].h;
      return ax != ay ? ax > ay : x < y;
    });
    std::vector<Box> out;
    for (size_t k = 0; k < rocks; ++k) out.push_back(boxes[order[k]]);
    return out;
  };
  RegistrationOptions sub = o;
  sub.record_trace = false;
  // Under the whole registration's deadline: the coarse pass spends the budget, it gets none of its own.
  const RegistrationReport r = register_rocks_until(largest(boxes_a), largest(boxes_b), sub, deadline);
  if (r.inliers < 3) return {};
  return {f.from_image(r.affine)};
}

// The fit that goes out, judged on the pairing it gives (consensus + IoU - unpaired rocks) among the polished
// one, the search's own (polishing fits every inlier alike, a wrong one included) and plain least squares on
// the inliers (the consensus' kernel can prefer an exact fit of three rocks that pairs worse than a fit of all
// of them). Small sets only: with many inliers one wrong pair barely moves the polish, and the three pairings
// would add a third to the cost of a large set.
Affine2 final_fit(const RegistrationFrame& f, const std::vector<Box>& boxes_a, const std::vector<Box>& boxes_b,
                  const RegistrationOptions& o, const Bounds& bounds, double gate, SupportMeasurer* support,
                  const Affine2& searched) {
  Affine2 polished = searched;
  polish(support, &polished);
  if (f.a.size() * f.b.size() > kTuning.judged_fit_max_pairs) return polished;
  std::vector<Affine2> fits{polished, searched};
  std::vector<Eigen::Vector2d> src, dst;
  support->inlier_pairs(searched, gate * gate, &src, &dst);
  Affine2 least_squares;
  if (src.size() >= 3 && affine_least_squares(src, dst, &least_squares) &&
      bounds.plausible(least_squares.leftCols<2>()))
    fits.push_back(least_squares);
  Affine2 out = polished;
  double best_total = -INFINITY;
  for (const auto& m : fits) {
    const double total = judge_candidate(f, boxes_a, boxes_b, m, support->score(m), pairing_rule(o)).total;
    if (total > best_total) best_total = total, out = m;
  }
  return out;
}

// The search's answer and its best distinct rival, as searched.
struct AnswerAndRival {
  double answer, rival;
};

// The search stops as soon as its best can't be beaten, often before a rival is scored. Shifted placements are
// the rivals a small overlap allows (a patch of rocks that fits in several places), so the translations most
// rock pairs agree on under the best's linear part are scored too. Never hand out an alignment a placement we
// scored beats (a 7 x 7 grid and the same grid one column on stopped at the identity, 42 of 49 rocks, while the
// shift fits all). When the search's own alignment, placed better, fits at least as well as the rival, that is
// the answer (least squares cannot refine rocks on a line); otherwise the rival is, flagged. Only then:
// adopting the better placed own alignment every time lost large-tier cases.
AnswerAndRival settle_shifted_placements(const RegistrationFrame& f, double gate, double best_score,
                                         SupportMeasurer* support, SearchRecorder* recorder, MethodOutcome* out) {
  const Affine2 best = out->affine_normalised;
  const ShiftedPlacements shifted = shifted_placements(support, *recorder, f, best, best.leftCols<2>(), gate, false);
  double answer = best_score, rival = std::max(recorder->rival_score(), shifted.rival);
  if (shifted.rival > answer && shifted.same >= shifted.rival) {
    out->affine_normalised = shifted.same_model;
    out->fit = answer = shifted.same;
    recorder->add_step(TraceStepKind::kRefinement, out->affine_normalised, answer, answer, true);
  } else if (shifted.rival > answer) {
    Affine2 m = shifted.rival_model;
    double s = shifted.rival;
    improve(support, &m, &s);
    out->affine_normalised = m;
    // Against the search's best and the adopted placement's own rivals (the grid's other shifts).
    const double others = shifted_placements(support, *recorder, f, m, m.leftCols<2>(), gate, false).rival;
    rival = std::max({answer, shifted.same, others});
    out->fit = answer = s;
    out->beaten = true;
    recorder->add_step(TraceStepKind::kRefinement, m, s, s, true);
    out->note = "a shifted placement scored after the search fitted better than its best: used";
  }
  return {answer, rival};
}

// Under a time budget, whether a stage after the search may start: only when the time left (before the final
// pairing's share) exceeds its cost, counted in whole-set scores and timed by one score measured after the search.
// A stage cannot be cut once started (rival placements sort thousands of votes), so it is not started. Without a
// budget every stage runs and the clock is never read.
struct StageTime {
  const Deadline& deadline;
  double score_ms = 0;
  bool allows(double scores) const {
    return !deadline.has_budget() || deadline.ends_at_ms() - deadline.elapsed_ms() > scores * score_ms;
  }
};
// Whole-set scores each stage costs, about (translation votes and their sort count as four): the rival placements
// vote and score twice and may improve one, the soft refinement and the judged final fit iterate over the set.
constexpr double kPlacementsScores = 30, kSoftRefineScores = 20, kFinalFitScores = 20, kSecondLookScores = 10;

// The stages after a search that found a best (with time left): rival placements, the soft refinement of a
// confirmed best, the judged final fit, and the second look of an unconfirmed one. Each later stage only starts
// while the time budget lasts; a stage left out is noted and the budget named as the stop.
void after_search(const RegistrationFrame& f, const std::vector<Box>& boxes_a, const std::vector<Box>& boxes_b,
                  const RegistrationOptions& o, const Bounds& bounds, double gate, const RobustLoopResult<Affine2>& r,
                  const StageTime& time, SupportMeasurer* support, SearchRecorder* recorder, MethodOutcome* out) {
  out->affine_normalised = r.best;
  out->fit = r.best_score;
  const AnswerAndRival scores = settle_shifted_placements(f, gate, r.best_score, support, recorder, out);
  out->confidence = confidence_from_scores(scores.answer, scores.rival);  // as searched, before soft refinement
  const char* left_out = nullptr;
  if (!time.allows(kSoftRefineScores)) {
    left_out = "the soft refinement, final fit and second look";
  } else {
    // A confirmed best only: an unconfirmed one is judged against the second look's candidates next, and
    // raising it alone would tilt that comparison (3 true pairs among 15 rocks: seed 5 of
    // SmallOverlap.ThreeTruePairsAmongFifteenRocksAt25Degrees).
    if (r.stop == StopReason::kCannotBeBeaten && soft_refine(support, &out->affine_normalised, &out->fit))
      recorder->add_step(TraceStepKind::kRefinement, out->affine_normalised, out->fit, out->fit, true);
    if (!time.allows(kFinalFitScores)) {
      left_out = "the final fit and second look";
    } else {
      out->affine_normalised = final_fit(f, boxes_a, boxes_b, o, bounds, gate, support, out->affine_normalised);
      recorder->add_step(TraceStepKind::kPolish, out->affine_normalised, out->fit, out->fit, false);
      if (second_look_applies(f, out->stop) && !time.allows(kSecondLookScores))
        left_out = "the second look";
      else
        second_look(f, boxes_a, boxes_b, o, bounds, support, recorder, out);
    }
  }
  if (left_out != nullptr) {
    out->stop = StopReason::kTimeBudget;
    add_note(&out->note, fmt::format("time budget spent after the search: {} left out", left_out));
  }
}

// The answer when the time budget ends the set-up before any hypothesis is scored: the coarse pass's alignment
// of the largest rocks when it found one, else the identity; neither was judged against a rival.
void cut_during_set_up(const RegistrationFrame& f, const std::vector<Affine2>& coarse, MethodOutcome* out) {
  out->stop = StopReason::kTimeBudget;
  out->confidence = 0;
  out->unjudged = Ambiguity::kUnchecked;
  out->inliers = -1;  // the pairs stand in (no grid was built to count them)
  if (!coarse.empty()) {
    out->affine_normalised = coarse.front();
    out->note = "time budget spent while setting up the search: the alignment of the largest rocks used";
  } else {
    out->affine_normalised = f.from_image(identity_affine());
    out->note = "time budget spent while setting up the search: identity used";
  }
}

// The search and the stages after it, on two non-empty sides.
void search(const RegistrationFrame& f, const std::vector<Box>& boxes_a, const std::vector<Box>& boxes_b,
            const RegistrationOptions& o, const Deadline& deadline, MethodOutcome* out) {
  const Bounds bounds = hypothesis_bounds(o);
  const double gate = consensus_gate(f, o, deadline);
  // The set-up (the coarse pass, each side's neighbours, the grid) is read against the time budget between its
  // stages; when the budget ends it, no hypothesis has been scored and the search does not start.
  std::vector<Affine2> coarse;
  if (!deadline.passed()) coarse = coarse_hypotheses(f, boxes_a, boxes_b, o, deadline);
  if (deadline.passed()) return cut_during_set_up(f, coarse, out);
  GuidedSampler sampler(f, bounds, gate, o.seed, o.record_trace, coarse, &deadline);
  if (deadline.passed()) return cut_during_set_up(f, coarse, out);
  SupportMeasurer support(f, gate, bounds);
  ConsensusScorer scorer(&support, o.consensus.max_hypotheses, &deadline);
  PassThroughEstimator estimator;
  RobustLoopOptions lo;
  lo.max_trials = o.consensus.max_hypotheses;
  lo.max_work = work_budget(o, f.a.size(), f.b.size());
  lo.work_per_model = static_cast<double>(f.a.size());  // one nearest-neighbour query per A rock
  auto sample_of = [&](const Affine2&, std::vector<int>* sa, std::vector<int>* sb) {
    if (!sampler.has_sample) return;  // identity and voted translations are not built from rocks
    sa->assign(sampler.sample.begin(), sampler.sample.begin() + 3);
    sb->assign(sampler.sample.begin() + 3, sampler.sample.end());
  };
  SearchRecorder recorder(
      f, gate, o.record_trace, [](double s) { return s; }, sample_of);
  DeadlineSampler<GuidedSampler> timed{sampler, deadline, o.consensus.max_hypotheses};
  auto r = run_robust_loop<Affine2, GuidedHypothesis>(timed, estimator, scorer, lo, recorder);
  r.stop = timed.stop(r.stop);
  out->samples = r.samples;
  out->hypotheses = r.hypotheses;
  out->work = r.work;
  out->stop = r.stop;
  const bool found = r.found && std::isfinite(r.best_score);
  StageTime time{deadline};
  if (found && deadline.has_budget()) {
    const double before = deadline.elapsed_ms();
    support.score(r.best);
    time.score_ms = deadline.elapsed_ms() - before;
  }
  if (found && !time.allows(kPlacementsScores)) {
    // Each stage after the search scores whole sets again (tens of milliseconds on 5,000 rocks): with the
    // time budget spent the answer is the search's best as it stands, judged against the rivals it scored.
    out->affine_normalised = r.best;
    out->fit = r.best_score;
    out->stop = StopReason::kTimeBudget;
    out->confidence = confidence_from_scores(r.best_score, recorder.rival_score());
    out->note = "time budget spent: the search's best, without the rival placements, polish or second look";
  } else if (found) {
    after_search(f, boxes_a, boxes_b, o, bounds, gate, r, time, &support, &recorder, out);
  } else {
    out->note = r.stop == StopReason::kTimeBudget
                    ? "time budget spent before a plausible affine was found: identity used"
                    : "no plausible affine found: identity used";
    out->confidence = 0;
    out->unjudged = r.stop == StopReason::kTimeBudget ? Ambiguity::kUnchecked : Ambiguity::kNoPlausible;
  }
  out->trace = recorder.take_trace(describe_stop(r.stop, r.samples, r.hypotheses, r.work, lo.max_work));
  // Counting inliers queries the grid once per A rock: with the budget spent the pairs stand in (set after them).
  out->inliers = deadline.passed() ? -1 : support.count_inliers(out->affine_normalised);
  if (f.a.size() < 3 || f.b.size() < 3) out->note = "fewer than 3 rocks on a side: translation at most";
}

}  // namespace

// The gate: the user's, or a fraction of the typical spacing of B's rocks within bounds of the layout's spread
// (normalised units, so shifting or scaling a layout within the picture keeps it), and not under a fraction of
// the picture's width (two labellings put a rock's centre up to ~1% of the width apart however close the rocks
// are) unless that is over half the spacing.
double consensus_gate(const RegistrationFrame& f, const RegistrationOptions& o, const Deadline& deadline) {
  if (o.consensus.inlier_gate) return *o.consensus.inlier_gate / f.spread;
  const double spacing = median_nn_distance(f.b, &deadline);
  return std::max(std::clamp(kTuning.gate_of_spacing * spacing, kTuning.gate_min, kTuning.gate_max),
                  std::min(kTuning.min_gate_of_width / f.spread, kTuning.max_floor_of_spacing * spacing));
}

MethodOutcome register_consensus(const RegistrationFrame& f, const std::vector<Box>& boxes_a,
                                 const std::vector<Box>& boxes_b, const RegistrationOptions& o,
                                 const Deadline& deadline) {
  MethodOutcome out;
  out.affine_normalised = f.from_image(identity_affine());
  if (!f.a.empty() && !f.b.empty()) {
    search(f, boxes_a, boxes_b, o, deadline, &out);
  } else {
    out.stop = StopReason::kTooFewPoints;
    out.note = "a side has no rocks: nothing to register";
  }
  pair_final(f.to_image(out.affine_normalised), boxes_a, boxes_b, o, deadline, &out);
  if (out.inliers < 0) out.inliers = static_cast<int>(out.pairs.size());
  return out;
}

}  // namespace ipd::detail
