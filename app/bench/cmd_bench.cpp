// `ipd bench registration`: run time against error for every registration method, on cases built from
// real POLAR-Sim label pairs with known misalignments (see app/bench/registration_benchmark.h).
#include <fmt/format.h>

#include <unistd.h>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <opencv2/imgproc.hpp>
#include <thread>

#include <nlohmann/json.hpp>

#include <random>
#include "app/bench/fold_benchmark.h"
#include "app/bench/ipd_check.h"
#include "app/bench/registration_benchmark.h"
#include "app/cli/cli_common.h"
#include "app/cli/commands.h"
#include "app/data_files.h"
#include "core/picture/picture_codec.h"
#include "core/registration/pairing.h"
#include "core/report/csv.h"
#include "core/session/session.h"
#include "core/util/atomic_file.h"
#include "core/util/parallel.h"

namespace fs = std::filesystem;

namespace ipd::cli {

namespace {

struct Config {
  RegistrationMethod method;
  int budget;  // paper: K; consensus: hypothesis cap; cpd: EM iterations
};

struct Row {
  std::string regime, method;  // method: a registration method's name, "pycpd-numpy", "floor" or "ceiling"
  Config config;
  int cases = 0;
  double ms_per_pair = 0, ms_median = 0, f1 = 0, precision = 0, recall = 0, terr_median = 0, terr_p90 = 0;
  double ambiguous = -1, f1_ambiguous = 0;  // fraction of cases flagged, and their mean F1 (-1: not reported)
};

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
void score_case(const RegistrationCase& c, const RockPairs& pairs, const Affine2& affine, double aspect, Row* row,
                std::vector<double>* terr) {
  const PairScore s = score_pairs(pairs, c.truth);
  row->f1 += s.f1;
  row->precision += s.precision;
  row->recall += s.recall;
  terr->push_back(transform_error(affine, c.truth_affine, c.a, aspect));
}

void finish_row(const std::vector<double>& terr, Row* row) {
  const double n = static_cast<double>(std::max<size_t>(1, terr.size()));
  row->f1 /= n;
  row->precision /= n;
  row->recall /= n;
  row->terr_median = percentile(terr, 0.5);
  row->terr_p90 = percentile(terr, 0.9);
}

Row run_config(const std::vector<RegistrationCase>& cases, const std::string& regime, const Config& c, double aspect) {
  RegistrationOptions o;
  o.method = c.method;
  o.aspect = aspect;
  o.trials() = c.budget;
  Row row;
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
std::vector<Row> bounds_rows(const std::vector<RegistrationCase>& cases, const std::string& regime, double aspect) {
  Row floor, ceiling;
  floor.regime = ceiling.regime = regime;
  floor.method = "floor";
  ceiling.method = "ceiling";
  floor.config = ceiling.config = {RegistrationMethod::kConsensus, 0};
  floor.cases = ceiling.cases = static_cast<int>(cases.size());
  std::vector<double> terr_floor, terr_ceiling;
  Row unused;
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
Row run_pycpd(const std::vector<RegistrationCase>& cases, const std::string& regime, const std::string& script,
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
  Row row;
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
    const Row ours =
        run_config(list, tier.name, {RegistrationMethod::kConsensus, RegistrationOptions().trials()}, aspect);
    const Row theirs = run_pycpd(list, tier.name, script, aspect);
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
void scaling(double aspect, std::uint64_t seed) {
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
void work_bound(std::uint64_t seed) {
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

void plot(const std::vector<Row>& rows, const std::string& path) {
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

}  // namespace

// `ipd bench edits STUDY`: how long one manual edit takes, live IPD update included (the GUI's budget is
// 1 ms), over random pair / unpair / exclude / undo operations.
Runner add_bench_edits(CLI::App* bench) {
  struct Args {
    std::string study;
    int edits = 2000;
  };
  auto args = std::make_shared<Args>();
  CLI::App* cmd = bench->add_subcommand("edits", "Latency of manual edits with the live IPD update (ipd-studio)");
  cmd->add_option("STUDY", args->study, "Study directory")->required();
  cmd->add_option("--edits", args->edits, "Number of edits")->check(CLI::Range(1, 1000000));
  return [args]() -> int {
    const auto t0 = std::chrono::steady_clock::now();
    Session s = Session::open(args->study);
    const double open_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    if (s.scenes().empty()) throw StudyError(args->study + ": no scene to edit");
    std::mt19937 gen(1);
    struct {
      std::mt19937& g;
      int below(int n) { return static_cast<int>(g() % static_cast<unsigned>(n)); }
    } rng{gen};
    std::vector<double> us;
    size_t rocks = 0;
    for (int k = 0; k < args->edits; ++k) {
      const int scene = rng.below(static_cast<int>(s.scenes().size()));
      const int nl = static_cast<int>(s.gt(Side::kA, scene).size()),
                nr = static_cast<int>(s.gt(Side::kB, scene).size());
      if (nl == 0 || nr == 0) continue;
      rocks += nl + nr;
      const int op = rng.below(4);
      const auto e0 = std::chrono::steady_clock::now();
      if (op == 0)
        s.apply(scene, Edit::pair(rng.below(nl), rng.below(nr)));
      else if (op == 1)
        s.apply(scene, Edit::unpair(Side::kA, rng.below(nl)));
      else if (op == 2)
        s.apply(scene, Edit::toggle_exclude(Side::kB, rng.below(nr)));
      else
        s.undo();
      volatile double ipd = s.totals().ipd();  // what the panel shows next frame
      (void)ipd;
      us.push_back(std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - e0).count());
    }
    std::sort(us.begin(), us.end());
    fmt::print(
        "{}: opened in {:.1f} ms ({} scenes in view, {} models); {} edits on scenes of {:.1f} rocks on average\n",
        args->study, open_ms, s.scenes().size(), s.study().models.size(), us.size(),
        us.empty() ? 0.0 : static_cast<double>(rocks) / us.size());
    if (!us.empty())
      fmt::print("edit_us median={:.1f} p95={:.1f} max={:.1f}\n", us[us.size() / 2], us[us.size() * 95 / 100],
                 us.back());
    return kOk;
  };
}

Runner add_bench_command(CLI::App& app) {
  struct Args {
    std::string data = "../shared/data/polar-sim", csv, plot;
    int cases = 300;
    std::uint64_t seed = 1;
    double pair_noise_floor = 0;
    std::string bands_of = "validation";
    bool quick = false, pycpd = false, failures = false, scaling_only = false, folds = false, ipd_check = false;
    std::vector<std::string> tiers, methods;
    std::string pycpd_script = find_data_file("pycpd_reference.py", IPD_APP_DIR);
  };
  auto args = std::make_shared<Args>();
  CLI::App* bench = app.add_subcommand("bench", "Benchmarks");
  bench->require_subcommand(1);
  auto edits = std::make_shared<Runner>(add_bench_edits(bench));
  auto which = std::make_shared<std::string>("registration");
  bench->get_subcommands({}).front()->callback([which] { *which = "edits"; });
  auto bootstrap = std::make_shared<Runner>(add_bench_bootstrap(bench));
  bench->get_subcommands({}).back()->callback([which] { *which = "bootstrap"; });
  auto study = std::make_shared<Runner>(add_bench_study(bench));
  bench->get_subcommands({}).back()->callback([which] { *which = "study"; });
  auto budget = std::make_shared<Runner>(add_bench_budget(bench));
  bench->get_subcommands({}).back()->callback([which] { *which = "budget"; });
  CLI::App* cmd = bench->add_subcommand("registration", "Registration run time against pair F1 and transform error");
  cmd->add_option("--data", args->data, "POLAR-Sim label directory (containing labels/)");
  cmd->add_option("--cases", args->cases, "Cases per misalignment range")->check(CLI::Range(1, 100000));
  cmd->add_option("--seed", args->seed, "Seed for the cases")->check(seed_validator());
  cmd->add_option("--csv", args->csv, "Also write the table as CSV");
  cmd->add_option("--plot", args->plot, "Draw F1 against run time to this PNG");
  cmd->add_flag("--quick", args->quick, "One budget per method (for CI smoke runs)");
  cmd->add_option("--tiers", args->tiers, "Only these tiers (small, large, unequal)")
      ->delimiter(',')
      ->check(CLI::IsMember({"small", "large", "unequal"}));
  cmd->add_option("--methods", args->methods, "Only these methods (consensus, paper, cpd)")
      ->delimiter(',')
      ->check(CLI::IsMember(method_names()));
  cmd->add_flag("--folds", args->folds,
                "Only the fold table: tuning against held-out terrains, gaps to the ceiling, size bands");
  cmd->add_flag("--ipd-check", args->ipd_check,
                "Only the IPD on known pairs: true pairs against overlap alone and the rule with a noise floor");
  cmd->add_option("--pair-noise-floor", args->pair_noise_floor,
                  "--folds: score the pairing rule with this noise floor (fraction of the width; 0: overlap alone); "
                  "--ipd-check: the floor compared with overlap alone (0: 0.0125)")
      ->check(CLI::Range(0.0, 0.5));
  cmd->add_option("--bands-of", args->bands_of,
                  "--folds: count the size-band table over the validation sides (the default) or the tuning sides, "
                  "where a pairing rule is chosen")
      ->check(CLI::IsMember({"validation", "tuning"}));
  cmd->add_flag("--scaling-only", args->scaling_only, "Only the time against the rock count");
  cmd->add_flag(
      "--failures", args->failures,
      "List the default method's cases below F1 1 (for analysis; with --folds: each fold's validation cases)");
  cmd->add_flag("--pycpd", args->pycpd, "Also run the Python baseline (numpy port of pycpd; needs python3-numpy)");
  cmd->add_option("--pycpd-script", args->pycpd_script, "Path of pycpd_reference.py");
  return [args, edits, bootstrap, study, budget, which]() -> int {
    if (*which == "edits") return (*edits)();
    if (*which == "budget") return (*budget)();
    if (*which == "bootstrap") return (*bootstrap)();
    if (*which == "study") return (*study)();
    if (args->scaling_only) {
      scaling(1936.0 / 1216.0, args->seed);
      return kOk;
    }
    const std::string root = (std::filesystem::path(args->data) / "labels").string();
    if (!std::filesystem::is_directory(root))
      throw StudyError(root + ": no POLAR-Sim labels here (pass --data DIR; see ../shared/data/polar-sim)");
    const auto pairs = polar_sim_label_pairs(root);
    if (pairs.empty()) throw StudyError(root + ": no label pairs of one view at different sun azimuths");
    const double W = 1936, H = 1216, aspect = W / H;
    if (args->folds || args->ipd_check) {
      auto tiers = benchmark_tiers();
      if (!args->tiers.empty())
        tiers.erase(std::remove_if(tiers.begin(), tiers.end(),
                                   [&](const MisalignmentRange& r) {
                                     return std::find(args->tiers.begin(), args->tiers.end(), r.name) ==
                                            args->tiers.end();
                                   }),
                    tiers.end());
      fmt::print("{} label pairs (same view, different sun) from {}; 1 thread; seed {}\n", pairs.size(), root,
                 args->seed);
      if (args->ipd_check) {
        print_ipd_check(pairs, tiers, args->cases, args->seed, W, H,
                        args->pair_noise_floor > 0 ? args->pair_noise_floor : 0.0125);
        return kOk;
      }
      print_fold_report(pairs, tiers, args->cases, args->seed, W, H, args->pair_noise_floor,
                        args->bands_of == "tuning");
      if (args->failures)
        for (const auto& fold : benchmark_folds())
          for (const auto& tier : tiers) {
            fmt::print("\nfold {}, validation, {}:\n", fold.name, tier.name);
            list_failures(make_cases(fold_pairs(pairs, fold, true), tier, args->cases, args->seed, W, H),
                          fmt::format("{}/{}", fold.name, tier.name), aspect);
          }
      if (args->pycpd) compare_with_pycpd(pairs, tiers, args->cases, args->seed, args->pycpd_script, W, H);
      return kOk;
    }
    fmt::print("{} label pairs (same view, different sun) from {}; {} cases per range; 1 thread; seed {}\n",
               pairs.size(), root, args->cases, args->seed);
    std::vector<Config> configs;
    if (args->quick) {
      configs = {
          {RegistrationMethod::kPaper, 1000}, {RegistrationMethod::kConsensus, 1000}, {RegistrationMethod::kCpd, 100}};
    } else {
      for (int k : {10, 100, 1000}) configs.push_back({RegistrationMethod::kPaper, k});
      for (int k : {25, 100, 250, 1000, 4000}) configs.push_back({RegistrationMethod::kConsensus, k});
      for (int k : {10, 30, 100}) configs.push_back({RegistrationMethod::kCpd, k});
    }
    auto listed = [](const std::vector<std::string>& only, const std::string& name) {
      return only.empty() || std::find(only.begin(), only.end(), name) != only.end();
    };
    configs.erase(std::remove_if(configs.begin(), configs.end(),
                                 [&](const Config& c) { return !listed(args->methods, to_string(c.method)); }),
                  configs.end());
    auto tiers = benchmark_tiers();
    tiers.erase(std::remove_if(tiers.begin(), tiers.end(),
                               [&](const MisalignmentRange& r) { return !listed(args->tiers, r.name); }),
                tiers.end());
    std::vector<Row> rows;
    std::vector<RegistrationCase> all_cases;
    std::string csv =
        "range,method,budget,cases,ms_per_pair,ms_median,f1,precision,recall,transform_err_median,transform_err_p90,"
        "ambiguous_fraction\n";
    fmt::print(
        "Columns: budget = hypotheses (consensus), samples K (paper) or EM iterations (cpd); ms/pair = mean run time,\n"
        "ms med = median; F1, prec, recall of the rock pairs; terr = transform error, where the found and the true\n"
        "affine put A's rocks, in % of the image width (median, 90th percentile); amb% = cases flagged ambiguous,\n"
        "ambF1 = their mean F1. Rows 'floor' and 'ceiling' are not methods: floor = least squares on the true pairs\n"
        "(the least transform error any method can reach), ceiling = the true affine (the F1 a perfect alignment\n"
        "gets), each followed by the same pairing. The floor's F1 can exceed the ceiling's: fitted to the labelled\n"
        "centres, it absorbs the shift of centres the picture's edge cuts.\n\n");
    fmt::print("{:<8} {:<11} {:>7} {:>9} {:>8} {:>7} {:>7} {:>7} {:>10} {:>10} {:>6} {:>6}\n", "tier", "method",
               "budget", "ms/pair", "ms med", "F1", "prec", "recall", "terr med%", "terr p90%", "amb%", "ambF1");
    for (const auto& range : tiers) {
      // Cases with at least three true pairs (fewer leave nothing to register), drawn from successive seeds.
      std::vector<RegistrationCase> cases = make_cases(pairs, range, args->cases, args->seed, W, H);
      double rocks_a = 0, rocks_b = 0, true_pairs = 0;
      for (const auto& c : cases) rocks_a += c.a.size(), rocks_b += c.b.size(), true_pairs += c.truth.size();
      const double n = static_cast<double>(cases.size());
      fmt::print("{}: {} cases, rocks per side {:.1f} / {:.1f}, true pairs {:.1f}\n", range.name, cases.size(),
                 rocks_a / n, rocks_b / n, true_pairs / n);
      std::vector<Row> tier = bounds_rows(cases, range.name, aspect);
      for (const auto& c : configs) tier.push_back(run_config(cases, range.name, c, aspect));
      if (args->failures) list_failures(cases, range.name, aspect);
      if (args->pycpd) tier.push_back(run_pycpd(cases, range.name, args->pycpd_script, aspect));
      for (const auto& r : tier) {
        const std::string budget = r.config.budget > 0 ? std::to_string(r.config.budget) : "-";
        const std::string amb = r.ambiguous >= 0 ? fmt::format("{:.1f}", 100 * r.ambiguous) : "-";
        const std::string amb_f1 = r.ambiguous > 0 ? fmt::format("{:.2f}", r.f1_ambiguous) : "-";
        fmt::print("{:<8} {:<11} {:>7} {:>9.4f} {:>8.4f} {:>7.4f} {:>7.4f} {:>7.4f} {:>10.4f} {:>10.4f} {:>6} {:>6}\n",
                   r.regime, r.method, budget, r.ms_per_pair, r.ms_median, r.f1, r.precision, r.recall,
                   100 * r.terr_median, 100 * r.terr_p90, amb, amb_f1);
        csv += fmt::format("{},{},{},{},{:.6f},{:.6f},{:.6f},{:.6f},{:.6f},{:.6f},{:.6f},{:.4f}\n", csv_field(r.regime),
                           csv_field(r.method), r.config.budget, r.cases, r.ms_per_pair, r.ms_median, r.f1, r.precision,
                           r.recall, r.terr_median, r.terr_p90, r.ambiguous);
      }
      // The default method's goals, checked in the same run.
      const Row* floor = &tier[0];
      const Row* deflt = nullptr;
      const Row* py = nullptr;
      for (const auto& r : tier) {
        if (r.method == "consensus" && r.config.budget == RegistrationOptions().consensus.max_hypotheses) deflt = &r;
        if (r.method == "pycpd-numpy") py = &r;
      }
      if (deflt) {
        // The goals: F1 >= 0.99 (small) or 0.97, transform error <= 1.1x the floor, median <= 0.5 ms
        // per pair, >= 10x faster than the pycpd port by mean.
        auto verdict = [](bool met) { return met ? "met" : "NOT met"; };
        const double f1_goal = range.name == "small" ? 0.99 : 0.97;
        const double terr_ratio = floor->terr_median > 0 ? deflt->terr_median / floor->terr_median : 0.0;
        fmt::print(
            "  default: F1 {:.4f} (goal {}: {}), transform error {:.2f}x the floor (goal 1.1x: {}), median {:.3f} "
            "ms/pair (goal 0.5: {})",
            deflt->f1, f1_goal, verdict(deflt->f1 >= f1_goal), terr_ratio, verdict(terr_ratio <= 1.1), deflt->ms_median,
            verdict(deflt->ms_median <= 0.5));
        if (py) {
          const double speedup = py->ms_per_pair / deflt->ms_per_pair;
          fmt::print(", {:.1f}x faster than the pycpd port by mean (goal 10x: {}; {:.1f}x by medians)", speedup,
                     verdict(speedup >= 10), py->ms_median / deflt->ms_median);
        }
        fmt::print("\n");
      }
      rows.insert(rows.end(), tier.begin(), tier.end());
      all_cases.insert(all_cases.end(), cases.begin(), cases.end());
      fmt::print("\n");
    }
    if (!args->quick) {
      scaling(aspect, args->seed);
      work_bound(args->seed);
    }
    // Throughput of the default method over a whole "study" on every core, as `ipd table` runs it.
    {
      const int n = 1000;
      RegistrationOptions o;
      o.aspect = aspect;
      const auto start = std::chrono::steady_clock::now();
      parallel_for(n, 0, [&](size_t k) {
        const auto& c = all_cases[k % all_cases.size()];
        register_rocks(c.a, c.b, o);
      });
      const unsigned threads = std::max(1u, std::thread::hardware_concurrency());
      const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
      fmt::print(
          "\nThroughput: {} image pairs drawn from the cases above, default method, {} threads: {:.1f} ms in all\n", n,
          threads, ms);
    }
    if (!args->csv.empty()) write_file_atomically(args->csv, csv);
    if (!args->plot.empty()) plot(rows, args->plot);
    return kOk;
  };
}

}  // namespace ipd::cli
