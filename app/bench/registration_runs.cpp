// The measurements behind `ipd bench registration` (see registration_runs.h).
#include "app/bench/registration_runs.h"

#include <fmt/format.h>

#include <unistd.h>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <opencv2/imgproc.hpp>

#include <nlohmann/json.hpp>

#include "app/bench/fold_benchmark.h"
#include "core/picture/picture_codec.h"
#include "core/registration/pairing.h"
#include "core/util/atomic_file.h"
#include "core/util/errors.h"

namespace fs = std::filesystem;

namespace ipd::cli {

namespace {

double percentile(std::vector<double> v, double q) {
  if (v.empty()) return 0;
  const size_t k = std::min(v.size() - 1, static_cast<size_t>(q * static_cast<double>(v.size())));
  std::nth_element(v.begin(), v.begin() + k, v.end());
  return v[k];
}

// The default options' pairing rule in an image of this aspect (what every method pairs by).
RegistrationOptions default_options(double aspect) {
  RegistrationOptions o;
  o.aspect = aspect;
  return o;
}
PairingRule default_rule(double aspect) { return pairing_rule(default_options(aspect)); }

// Adds one case's pair F1 and transform error to a row; finish_row averages.
void score_case(const RegistrationCase& c, const RockPairs& pairs, const Affine2& affine, double aspect, BenchRow* row,
                std::vector<double>* terr) {
  const PairScore s = score_pairs(pairs, c.truth);
  row->f1 += s.f1;
  row->precision += s.precision;
  row->recall += s.recall;
  terr->push_back(transform_error(affine, c.truth_affine, c.a, aspect));
}

void finish_row(const std::vector<double>& terr, BenchRow* row) {
  const double n = static_cast<double>(std::max<size_t>(1, terr.size()));
  row->f1 /= n;
  row->precision /= n;
  row->recall /= n;
  row->terr_median = percentile(terr, 0.5);
  row->terr_p90 = percentile(terr, 0.9);
}

}  // namespace

BenchRow run_config(const std::vector<RegistrationCase>& cases, const std::string& regime, const MethodConfig& c,
                    double aspect) {
  RegistrationOptions o;
  o.method = c.method;
  o.aspect = aspect;
  o.trials() = c.budget;
  BenchRow row;
  row.regime = regime;
  row.method = to_string(c.method);
  row.config = c;
  row.cases = static_cast<int>(cases.size());
  std::vector<double> terr, ms;
  std::vector<RegistrationReport> reports;
  reports.reserve(cases.size());
  for (const auto& k : cases) {
    const auto start = std::chrono::steady_clock::now();
    reports.push_back(register_rocks(k.a, k.b, o));
    ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
  }
  for (double x : ms) row.ms_per_pair += x / static_cast<double>(cases.size());
  row.ms_median = percentile(ms, 0.5);
  int flagged = 0;
  for (size_t i = 0; i < cases.size(); ++i) {
    const double before = row.f1;
    score_case(cases[i], reports[i].pairs, reports[i].affine, aspect, &row, &terr);
    if (reports[i].ambiguous) ++flagged, row.f1_ambiguous += row.f1 - before;
  }
  row.ambiguous = static_cast<double>(flagged) / static_cast<double>(cases.size());
  row.f1_ambiguous = flagged ? row.f1_ambiguous / flagged : 0;
  finish_row(terr, &row);
  return row;
}

// The default method's cases below F1 1, one line each: what the case holds and what went wrong.
void list_failures(const std::vector<RegistrationCase>& cases, const std::string& regime, double aspect) {
  RegistrationOptions o;
  o.aspect = aspect;
  int failed = 0, flagged_failed = 0, flagged_ok = 0, wrong = 0, flagged_wrong = 0;
  for (size_t i = 0; i < cases.size(); ++i) {
    const auto& c = cases[i];
    const auto r = register_rocks(c.a, c.b, o);
    const double f1 = score_pairs(r.pairs, c.truth).f1,
                 ceiling = score_pairs(pairs_under_true_affine(c, o), c.truth).f1;
    if (f1 >= ceiling) {
      flagged_ok += r.ambiguous;
      continue;
    }
    ++failed;
    flagged_failed += r.ambiguous;
    if (f1 < 0.8) ++wrong, flagged_wrong += r.ambiguous;
    const Eigen::Matrix2d l = c.truth_affine.leftCols<2>();
    const double deg = std::atan2(l(1, 0) * aspect - l(0, 1) / aspect, l(0, 0) + l(1, 1)) * 180 / M_PI;
    fmt::print(
        "  {} case {:>3}: {:>2} / {:>2} rocks, {:>2} true pairs, rotation {:>5.1f} deg; F1 {:.3f} (ceiling {:.3f}), "
        "terr {:.2f}%, confidence {:.2f}{}, {} hypotheses, stopped: {}  [{}]\n",
        regime, i, c.a.size(), c.b.size(), c.truth.size(), deg, f1, ceiling,
        100 * transform_error(r.affine, c.truth_affine, c.a, aspect), r.confidence, r.ambiguous ? " AMBIGUOUS" : "",
        r.hypotheses, to_string(r.stop), c.source);
  }
  fmt::print(
      "  {}: {} of {} cases below the ceiling ({} flagged ambiguous), {} of them below F1 0.8 ({} flagged); "
      "{} cases at the ceiling flagged\n",
      regime, failed, cases.size(), flagged_failed, wrong, flagged_wrong, flagged_ok);
}

// What no method can beat on these cases: the transform error of least squares on the true pairs (the
// floor) and the pair F1 of the true affine with our pairing (the ceiling).
std::vector<BenchRow> bounds_rows(const std::vector<RegistrationCase>& cases, const std::string& regime,
                                  double aspect) {
  BenchRow floor, ceiling;
  floor.regime = ceiling.regime = regime;
  floor.method = "floor";
  ceiling.method = "ceiling";
  floor.config = ceiling.config = {RegistrationMethod::kConsensus, 0};
  floor.cases = ceiling.cases = static_cast<int>(cases.size());
  std::vector<double> terr_floor, terr_ceiling;
  BenchRow unused;
  for (const auto& c : cases) {
    Affine2 ls;
    if (!least_squares_on_truth(c, &ls)) ls = identity_affine();
    score_case(c, pair_aligned_boxes(ls, c.a, c.b, default_rule(aspect)), ls, aspect, &floor, &terr_floor);
    score_case(c, pairs_under_true_affine(c, default_options(aspect)), c.truth_affine, aspect, &ceiling, &terr_ceiling);
  }
  finish_row(terr_floor, &floor);
  finish_row(terr_ceiling, &ceiling);
  return {floor, ceiling};
}

// The Python baseline: app/bench/pycpd_reference.py (a numpy port of pycpd's affine CPD) on the same cases, its
// affines paired and scored exactly like ours. Its time is what pycpd's register() takes, measured in Python.
BenchRow run_pycpd(const std::vector<RegistrationCase>& cases, const std::string& regime, const std::string& script,
                   double aspect) {
  const fs::path dir = fs::temp_directory_path() / fmt::format("ipd-pycpd-{}", ::getpid());
  fs::create_directories(dir);
  nlohmann::json in = nlohmann::json::array();
  for (const auto& c : cases) {
    nlohmann::json a = nlohmann::json::array(), b = nlohmann::json::array();
    for (const auto& x : c.a) a.push_back({x.cx, x.cy / aspect});
    for (const auto& x : c.b) b.push_back({x.cx, x.cy / aspect});
    in.push_back({{"a", a}, {"b", b}});
  }
  write_file_atomically((dir / "cases.json").string(), in.dump());
  const std::string cmd = fmt::format("/usr/bin/python3 '{}' '{}' '{}'", script, (dir / "cases.json").string(),
                                      (dir / "out.json").string());
  if (std::system(cmd.c_str()) != 0) throw StudyError("the pycpd reference failed: " + cmd);
  const auto out = nlohmann::json::parse(read_file((dir / "out.json").string()));
  fs::remove_all(dir);
  BenchRow row;
  row.regime = regime;
  row.method = "pycpd-numpy";
  row.config = {RegistrationMethod::kCpd, 100};
  row.cases = static_cast<int>(cases.size());
  std::vector<double> terr, ms;
  const Eigen::Matrix2d s = Eigen::Vector2d(1, 1 / aspect).asDiagonal(), si = Eigen::Vector2d(1, aspect).asDiagonal();
  for (size_t i = 0; i < cases.size(); ++i) {
    const auto& o = out[i];
    Affine2 iso;
    iso << o["B"][0][0].get<double>(), o["B"][0][1].get<double>(), o["t"][0].get<double>(), o["B"][1][0].get<double>(),
        o["B"][1][1].get<double>(), o["t"][1].get<double>();
    Affine2 m;  // back to normalised image coordinates
    m.leftCols<2>() = si * iso.leftCols<2>() * s;
    m.col(2) = si * iso.col(2);
    score_case(cases[i], pair_aligned_boxes(m, cases[i].a, cases[i].b, default_rule(aspect)), m, aspect, &row, &terr);
    row.ms_per_pair += o["ms"].get<double>();
    ms.push_back(o["ms"].get<double>());
  }
  row.ms_per_pair /= cases.size();
  row.ms_median = percentile(ms, 0.5);
  finish_row(terr, &row);
  return row;
}

// The speed goal in the fold run: the default method and the pycpd port on the same validation cases (every
// fold's held-out terrains), medians of ms per pair and their ratio.
void compare_with_pycpd(const std::vector<LabelPair>& pairs, const std::vector<MisalignmentRange>& tiers, int cases,
                        std::uint64_t seed, const std::string& script, double W, double H) {
  const double aspect = W / H;
  fmt::print("\nSpeed on the validation cases of every fold (same cases for both):\n");
  for (const auto& tier : tiers) {
    std::vector<RegistrationCase> list;
    for (const auto& fold : benchmark_folds()) {
      auto more = make_cases(fold_pairs(pairs, fold, true), tier, cases, seed, W, H);
      list.insert(list.end(), std::make_move_iterator(more.begin()), std::make_move_iterator(more.end()));
    }
    const BenchRow ours =
        run_config(list, tier.name, {RegistrationMethod::kConsensus, RegistrationOptions().trials()}, aspect);
    const BenchRow theirs = run_pycpd(list, tier.name, script, aspect);
    const double ratio = ours.ms_median > 0 ? theirs.ms_median / ours.ms_median : 0;
    fmt::print(
        "  {}: {} cases; consensus median {:.3f} ms/pair (F1 {:.4f}), pycpd-numpy median {:.3f} ms/pair (F1 {:.4f}): "
        "{:.0f}x (goal >= 10x: {})\n",
        tier.name, list.size(), ours.ms_median, ours.f1, theirs.ms_median, theirs.f1, ratio,
        ratio >= 10 ? "met" : "NOT met");
  }
}

// Time of the default method against the rock count (synthetic layouts, small misalignment): the goal is no
// worse than n log n up to 500 a side.
void print_scaling(double aspect, std::uint64_t seed) {
  fmt::print("default method against the rock count (synthetic layouts, small misalignment, 20 cases each):\n");
  fmt::print("{:>6} {:>10} {:>8} {:>22} {:>12} {:>12}\n", "rocks", "ms median", "F1", "ms / (n log2 n), n=25: 1",
             "hypotheses", "work");
  double unit = 0;
  for (int n : {25, 50, 100, 200, 500}) {
    std::vector<double> ms, hypotheses, work;
    double f1 = 0;
    const int count = 20;
    for (int k = 0; k < count; ++k) {
      const auto c = make_case(synthetic_label_pair(n, seed * 1000 + k), small_misalignment(), seed * 7 + k);
      RegistrationOptions o;
      o.aspect = aspect;
      const auto start = std::chrono::steady_clock::now();
      const auto r = register_rocks(c.a, c.b, o);
      ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
      f1 += score_pairs(r.pairs, c.truth).f1 / count;
      hypotheses.push_back(r.hypotheses);
      work.push_back(r.work);
    }
    const double med = percentile(ms, 0.5), per = med / (n * std::log2(static_cast<double>(n)));
    if (unit == 0) unit = per;
    fmt::print("{:>6} {:>10.3f} {:>8.4f} {:>22.2f} {:>12.0f} {:>12.3g}\n", n, med, f1, per / unit,
               percentile(hypotheses, 0.5), percentile(work, 0.5));
  }
}

// Every method on 5,000 rocks a side with its default settings: the work budget must end each within
// seconds, saying why it stopped.
void print_work_bound(std::uint64_t seed) {
  const auto c = make_case(synthetic_label_pair(5000, seed), small_misalignment(), seed);
  fmt::print("\n{} vs {} rocks, default settings:\n", c.a.size(), c.b.size());
  for (auto m : {RegistrationMethod::kConsensus, RegistrationMethod::kPaper, RegistrationMethod::kCpd}) {
    RegistrationOptions o;
    o.method = m;
    const auto r = register_rocks(c.a, c.b, o);
    fmt::print("  {:<10} {:>9.1f} ms  F1 {:.3f}  work {:.3g} of {:.3g}; stopped: {}\n", to_string(m), r.elapsed_ms,
               score_pairs(r.pairs, c.truth).f1, r.work, r.work_budget, to_string(r.stop));
  }
}

void plot_f1_against_time(const std::vector<BenchRow>& rows, const std::string& path) {
  const int panel_w = 560, W = 70 + 3 * (panel_w + 40), H = 620, top = 60, plot_h = 480;
  cv::Mat img(H, W, CV_8UC3, cv::Scalar(255, 255, 255));
  const cv::Scalar colours[] = {{200, 80, 20}, {40, 40, 220}, {40, 160, 40}, {120, 120, 120}};
  const char* const names[] = {"paper", "consensus", "cpd", "pycpd-numpy"};
  const double lo = -2.5, hi = 2.5;  // log10 ms
  int panel = 0;
  for (const std::string regime : {"small", "large", "unequal"}) {
    const int x0 = 70 + panel * (panel_w + 40), y0 = top;
    cv::rectangle(img, {x0, y0, panel_w - 60, plot_h}, cv::Scalar(0, 0, 0), 1);
    auto px = [&](double ms, double f1) {
      const double lx = std::clamp(std::log10(std::max(ms, 1e-3)), lo, hi);
      return cv::Point(x0 + static_cast<int>((lx - lo) / (hi - lo) * (panel_w - 60)),
                       y0 + static_cast<int>((1 - f1) * plot_h));
    };
    for (int e = -2; e <= 2; ++e) {
      const cv::Point p = px(std::pow(10, e), 0);
      cv::line(img, {p.x, y0}, {p.x, y0 + plot_h}, cv::Scalar(220, 220, 220));
      cv::putText(img, fmt::format("{}", std::pow(10.0, e)), {p.x - 12, y0 + plot_h + 20}, cv::FONT_HERSHEY_SIMPLEX,
                  0.45, cv::Scalar(0, 0, 0));
    }
    for (int f = 0; f <= 10; f += 2) {
      const cv::Point p = px(1, f / 10.0);
      cv::line(img, {x0, p.y}, {x0 + panel_w - 60, p.y}, cv::Scalar(220, 220, 220));
      cv::putText(img, fmt::format("{:.1f}", f / 10.0), {x0 - 35, p.y + 5}, cv::FONT_HERSHEY_SIMPLEX, 0.45,
                  cv::Scalar(0, 0, 0));
    }
    cv::putText(img, regime + ": pair F1 vs ms per image pair (log)", {x0, y0 - 15}, cv::FONT_HERSHEY_SIMPLEX, 0.6,
                cv::Scalar(0, 0, 0), 1, cv::LINE_AA);
    for (int m = 0; m < 4; ++m) {
      std::vector<cv::Point> pts;
      for (const auto& r : rows)
        if (r.regime == regime && r.method == names[m]) pts.push_back(px(r.ms_per_pair, r.f1));
      if (pts.empty()) continue;
      for (size_t k = 0; k < pts.size(); ++k) {
        cv::circle(img, pts[k], 5, colours[m], cv::FILLED, cv::LINE_AA);
        if (k) cv::line(img, pts[k - 1], pts[k], colours[m], 2, cv::LINE_AA);
      }
      cv::putText(img, names[m], {x0 + 10, y0 + plot_h - 15 - 22 * m}, cv::FONT_HERSHEY_SIMPLEX, 0.6, colours[m], 2,
                  cv::LINE_AA);
    }
    ++panel;
  }
  std::vector<uchar> png;
  encode_picture(".png", img, &png);
  write_file_atomically(path, std::string(png.begin(), png.end()));
}

}  // namespace ipd::cli
