// Internal: every constant of the consensus registration that was chosen on the registration benchmark, in one
// place. Each says why it has its value; the measurements behind them are in docs/method.md ("Tuned constants
// and their evidence").
#pragma once

#include <array>
#include <cstddef>

namespace ipd::detail {

struct ConsensusTuning {
  // --- Hypotheses (guided_sampler.cpp) ---
  // A rock's neighbours that form triples: more on side B, where some of A's neighbours may be hidden or moved.
  int neighbours_a = 5, neighbours_b = 8;
  // Sets of at most this many rocks a side are searched more widely (fewer rocks keep fewer neighbours in
  // common): two more neighbours on A, three more on B; a side of at most `all_neighbours_below` rocks uses all.
  std::size_t small_set = 16, all_neighbours_below = 12;
  // Above this many (A, B) rock pairs no translation votes are cast: the triples alone are cheaper.
  std::size_t max_vote_pairs = 250000;
  // Slack on the user's bounds for a triple's affine, which carries its three rocks' labelling noise.
  double bound_slack_scale = 1.25, bound_slack_deg = 15.0;
  // Largest |log size ratio| (after the sets' median ratio) of two rocks that may be one rock.
  double max_log_size_gap = 1.1;
  // Triangles flatter than this (twice the area over the longest side squared) propose a similarity.
  double flat_triple = 0.05;
  // A rocks that vote for translations (every k-th): more make the votes cost n^2 on mid-sized sets.
  std::size_t translation_voters = 16;
  // Sets of at least `coarse_above` rocks a side are first registered on their `coarse_rocks` largest.
  std::size_t coarse_above = 160, coarse_rocks = 64;

  // --- The gate (consensus_registration.cpp) ---
  // The gate is this fraction of B's rock spacing, within [gate_min, gate_max] of the layout's spread...
  double gate_of_spacing = 0.3, gate_min = 0.02, gate_max = 0.2;
  // ...and never under this fraction of the picture's width, unless that is over this fraction of the spacing.
  double min_gate_of_width = 0.015, max_floor_of_spacing = 0.5;

  // --- The soft consensus score (support_measurer.cpp) ---
  // Spread of the log width and height ratio of one rock's two labellings.
  double size_sigma = 0.25;
  constexpr double size_weight() const { return 1.0 / (2 * size_sigma * size_sigma); }
  // Sets of at least twice `preview_rocks` preview each hypothesis on that many rocks; previews scaled up
  // below `preview_reject` of the best refined score end there (half the refinement threshold: room for noise).
  std::size_t preview_rocks = 64;
  double preview_reject = 0.25;

  // --- Local optimisation (local_optimisers.cpp) ---
  // A hypothesis is refined when it scores at least `refine_fraction` of the best and above `min_refine_score`
  // (its own three rocks and a half).
  double refine_fraction = 0.5, min_refine_score = 3.5;
  // The least-squares steps' gates, in squared scoring gates: wide first (a triple's affine extrapolates
  // poorly far from it), then the scoring gate.
  std::array<double, 5> refine_gate_scales{{9.0, 4.0, 1.0, 1.0, 1.0}};
  // The polish's Cauchy scale (squared: the gate's, over this) and rounds; it gives up at most `polish_loss`
  // of the consensus (of 1, if less) for its fit.
  double polish_scale_divisor = 9.0;
  int polish_rounds = 4;
  double polish_loss = 0.05;
  // The soft refinement: the spread of each step in gates (annealed), the outlier class's weight (relative to a
  // B rock at distance 0 of the same shape) and the largest A x B it runs on (its cost is A x B per step).
  std::array<double, 7> soft_sigmas{{1.5, 1.2, 1.0, 0.8, 0.6, 0.5, 0.5}};
  double soft_outlier = 0.5;
  std::size_t soft_max_pairs = 1024;
  // The fit that goes out is judged among several when A x B is at most this (64 rocks a side).
  std::size_t judged_fit_max_pairs = 4096;

  // --- The stop rule (consensus_stop.cpp) ---
  // The best consensus found again from this many other anchor rocks ends the search.
  int confirmations = 2;
  // A confirmed best must hold at least this many inliers, and the search must have scored COLMAP's number of
  // trials for its inlier ratio at this confidence, before it is believed.
  int min_confirmed_inliers = 5;
  double trials_confidence = 0.99;
  // A consensus that chance would give less often than `chance_level`, over every hypothesis allowed, and of at
  // least `min_beyond_chance_inliers` rocks, is beyond chance; the chance of one rock is capped at `max_chance`.
  double chance_level = 0.05;
  int min_beyond_chance_inliers = 6;
  double max_chance = 0.5;

  // --- The second look (consensus_second_look.cpp) ---
  // Edge pairs it may examine (about 18 rocks a side); beyond, it is skipped.
  double max_edge_pairs = 60000;
  // How far a rock's log box size may stray from the log scale of the edge it ends, and how many of the best
  // similarities are refined into candidates.
  double edge_log_size_gap = 0.4;
  std::size_t edge_candidates = 15;
  // The judgement's weights against the consensus (one well-matched rock ~ 1): IoU of the pairs, and rocks left
  // unpaired although the other picture shows them (A's count more: hand labels hold fewer rocks).
  double weight_iou = 0.2, weight_unpaired_a = 0.1, weight_unpaired_b = 0.05;
  // The judgement's prior on the camera: a twin is rendered from about the real camera, so when the rocks fit
  // two alignments about as well, the one nearer the unmoved camera is likelier. Cost per unit of
  // |log area scale| / 2 (|log s| of a similarity) and per radian of rotation.
  double weight_log_scale = 2.5, weight_rotation = 1.0;
};

inline constexpr ConsensusTuning kTuning{};

}  // namespace ipd::detail
