// Coherent Point Drift, affine variant (Myronenko & Song 2010), as the pycpd package implements it: a
// Gaussian mixture centred on the transformed A centres explains B's centres plus a uniform outlier term;
// EM alternates soft correspondences and a closed-form affine. Rocks are then paired like the consensus
// method (IoU of the aligned boxes, optimal assignment), so the two differ only in the alignment.
#include <fmt/format.h>
#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>

#include "core/geometry/point_grid.h"
#include "core/registration/consensus/shifted_placements.h"
#include "core/registration/consensus/support_measurer.h"
#include "core/registration/pairing.h"
#include "core/registration/registration_frame.h"
#include "core/registration/registration_recorder.h"

namespace ipd::detail {

namespace {

// det / trace^2 of the weighted scatter of A's centres is lambda1 lambda2 / (lambda1 + lambda2)^2: below this
// the centres' minor axis is under about 1e-4 of their major one, a line up to rounding.
constexpr double kSingularBelow = 1e-8;

// EM keeps one soft correspondence per (A, B) rock pair in memory (8 bytes each, plus a step's temporaries of
// the same size): 16 million pairs (4,000 x 4,000 rocks) is 128 MB for the weights, a few times that with the
// temporaries; 20,000 x 20,000 would be 3.2 GB for that matrix alone. Consensus pairs over sparse candidate edges and
// takes layouts that large.
constexpr double kCpdMaxPairs = 16e6;

// EM finds one local optimum and scores no rival, so its confidence is measured as the consensus method's:
// the soft consensus (closeness x box-size agreement, each B rock once) of its alignment against the best of
// the placements most rock pairs agree on under its linear part, each refined. A constant confidence would
// read 1.0 even when it paired 2 of 17 rocks. An alignment that aligns nothing gets 0. A rival that fits better
// replaces EM's answer (`*found`, `*beaten`): an alignment a scored rival beats is never handed out.
// `gate`: consensus_gate, the consensus method's own.
double cpd_confidence(const RegistrationFrame& f, double gate, Affine2* found, bool* beaten,
                      const SearchRecorder& recorder) {
  const Bounds any{1e-3, 1e3, M_PI, 1e6};  // cpd's affine is not held to the consensus bounds
  SupportMeasurer support(f, gate, any);
  const double best = support.score(*found);
  // Under cpd's own linear part and under the identity's (the camera unmoved): on a repetitive layout EM can
  // settle on a shrunk or stretched fit while the unmoved one fits as many rocks (a 3 x 3 block in a 5 x 5 grid
  // at 960 x 600 read 0.33 with only its own shifts as rivals).
  const ShiftedPlacements own = shifted_placements(&support, recorder, f, *found, found->leftCols<2>(), gate, true);
  const ShiftedPlacements unmoved =
      shifted_placements(&support, recorder, f, *found, f.from_image(identity_affine()).leftCols<2>(), gate, true);
  const double rival = std::max(own.rival, unmoved.rival);
  if (rival > best) {
    *found = own.rival >= unmoved.rival ? own.rival_model : unmoved.rival_model;
    *beaten = true;
    // Against EM's alignment and the adopted placement's own rivals (a repetitive layout's other shifts).
    const double others = shifted_placements(&support, recorder, f, *found, found->leftCols<2>(), gate, true).rival;
    return confidence_from_scores(rival, std::max(best, others));
  }
  return confidence_from_scores(best, rival);
}

// The M-step of rigid CPD with scaling (Myronenko & Song 2010, fig. 2) for when the weighted A centres lie on a
// line: the affine across the line is then undetermined (pycpd's inverse of a near-singular matrix gave a
// finite, meaningless affine with entries near 6.5e4 on 12 collinear rocks), a similarity is not.
Eigen::Matrix2d similarity_step(const Eigen::Matrix2d& a, const Eigen::Matrix2d& yy) {
  const Eigen::JacobiSVD<Eigen::Matrix2d> svd(a, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix2d c = Eigen::Matrix2d::Identity();
  c(1, 1) = (svd.matrixU() * svd.matrixV().transpose()).determinant() < 0 ? -1 : 1;
  const Eigen::Matrix2d rot = svd.matrixU() * c * svd.matrixV().transpose();
  const double s = (a.transpose() * rot).trace() / std::max(yy.trace(), 1e-300);
  return s * rot;
}

// Over its pair limit and under a time budget, cpd registers the largest rocks of each side: both labellings see
// the large rocks (the consensus method's coarse pass relies on the same), and EM's cost is the product of the
// two counts. sqrt(2,000 x budget in ms) a side, at least 64 and at most 4,000 (the pair limit): about 2,000
// pair weights per millisecond of budget per EM step, so tens of steps fit the budget on a 2-core machine. The
// subset depends on the budget, never on the clock.
size_t budget_subset(double budget_ms) {
  return static_cast<size_t>(std::clamp(std::sqrt(2000.0 * budget_ms), 64.0, std::sqrt(kCpdMaxPairs)));
}

// The indices of the `count` largest boxes (by area, ties by index), in index order.
std::vector<int> largest_rocks(const std::vector<Box>& boxes, size_t count) {
  std::vector<int> order(boxes.size());
  std::iota(order.begin(), order.end(), 0);
  count = std::min(count, order.size());
  std::partial_sort(order.begin(), order.begin() + static_cast<long>(count), order.end(), [&](int x, int y) {
    const double ax = boxes[x].w * boxes[x].h, ay = boxes[y].w * boxes[y].h;
    return ax != ay ? ax > ay : x < y;
  });
  order.resize(count);
  std::sort(order.begin(), order.end());
  return order;
}

// The rocks EM runs on, as indices into each side of m and n rocks: all of them, or over the pair limit and under a
// time budget the largest of each side (budget_subset; the note says so). Over the limit without a budget: refused.
void rocks_for_em(int m, int n, const std::vector<Box>& boxes_a, const std::vector<Box>& boxes_b,
                  const Deadline& deadline, std::vector<int>* keep_a, std::vector<int>* keep_b, std::string* note) {
  const bool subset = static_cast<double>(m) * n > kCpdMaxPairs && deadline.has_budget();
  if (subset) {
    *keep_a = largest_rocks(boxes_a, budget_subset(deadline.budget_ms()));
    *keep_b = largest_rocks(boxes_b, budget_subset(deadline.budget_ms()));
    add_note(note, fmt::format("{} x {} rocks is over cpd's limit of {} rock pairs: EM ran on the {} and {} "
                               "largest rocks (the time budget's subset), then every rock was paired",
                               m, n, grouped(kCpdMaxPairs), keep_a->size(), keep_b->size()));
  } else if (static_cast<double>(m) * n > kCpdMaxPairs) {
    throw std::invalid_argument(fmt::format(
        "--method cpd: {} x {} rocks is {:.0f} rock pairs, over cpd's limit of {:.0f} (it holds a weight for every "
        "pair in memory); --method consensus registers layouts this large (or give cpd a time budget: it then "
        "registers the largest rocks of each side)",
        m, n, static_cast<double>(m) * n, kCpdMaxPairs));
  } else {
    keep_a->resize(m), keep_b->resize(n);
    std::iota(keep_a->begin(), keep_a->end(), 0);
    std::iota(keep_b->begin(), keep_b->end(), 0);
  }
}

// EM stops when the variance changes by less than this, and takes it as the variance when a step drives it to 0.
constexpr double kTolerance = 1e-10;

// What EM fits: the affine (linear part and translation, acting on row vectors) and the mixture's variance.
struct CpdFit {
  Eigen::Matrix2d lin;
  Eigen::RowVector2d t;
  double sigma2 = 0;
};

// The starting variance: the mean squared distance of every (A, B) pair under the starting affine, per axis.
double initial_sigma2(const Eigen::MatrixXd& x, const Eigen::MatrixXd& y, const CpdFit& fit, const Deadline& deadline) {
  const int m = static_cast<int>(y.rows()), n = static_cast<int>(x.rows());
  double sigma2 = 0;
  // Read every 64 rows: the first mixture width alone weighs every rock pair once.
  for (int i = 0; i < m && !((i & 63) == 0 && deadline.passed()); ++i)
    for (int j = 0; j < n; ++j) sigma2 += (x.row(j) - (y.row(i) * fit.lin.transpose() + fit.t)).squaredNorm();
  sigma2 /= 2.0 * m * n;
  return sigma2;
}

enum class EmStep {
  kStepped,       // the fit moved
  kNothingToFit,  // no weight left, the weight on one centre, or a degenerate affine: the fit stays
  kCut,           // the time budget passed during the E-step: the step is dropped, the fit stays
};

// One EM step: the soft correspondences under the current fit (E), then the closed-form affine and variance (M).
// p_weights: the m x n correspondence weights, reused between steps.
EmStep em_step(const Eigen::MatrixXd& x, const Eigen::MatrixXd& y, double w, const Deadline& deadline,
               Eigen::MatrixXd* p_weights, CpdFit* fit) {
  const int m = static_cast<int>(y.rows()), n = static_cast<int>(x.rows());
  Eigen::MatrixXd& p = *p_weights;
  const double sigma2 = fit->sigma2;
  const Eigen::MatrixXd ty = (y * fit->lin.transpose()).rowwise() + fit->t;
  // One step weighs every pair (tens of milliseconds at the pair limit): the budget is also read every 16 rows,
  // and a step it cuts is dropped, the alignment staying at the last whole step's.
  bool cut = false;
  for (int i = 0; i < m && !cut; ++i) {
    if (deadline.has_budget() && (i & 15) == 0 && deadline.passed()) cut = true;
    for (int j = 0; j < n && !cut; ++j) p(i, j) = std::exp(-(x.row(j) - ty.row(i)).squaredNorm() / (2 * sigma2));
  }
  if (cut) return EmStep::kCut;
  const double c = 2 * M_PI * sigma2 * w / (1 - w) * m / n;
  Eigen::RowVectorXd den = p.colwise().sum().array() + c;
  for (int j = 0; j < n; ++j) p.col(j) /= std::max(den(j), 1e-300);
  const Eigen::VectorXd pt1 = p.colwise().sum().transpose(), p1 = p.rowwise().sum();
  const double np = p1.sum();
  if (!(np > 1e-12)) return EmStep::kNothingToFit;
  const Eigen::RowVector2d mu_x = (pt1.transpose() * x) / np, mu_y = (p1.transpose() * y) / np;
  const Eigen::MatrixXd xh = x.rowwise() - mu_x, yh = y.rowwise() - mu_y;
  const Eigen::Matrix2d a = xh.transpose() * p.transpose() * yh;
  const Eigen::Matrix2d yy = yh.transpose() * p1.asDiagonal() * yh;
  // Singular relative to the centres' own spread (an absolute bound let rounding noise through).
  if (!(yy.trace() > 1e-12)) return EmStep::kNothingToFit;  // the weight sits on one centre: nothing to fit
  const bool on_a_line = !(yy.determinant() > kSingularBelow * yy.trace() * yy.trace());
  const Eigen::Matrix2d b = on_a_line ? similarity_step(a, yy) : Eigen::Matrix2d(a * yy.inverse());
  if (!b.allFinite() || !(std::abs(b.determinant()) > 0)) return EmStep::kNothingToFit;
  fit->lin = b;
  fit->t = mu_x - mu_y * b.transpose();
  const double xx = (xh.array().square().colwise() * pt1.array()).sum();
  fit->sigma2 = (xx - (a * b.transpose()).trace()) / (np * 2);
  if (!(fit->sigma2 > 0)) fit->sigma2 = kTolerance;
  return EmStep::kStepped;
}

// EM from the fit given until it converges, cannot go on, or the iteration, work or time budget ends it (at most
// `allowed` steps of `per_step` point evaluations each). Returns the steps run; sets out->stop and out->work.
int run_em(const RegistrationFrame& f, const Eigen::MatrixXd& x, const Eigen::MatrixXd& y, const RegistrationOptions& o,
           const Deadline& deadline, int allowed, double per_step, SearchRecorder& recorder, CpdFit* fit,
           MethodOutcome* out) {
  Eigen::MatrixXd p(y.rows(), x.rows());
  int it = 0;
  out->stop = StopReason::kMaxTrials;
  double best_sigma = INFINITY;
  for (; it < o.cpd.iterations; ++it) {
    if (it >= allowed) {
      out->stop = StopReason::kWorkBudget;
      break;
    }
    // One EM step on 5,000 rocks a side is tens of milliseconds: the time budget is read before each.
    if (deadline.passed()) {
      out->stop = StopReason::kTimeBudget;
      break;
    }
    out->work += per_step;
    if (!(fit->sigma2 > 1e-12)) {
      out->stop = StopReason::kCannotBeBeaten;
      break;
    }
    const double old = fit->sigma2;
    const EmStep step = em_step(x, y, o.cpd.outlier_weight, deadline, &p, fit);
    if (step == EmStep::kCut) {
      out->work -= per_step;
      out->stop = StopReason::kTimeBudget;
      break;
    }
    if (step == EmStep::kNothingToFit) break;
    if (recorder.recording()) {
      Affine2 affine;
      affine.leftCols<2>() = fit->lin;
      affine.col(2) = fit->t.transpose();
      const double sigma = std::sqrt(fit->sigma2) * f.spread;
      const bool better = sigma < best_sigma;
      best_sigma = std::min(best_sigma, sigma);
      recorder.add_step(TraceStepKind::kIteration, affine, sigma, best_sigma, better);
    }
    if (std::abs(old - fit->sigma2) < kTolerance) {
      out->stop = StopReason::kConverged;
      ++it;
      break;
    }
  }
  return it;
}

}  // namespace

MethodOutcome register_cpd(const RegistrationFrame& f, const std::vector<Box>& boxes_a, const std::vector<Box>& boxes_b,
                           const RegistrationOptions& o, const Deadline& deadline) {
  MethodOutcome out;
  out.affine_normalised = f.from_image(identity_affine());
  if (f.a.empty() || f.b.empty()) {
    out.stop = StopReason::kTooFewPoints;
    out.note = "a side has no rocks: nothing to register";
    return out;
  }
  // Over the pair limit with a time budget: EM on the largest rocks of each side (see budget_subset); without
  // one, refused as before.
  std::vector<int> keep_a, keep_b;
  rocks_for_em(static_cast<int>(f.a.size()), static_cast<int>(f.b.size()), boxes_a, boxes_b, deadline, &keep_a, &keep_b,
               &out.note);
  const int m = static_cast<int>(keep_a.size()), n = static_cast<int>(keep_b.size());
  Eigen::MatrixXd x(n, 2), y(m, 2);
  for (int k = 0; k < n; ++k) x.row(k) = f.b[keep_b[k]].transpose();
  for (int k = 0; k < m; ++k) y.row(k) = f.a[keep_a[k]].transpose();
  CpdFit fit;
  fit.lin = out.affine_normalised.leftCols<2>();
  fit.t = out.affine_normalised.col(2).transpose();
  fit.sigma2 = initial_sigma2(x, y, fit, deadline);
  // Each EM step weighs every (A, B) pair: the work budget bounds the number of steps (at least one).
  const double budget = work_budget(o, f.a.size(), f.b.size()), per_step = static_cast<double>(m) * n;
  const int allowed = static_cast<int>(std::clamp(std::floor(budget / per_step), 1.0, 1e9));
  // Trace: one step per EM iteration; inliers within the consensus gate (consensus_gate), which also measures
  // the confidence. B's spacing reads the deadline (a millisecond on 5,000 rocks): cut short, EM does not start,
  // and the gate, used only after EM, is never read.
  const double gate = consensus_gate(f, o, deadline);
  SearchRecorder recorder(
      f, gate, o.record_trace, [](double s) { return s; }, nullptr);
  const int it = run_em(f, x, y, o, deadline, allowed, per_step, recorder, &fit, &out);
  out.em_iterations = it;
  out.hypotheses = it;
  out.affine_normalised.leftCols<2>() = fit.lin;
  out.affine_normalised.col(2) = fit.t.transpose();
  if (!out.affine_normalised.allFinite()) {
    out.affine_normalised = f.from_image(identity_affine());
    out.note = "EM diverged: identity used";
  }
  out.fit = std::sqrt(std::max(fit.sigma2, 0.0)) * f.spread;  // final mixture width, fraction of image width
  if (out.stop == StopReason::kTimeBudget || deadline.passed()) {
    // The rival placements score whole sets again: with the budget spent EM's answer stands, unjudged.
    out.stop = StopReason::kTimeBudget;
    out.confidence = 0;
    out.unjudged = Ambiguity::kUnchecked;
    add_note(&out.note, "time budget spent: EM's alignment, not judged against rival placements");
  } else {
    out.confidence = cpd_confidence(f, gate, &out.affine_normalised, &out.beaten, recorder);
  }
  if (out.beaten) {
    out.note = "a shifted placement fitted better than EM's alignment: used";
    recorder.add_step(TraceStepKind::kPolish, out.affine_normalised, out.fit, out.fit, true);  // replays end on it
  }
  // The bound named as ipd register names it: a reader can't tell 1,045,000 from a setting otherwise.
  out.trace = recorder.take_trace(fmt::format("{} ({}, {} of {}: the bound for this many rocks)", to_string(out.stop),
                                              count_of(it, "EM iteration", "EM iterations"), grouped(out.work),
                                              count_of(budget, "point evaluation", "point evaluations")));
  pair_final(f.to_image(out.affine_normalised), boxes_a, boxes_b, o, deadline, &out);
  out.inliers = static_cast<int>(out.pairs.size());
  return out;
}

}  // namespace ipd::detail
