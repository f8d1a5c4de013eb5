#include "core/registration/registration.h"

#include <fmt/format.h>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <iterator>
#include <stdexcept>
#include <tuple>

#include "core/geometry/point_grid.h"
#include "core/registration/pairing.h"
#include "core/registration/registration_frame.h"
#include "core/registration/registration_recorder.h"
#include "core/util/number_text.h"

namespace ipd {

const std::vector<RegistrationMethodInfo>& registration_methods() {
  static const std::vector<RegistrationMethodInfo> table = {
      {RegistrationMethod::kConsensus, "consensus",
       "guided hypotheses (identity, voted shifts, neighbour triples), soft consensus with box sizes, LO refinement",
       "hypothesis cap 1000, rotation <= 30 deg, scale 0.5-2, anisotropy <= 2, pairs by aligned-box IoU >= 0.1"},
      {RegistrationMethod::kPaper, "paper",
       "the paper's RANSAC: random triples, all 6 orders, best mean nearest-neighbour distance of K",
       "K = 1000 samples, mutual nearest neighbours within 0.2 of the centres' spread"},
      {RegistrationMethod::kCpd, "cpd", "Coherent Point Drift (affine, as pycpd), then pairs by aligned-box IoU",
       "100 EM iterations, outlier weight 0.2"},
  };
  return table;
}

const RegistrationMethodInfo& method_info(RegistrationMethod m) {
  for (const auto& info : registration_methods())
    if (info.method == m) return info;
  return registration_methods().front();
}

const char* to_string(RegistrationMethod m) { return method_info(m).name; }

bool parse_method(const std::string& name, RegistrationMethod* out) {
  for (const auto& info : registration_methods()) {
    if (name == info.name) {
      *out = info.method;
      return true;
    }
  }
  return false;
}

std::vector<std::string> method_names() {
  std::vector<std::string> names;
  for (const auto& info : registration_methods()) names.emplace_back(info.name);
  return names;
}

std::string method_choices() {
  const auto names = method_names();
  std::string s;
  for (size_t k = 0; k < names.size(); ++k) s += (k == 0 ? "" : k + 1 == names.size() ? " or " : ", ") + names[k];
  return s;
}

std::string methods_help() {
  std::string s;
  for (const auto& info : registration_methods())
    s += fmt::format("{}{}{}: {} ({})", s.empty() ? "" : "\n", info.name,
                     &info == &registration_methods().front() ? " (default)" : "", info.description, info.defaults);
  return s;
}

FitMeasure fit_measure_of(RegistrationMethod m) {
  switch (m) {
    case RegistrationMethod::kPaper:
      return FitMeasure::kMeanDistance;
    case RegistrationMethod::kConsensus:
      return FitMeasure::kSoftInliers;
    case RegistrationMethod::kCpd:
      return FitMeasure::kMixtureWidth;
  }
  return FitMeasure::kNotScored;
}

namespace {
// Each measure's words and direction, in FitMeasure's order: one row to read, not three switches to keep in step.
struct FitMeasureInfo {
  const char* name;  // as printed
  const char* key;   // as --json writes it
  bool lower_is_better;
};
constexpr FitMeasureInfo kFitMeasures[] = {{"not scored", "", false},
                                           {"mean distance", "mean_distance", true},
                                           {"soft inliers", "soft_inliers", false},
                                           {"mixture width", "mixture_width", true}};
static_assert(std::size(kFitMeasures) == static_cast<size_t>(FitMeasure::kMixtureWidth) + 1);
const FitMeasureInfo& info_of(FitMeasure m) { return kFitMeasures[static_cast<size_t>(m)]; }
}  // namespace

bool lower_is_better(FitMeasure m) { return info_of(m).lower_is_better; }
const char* fit_measure_name(FitMeasure m) { return info_of(m).name; }
const char* fit_measure_key(FitMeasure m) { return info_of(m).key; }

std::string fit_text(const FitScore& fit, int decimals) {
  if (!fit.scored()) return fit_measure_name(fit.measure);
  const std::string name = fit_measure_name(fit.measure);
  // A positive value too small for these decimals (cpd's mixture width on an exact fit is 1e-9) is said to be so:
  // "0.0000" would read as an underflow, or as a width of exactly nothing.
  const std::string zero = fixed_decimals(0.0, decimals);
  if (fit.value > 0 && fixed_decimals(fit.value, decimals) == zero)
    return name + " below " + fixed_decimals(std::pow(10.0, -decimals), decimals);
  return name + " " + fixed_decimals(fit.value, decimals);
}

const char* ambiguity_reason(Ambiguity a) {
  switch (a) {
    case Ambiguity::kNone:
      return "";
    case Ambiguity::kRival:
      return kAmbiguousReason;
    case Ambiguity::kNoSupport:
      return "the alignment pairs no rock, so nothing supports it";
    case Ambiguity::kFewPairs:
      return "fewer than 3 rocks are paired: too few to fix an alignment, another fits as well";
    case Ambiguity::kDegenerate:
      return "the paired rocks lie almost on one line (or the alignment squashes them onto one), so the alignment "
             "across it is a guess";
    case Ambiguity::kBeaten:
      return "the search's own best was beaten by a placement scored after it (that one is used), so the search "
             "may have missed a better one";
    case Ambiguity::kUnchecked:
      return "the time budget ended before the alignment used was compared with another, so nothing singles it "
             "out";
    case Ambiguity::kNoPlausible:
      return "no alignment within the scale, rotation and anisotropy bounds was found (the identity is used), so "
             "nothing singles it out";
  }
  return "";
}

std::string ConsensusParams::validate() const {
  if (max_hypotheses < 1) return fmt::format("consensus.max_hypotheses must be at least 1, got {}", max_hypotheses);
  if (!(min_scale > 0) || !(max_scale >= min_scale) || !std::isfinite(max_scale))
    return fmt::format("scale bounds must satisfy 0 < min_scale <= max_scale, got [{}, {}]", min_scale, max_scale);
  if (!(max_rotation_deg > 0) || max_rotation_deg > 180)
    return fmt::format("max_rotation_deg must be in (0, 180], got {}", max_rotation_deg);
  if (!(max_anisotropy >= 1) || !std::isfinite(max_anisotropy))
    return fmt::format("max_anisotropy must be a number >= 1, got {}", max_anisotropy);
  if (inlier_gate && (!(*inlier_gate > 0) || !std::isfinite(*inlier_gate)))
    return fmt::format("inlier_gate must be > 0 when set (unset: from the rock spacing), got {}", *inlier_gate);
  return {};
}

std::string PaperParams::validate() const {
  if (samples < 1) return fmt::format("paper.samples must be at least 1, got {}", samples);
  if (!(pair_gate > 0) || !std::isfinite(pair_gate)) return fmt::format("pair_gate must be > 0, got {}", pair_gate);
  return {};
}

std::string CpdParams::validate() const {
  if (iterations < 1) return fmt::format("cpd.iterations must be at least 1, got {}", iterations);
  if (!(outlier_weight >= 0 && outlier_weight < 1))
    return fmt::format("cpd.outlier_weight must be in [0, 1), got {}", outlier_weight);
  return {};
}

int& RegistrationOptions::trials() {
  switch (method) {
    case RegistrationMethod::kPaper:
      return paper.samples;
    case RegistrationMethod::kCpd:
      return cpd.iterations;
    case RegistrationMethod::kConsensus:
      break;
  }
  return consensus.max_hypotheses;
}

int RegistrationOptions::trials() const { return const_cast<RegistrationOptions*>(this)->trials(); }

std::string RegistrationOptions::validate() const {
  if (time_budget_ms && (!(*time_budget_ms > 0) || !std::isfinite(*time_budget_ms)))
    return fmt::format("time_budget_ms must be > 0 when set (unset: no limit), got {}", *time_budget_ms);
  if (aspect && (!(*aspect > 0) || !std::isfinite(*aspect)))
    return fmt::format("aspect must be a positive number, got {}", *aspect);
  if (!(min_pair_iou >= 0 && min_pair_iou < 1))
    return fmt::format("min_pair_iou must be in [0, 1), got {}", min_pair_iou);
  if (!(pair_noise_floor >= 0 && pair_noise_floor < 1))
    return fmt::format("pair_noise_floor must be in [0, 1) of the image width, got {}", pair_noise_floor);
  if (!(pair_max_size_ratio >= 1 && std::isfinite(pair_max_size_ratio)))
    return fmt::format("pair_max_size_ratio must be a finite number >= 1, got {}", pair_max_size_ratio);
  if (work_budget && (!(*work_budget > 0) || !std::isfinite(*work_budget)))
    return fmt::format("work_budget must be > 0 when set (unset: automatic), got {}", *work_budget);
  for (const std::string& problem : {consensus.validate(), paper.validate(), cpd.validate()})
    if (!problem.empty()) return problem;
  return {};
}

void RegistrationOptions::check() const {
  const std::string problem = validate();
  if (!problem.empty()) throw std::invalid_argument("registration options: " + problem);
}

namespace detail {

RegistrationFrame::RegistrationFrame(const std::vector<Box>& boxes_a, const std::vector<Box>& boxes_b, double asp)
    : aspect(asp) {
  auto iso = [&](const Box& bx) { return Eigen::Vector2d(bx.cx, bx.cy / aspect); };
  auto centroid = [&](const std::vector<Box>& v) {
    Eigen::Vector2d c(0, 0);
    for (const auto& bx : v) c += iso(bx);
    return v.empty() ? c : Eigen::Vector2d(c / static_cast<double>(v.size()));
  };
  centroid_a = centroid(boxes_a);
  centroid_b = centroid(boxes_b);
  double ss = 0;
  size_t n = 0;
  for (const auto& bx : boxes_a) ss += (iso(bx) - centroid_a).squaredNorm(), ++n;
  for (const auto& bx : boxes_b) ss += (iso(bx) - centroid_b).squaredNorm(), ++n;
  spread = n > 0 ? std::sqrt(ss / static_cast<double>(n)) : 1.0;
  if (!(spread > 0) || !std::isfinite(spread)) spread = 1.0;
  for (const auto& bx : boxes_a) {
    a.push_back((iso(bx) - centroid_a) / spread);
    size_a.emplace_back(bx.w / spread, bx.h / aspect / spread);
  }
  for (const auto& bx : boxes_b) {
    b.push_back((iso(bx) - centroid_b) / spread);
    size_b.emplace_back(bx.w / spread, bx.h / aspect / spread);
  }
}

namespace {
// Flatter than this (minor over major axis, or smallest over largest singular value) is a line: labelling noise
// alone decides the alignment across it. A camera misalignment keeps singular values within a factor of 2.
constexpr double kFlatBelow = 0.02;
}  // namespace

double flatness(const std::vector<Eigen::Vector2d>& p) {
  if (p.size() < 2) return 0;
  Eigen::Vector2d mean(0, 0);
  for (const auto& q : p) mean += q;
  mean /= static_cast<double>(p.size());
  double sxx = 0, sxy = 0, syy = 0;
  for (const auto& q : p) {
    const Eigen::Vector2d d = q - mean;
    sxx += d.x() * d.x(), sxy += d.x() * d.y(), syy += d.y() * d.y();
  }
  const double m = 0.5 * (sxx + syy), r = std::hypot(0.5 * (sxx - syy), sxy);
  if (!(m + r > 0)) return 0;  // every point in one place
  return std::sqrt(std::max(m - r, 0.0) / (m + r));
}

Ambiguity judge_answer(const RegistrationFrame& f, const RockPairs& pairs, const Affine2& normalised,
                       const MethodOutcome& out, double* confidence) {
  if (out.unjudged != Ambiguity::kNone) {
    *confidence = 0;  // the method's own reason first: however many rocks it pairs, nothing was weighed against it
    return out.unjudged;
  }
  Ambiguity a = Ambiguity::kNone;
  if (pairs.empty()) {
    a = Ambiguity::kNoSupport;
  } else if (pairs.size() < 3) {
    a = Ambiguity::kFewPairs;
  } else {
    // Singular values of the linear part, q + r and |q - r| (as Bounds computes them), in units of the layout's
    // spread: the frame is normalised by it.
    const Eigen::Matrix2d l = normalised.leftCols<2>();
    const double e = 0.5 * (l(0, 0) + l(1, 1)), g = 0.5 * (l(0, 0) - l(1, 1)), h = 0.5 * (l(1, 0) + l(0, 1)),
                 k = 0.5 * (l(1, 0) - l(0, 1));
    const double q = std::hypot(e, k), r = std::hypot(g, h);
    std::vector<Eigen::Vector2d> paired_a, paired_b;
    for (const auto& [i, j] : pairs) paired_a.push_back(f.a[i]), paired_b.push_back(f.b[j]);
    const bool squashed = !(std::abs(q - r) >= kFlatBelow * std::max(1.0, q + r));  // |q - r|: a mirror's too
    if (squashed || std::min(flatness(paired_a), flatness(paired_b)) < kFlatBelow) a = Ambiguity::kDegenerate;
  }
  if (a != Ambiguity::kNone) {
    *confidence = 0;  // no placement is better than another: nothing pins it
    return a;
  }
  if (out.beaten) return Ambiguity::kBeaten;
  return *confidence < kAmbiguousBelow ? Ambiguity::kRival : Ambiguity::kNone;
}

double work_budget(const RegistrationOptions& o, size_t na, size_t nb) {
  if (o.work_budget) return *o.work_budget;
  const double n = static_cast<double>(na + nb);
  return 1e6 + 300.0 * n * std::log2(n + 2);
}

double median_nn_distance(const std::vector<Eigen::Vector2d>& p, const Deadline* deadline) {
  if (p.size() < 2) return 0;
  const PointGrid g(p);
  std::vector<double> d;
  std::vector<int> near;
  // The first disc is about the mean spacing of a layout spread over its bounding box, so most points find their
  // nearest other point in one or two queries (from 1e-9 it took a dozen: most of the set-up on 5,000 rocks). Any
  // start gives the same distance: whatever is closer than a disc's radius is inside it.
  Eigen::Vector2d lo = p[0], hi = p[0];
  for (const auto& q : p) lo = lo.cwiseMin(q), hi = hi.cwiseMax(q);
  const double spacing = std::sqrt(std::max((hi - lo).prod(), 0.0) / static_cast<double>(p.size()));
  const double first = spacing > 1e-9 && std::isfinite(spacing) ? spacing : 1e-9;
  for (size_t i = 0; i < p.size(); ++i) {
    if (deadline != nullptr && (i & 255) == 0 && deadline->passed()) break;
    // nearest other point: widen the search until it holds one besides the point itself
    double best = INFINITY;
    for (double r = first; best == INFINITY && r < 1e6; r *= 4) {
      g.within(p[i], r, &near);
      for (int j : near)
        if (j != static_cast<int>(i)) best = std::min(best, (p[j] - p[i]).norm());
      if (best == INFINITY && near.size() > 64) break;  // many duplicates: zero spacing
    }
    if (best == INFINITY) best = 0;
    d.push_back(best);
  }
  if (d.empty()) return 0;  // cut short before the first point
  std::nth_element(d.begin(), d.begin() + d.size() / 2, d.end());
  return d[d.size() / 2];
}

std::string grouped(double n) { return grouped_thousands(std::llround(n)); }

std::string count_of(double n, const char* singular, const char* plural) {
  return grouped(n) + " " + (std::llround(n) == 1 ? singular : plural);
}

std::string describe_stop(StopReason stop, int samples, int hypotheses, double work, double budget) {
  std::string s = to_string(stop);
  const std::string sampled = count_of(samples, "trial", "trials");  // as --trials and every report name them
  const std::string tried = count_of(hypotheses, "hypothesis", "hypotheses");
  switch (stop) {
    case StopReason::kWorkBudget:
      return fmt::format("{} ({} of {}; {}, {})", s, grouped(work),
                         count_of(budget, "point evaluation", "point evaluations"), sampled, tried);
    case StopReason::kNotRun:
    case StopReason::kTooFewPoints:
    case StopReason::kIdenticalLayouts:
      return s;
    default:
      return fmt::format("{} ({}, {}, {})", s, sampled, tried, count_of(work, "point evaluation", "point evaluations"));
  }
}

namespace {
// image -> isotropic: S = diag(1, 1/aspect); set A -> normalised: (p - ca)/spread.
Affine2 image_to_normalised(const Eigen::Vector2d& centroid, double aspect, double spread) {
  Affine2 m;
  m << 1.0 / spread, 0, -centroid.x() / spread, 0, 1.0 / (aspect * spread), -centroid.y() / spread;
  return m;
}
}  // namespace

Affine2 RegistrationFrame::to_image(const Affine2& m) const {
  Affine2 to_a = image_to_normalised(centroid_a, aspect, spread),
          to_b = image_to_normalised(centroid_b, aspect, spread);
  Affine2 from_b;
  invert(to_b, &from_b);
  return compose(from_b, compose(m, to_a));
}

Affine2 RegistrationFrame::from_image(const Affine2& m) const {
  Affine2 to_a = image_to_normalised(centroid_a, aspect, spread),
          to_b = image_to_normalised(centroid_b, aspect, spread);
  Affine2 from_a;
  invert(to_a, &from_a);
  return compose(to_b, compose(m, from_a));
}

}  // namespace detail

namespace {
// A twin rendered from the same labels has exactly the same GT boxes: found by sorting both sides
// (O(n log n)), it gets the identity and its pairs by aligned-box IoU without a search, whatever the method
// (a search on thousands of identical rocks costs seconds and can settle on a rival alignment).
bool identical_layouts(const std::vector<Box>& a, const std::vector<Box>& b) {
  if (a.size() != b.size() || a.size() < 3) return false;
  // First a sum of the boxes' bit patterns, mixed: equal multisets give equal sums in any order, so different
  // layouts are told apart in one pass before the sort (which alone costs a millisecond on 5,000 rocks).
  auto mixed = [](const Box& x) {
    std::uint64_t h = 0;
    for (double v : {x.cx, x.cy, x.w, x.h}) {
      std::uint64_t bits;
      std::memcpy(&bits, &v, sizeof bits);
      h = (h ^ bits) * 0x9E3779B97F4A7C15ull;
      h ^= h >> 29;
    }
    return h;
  };
  std::uint64_t sum_a = 0, sum_b = 0;
  for (const Box& x : a) sum_a += mixed(x);
  for (const Box& x : b) sum_b += mixed(x);
  if (sum_a != sum_b) return false;
  auto key = [](const Box& x) { return std::make_tuple(x.cx, x.cy, x.w, x.h); };
  std::vector<std::tuple<double, double, double, double>> ka, kb;
  ka.reserve(a.size()), kb.reserve(b.size());
  for (const Box& x : a) ka.push_back(key(x));
  for (const Box& x : b) kb.push_back(key(x));
  std::sort(ka.begin(), ka.end());
  std::sort(kb.begin(), kb.end());
  return ka == kb;
}
}  // namespace

RegistrationReport register_rocks(const std::vector<Box>& a, const std::vector<Box>& b,
                                  const RegistrationOptions& options) {
  options.check();
  return detail::register_rocks_until(a, b, options, Deadline(options.time_budget_ms.value_or(0)));
}

namespace detail {

// What the final pairing may cost per rock (A's and B's), kept back from the budget for it: greedy pairing took
// 0.9 ms for 4,500 + 4,231 rocks on the 2-core machine (about 0.1 us a rock), and the last stage before it can
// overrun by about as much again (docs/benchmarks.md, `ipd bench budget`).
constexpr double kPairingReserveMs = 0.0003;

void add_note(std::string* note, const std::string& sentence) {
  if (!sentence.empty()) *note += (note->empty() ? "" : "; ") + sentence;
}

void pair_final(const Affine2& image_affine, const std::vector<Box>& a, const std::vector<Box>& b,
                const RegistrationOptions& o, const Deadline& deadline, MethodOutcome* out) {
  const auto start = std::chrono::steady_clock::now();
  bool greedy = false;
  out->pairs = deadline.has_budget()
                   ? pair_aligned_boxes_within(image_affine, a, b, pairing_rule(o), deadline.whole(), &greedy)
                   : pair_aligned_boxes(image_affine, a, b, pairing_rule(o));
  out->pairing_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  if (greedy) {
    add_note(&out->note,
             "time budget spent before the rocks were paired: paired greedily (heaviest overlap first), "
             "not by the optimal assignment");
    out->stop = StopReason::kTimeBudget;
  }
}

RegistrationReport register_rocks_until(const std::vector<Box>& a, const std::vector<Box>& b,
                                        const RegistrationOptions& options, const Deadline& whole) {
  options.check();
  // The stages before the final pairing end kPairingReserveMs per rock before the budget (at most half of it), so
  // the pairing, greedy at worst, still ends within the budget.
  const Deadline deadline = whole.keeping_back(kPairingReserveMs * static_cast<double>(a.size() + b.size()));
  const auto start = std::chrono::steady_clock::now();
  const detail::RegistrationFrame frame(a, b, options.aspect_ratio());
  detail::MethodOutcome out;
  const bool identical = identical_layouts(a, b);
  if (identical) {
    out.affine_normalised = frame.from_image(identity_affine());
    pair_final(identity_affine(), a, b, options, deadline, &out);
    out.inliers = static_cast<int>(a.size());  // every centre sits on its copy
    if (out.stop != StopReason::kTimeBudget) out.stop = StopReason::kIdenticalLayouts;
    out.confidence = 1.0;
  } else {
    switch (options.method) {
      case RegistrationMethod::kPaper:
        out = detail::register_paper(frame, options, deadline);
        break;
      case RegistrationMethod::kConsensus:
        out = detail::register_consensus(frame, a, b, options, deadline);
        break;
      case RegistrationMethod::kCpd:
        out = detail::register_cpd(frame, a, b, options, deadline);
        break;
    }
  }
  RegistrationReport r;
  r.method = options.method;
  // Identical layouts: exactly the identity (the round trip through the normalised frame would round it).
  r.affine = identical ? identity_affine() : frame.to_image(out.affine_normalised);
  if (!r.affine.allFinite()) {
    r.affine = identity_affine();
    out.note += (out.note.empty() ? "" : "; ") + std::string("non-finite affine replaced by identity");
  }
  r.pairs = std::move(out.pairs);
  // Registration may align every box, but a rock pairs only with a rock of its class (the paper's mutual nearest
  // centres know no class; pair_weight already keeps the overlap rules within one).
  r.pairs.erase(std::remove_if(r.pairs.begin(), r.pairs.end(),
                               [&](const std::pair<int, int>& p) { return a[p.first].cls != b[p.second].cls; }),
                r.pairs.end());
  std::sort(r.pairs.begin(), r.pairs.end());
  r.samples = out.samples;
  r.em_iterations = out.em_iterations;
  r.hypotheses = out.hypotheses;
  r.inliers = out.inliers;
  // With no hypothesis scored a fit of 0 would read as paper's perfect fit: it is not scored instead.
  if (out.hypotheses > 0) r.fit = {fit_measure_of(options.method), out.fit};
  r.stop = out.stop;
  r.note = std::move(out.note);
  r.confidence = out.confidence;
  r.ambiguity = detail::judge_answer(frame, r.pairs, frame.from_image(r.affine), out, &r.confidence);
  r.ambiguous = r.ambiguity != Ambiguity::kNone;
  r.work = out.work;
  r.pairing_ms = out.pairing_ms;
  r.work_budget = detail::work_budget(options, a.size(), b.size());
  r.trace = std::move(out.trace);
  if (options.record_trace && r.trace.stop.empty()) r.trace.stop = to_string(r.stop);
  r.elapsed_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return r;
}

}  // namespace detail

}  // namespace ipd
