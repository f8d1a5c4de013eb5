// `ipd bench`: its subcommands, and `ipd bench registration`: run time against error for every registration
// method, on cases built from real POLAR-Sim label pairs with known misalignments (see
// app/bench/registration_benchmark.h; the runs themselves are in app/bench/registration_runs.h).
#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <thread>

#include "app/bench/fold_benchmark.h"
#include "app/bench/ipd_check.h"
#include "app/bench/registration_benchmark.h"
#include "app/bench/registration_runs.h"
#include "app/cli/cli_common.h"
#include "app/cli/commands.h"
#include "core/report/csv.h"
#include "core/util/atomic_file.h"
#include "core/util/data_files.h"
#include "core/util/parallel.h"

namespace ipd::cli {

namespace {

// What `ipd bench registration` was asked for.
struct RegistrationBenchArgs {
  std::string data = "../shared/data/polar-sim", csv, plot;
  int cases = 300;
  std::uint64_t seed = 1;
  double pair_noise_floor = 0;
  std::string bands_of = "validation";
  bool quick = false, pycpd = false, failures = false, scaling_only = false, folds = false, ipd_check = false;
  std::vector<std::string> tiers, methods;
  std::string pycpd_script = find_data_file("pycpd_reference.py", IPD_APP_DIR);
};

void declare_registration_bench_options(CLI::App* cmd, RegistrationBenchArgs* args) {
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
}

// Whether a --tiers or --methods list lets a name through (an empty list lets every name through).
bool listed(const std::vector<std::string>& only, const std::string& name) {
  return only.empty() || std::find(only.begin(), only.end(), name) != only.end();
}

std::vector<MisalignmentRange> chosen_tiers(const std::vector<std::string>& only) {
  auto tiers = benchmark_tiers();
  tiers.erase(
      std::remove_if(tiers.begin(), tiers.end(), [&](const MisalignmentRange& r) { return !listed(only, r.name); }),
      tiers.end());
  return tiers;
}

// The method configurations of the table: every method at a few budgets, or with --quick one budget each.
std::vector<MethodConfig> chosen_configs(const RegistrationBenchArgs& args) {
  std::vector<MethodConfig> configs;
  if (args.quick) {
    configs = {
        {RegistrationMethod::kPaper, 1000}, {RegistrationMethod::kConsensus, 1000}, {RegistrationMethod::kCpd, 100}};
  } else {
    for (int k : {10, 100, 1000}) configs.push_back({RegistrationMethod::kPaper, k});
    for (int k : {25, 100, 250, 1000, 4000}) configs.push_back({RegistrationMethod::kConsensus, k});
    for (int k : {10, 30, 100}) configs.push_back({RegistrationMethod::kCpd, k});
  }
  configs.erase(std::remove_if(configs.begin(), configs.end(),
                               [&](const MethodConfig& c) { return !listed(args.methods, to_string(c.method)); }),
                configs.end());
  return configs;
}

// --folds and --ipd-check: tuning against held-out terrains, or the IPD on known pairs.
int run_fold_bench(const RegistrationBenchArgs& args, const std::vector<LabelPair>& pairs, const std::string& root,
                   double W, double H) {
  const double aspect = W / H;
  const auto tiers = chosen_tiers(args.tiers);
  fmt::print("{} label pairs (same view, different sun) from {}; 1 thread; seed {}\n", pairs.size(), root, args.seed);
  if (args.ipd_check) {
    print_ipd_check(pairs, tiers, args.cases, args.seed, W, H,
                    args.pair_noise_floor > 0 ? args.pair_noise_floor : 0.0125);
    return kOk;
  }
  print_fold_report(pairs, tiers, args.cases, args.seed, W, H, args.pair_noise_floor, args.bands_of == "tuning");
  if (args.failures)
    for (const auto& fold : benchmark_folds())
      for (const auto& tier : tiers) {
        fmt::print("\nfold {}, validation, {}:\n", fold.name, tier.name);
        list_failures(make_cases(fold_pairs(pairs, fold, true), tier, args.cases, args.seed, W, H),
                      fmt::format("{}/{}", fold.name, tier.name), aspect);
      }
  if (args.pycpd) compare_with_pycpd(pairs, tiers, args.cases, args.seed, args.pycpd_script, W, H);
  return kOk;
}

void print_table_legend() {
  fmt::print(
      "Columns: budget = hypotheses (consensus), samples K (paper) or EM iterations (cpd); ms/pair = mean run time,\n"
      "ms med = median; F1, prec, recall of the rock pairs; terr = transform error, where the found and the true\n"
      "affine put A's rocks, in % of the image width (median, 90th percentile); amb% = cases flagged ambiguous,\n"
      "ambF1 = their mean F1. Rows 'floor' and 'ceiling' are not methods: floor = least squares on the true pairs\n"
      "(the least transform error any method can reach), ceiling = the true affine (the F1 a perfect alignment\n"
      "gets), each followed by the same pairing. The floor's F1 can exceed the ceiling's: fitted to the labelled\n"
      "centres, it absorbs the shift of centres the picture's edge cuts.\n\n");
  fmt::print("{:<8} {:<11} {:>7} {:>9} {:>8} {:>7} {:>7} {:>7} {:>10} {:>10} {:>6} {:>6}\n", "tier", "method", "budget",
             "ms/pair", "ms med", "F1", "prec", "recall", "terr med%", "terr p90%", "amb%", "ambF1");
}

// A tier's rows in the table and in the CSV.
void print_tier_rows(const std::vector<BenchRow>& tier, std::string* csv) {
  for (const auto& r : tier) {
    const std::string budget = r.config.budget > 0 ? std::to_string(r.config.budget) : "-";
    const std::string amb = r.ambiguous >= 0 ? fmt::format("{:.1f}", 100 * r.ambiguous) : "-";
    const std::string amb_f1 = r.ambiguous > 0 ? fmt::format("{:.2f}", r.f1_ambiguous) : "-";
    fmt::print("{:<8} {:<11} {:>7} {:>9.4f} {:>8.4f} {:>7.4f} {:>7.4f} {:>7.4f} {:>10.4f} {:>10.4f} {:>6} {:>6}\n",
               r.regime, r.method, budget, r.ms_per_pair, r.ms_median, r.f1, r.precision, r.recall, 100 * r.terr_median,
               100 * r.terr_p90, amb, amb_f1);
    *csv += fmt::format("{},{},{},{},{:.6f},{:.6f},{:.6f},{:.6f},{:.6f},{:.6f},{:.6f},{:.4f}\n", csv_field(r.regime),
                        csv_field(r.method), r.config.budget, r.cases, r.ms_per_pair, r.ms_median, r.f1, r.precision,
                        r.recall, r.terr_median, r.terr_p90, r.ambiguous);
  }
}

// The default method's goals, checked in the same run: F1 >= 0.99 (small) or 0.97, transform error <= 1.1x the
// floor, median <= 0.5 ms per pair, >= 10x faster than the pycpd port by mean. The tier's first row is the floor.
void print_default_goals(const std::vector<BenchRow>& tier, const std::string& tier_name) {
  const BenchRow* floor = &tier[0];
  const BenchRow* deflt = nullptr;
  const BenchRow* py = nullptr;
  for (const auto& r : tier) {
    if (r.method == "consensus" && r.config.budget == RegistrationOptions().consensus.max_hypotheses) deflt = &r;
    if (r.method == "pycpd-numpy") py = &r;
  }
  if (!deflt) return;
  auto verdict = [](bool met) { return met ? "met" : "NOT met"; };
  const double f1_goal = tier_name == "small" ? 0.99 : 0.97;
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

// One tier of the table: its cases (at least three true pairs each, drawn from successive seeds), the bounds,
// every configuration, and optionally the failures and the pycpd port.
std::vector<BenchRow> run_tier(const RegistrationBenchArgs& args, const std::vector<LabelPair>& pairs,
                               const MisalignmentRange& range, const std::vector<MethodConfig>& configs, double W,
                               double H, std::vector<RegistrationCase>* all_cases, std::string* csv) {
  const double aspect = W / H;
  std::vector<RegistrationCase> cases = make_cases(pairs, range, args.cases, args.seed, W, H);
  double rocks_a = 0, rocks_b = 0, true_pairs = 0;
  for (const auto& c : cases) rocks_a += c.a.size(), rocks_b += c.b.size(), true_pairs += c.truth.size();
  const double n = static_cast<double>(cases.size());
  fmt::print("{}: {} cases, rocks per side {:.1f} / {:.1f}, true pairs {:.1f}\n", range.name, cases.size(), rocks_a / n,
             rocks_b / n, true_pairs / n);
  std::vector<BenchRow> tier = bounds_rows(cases, range.name, aspect);
  for (const auto& c : configs) tier.push_back(run_config(cases, range.name, c, aspect));
  if (args.failures) list_failures(cases, range.name, aspect);
  if (args.pycpd) tier.push_back(run_pycpd(cases, range.name, args.pycpd_script, aspect));
  print_tier_rows(tier, csv);
  print_default_goals(tier, range.name);
  all_cases->insert(all_cases->end(), cases.begin(), cases.end());
  return tier;
}

// Throughput of the default method over a whole "study" on every core, as `ipd table` runs it.
void print_throughput(const std::vector<RegistrationCase>& all_cases, double aspect) {
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
  fmt::print("\nThroughput: {} image pairs drawn from the cases above, default method, {} threads: {:.1f} ms in all\n",
             n, threads, ms);
}

// The table of every method configuration per tier, then the scaling and work-bound runs and the throughput.
int run_method_table(const RegistrationBenchArgs& args, const std::vector<LabelPair>& pairs, const std::string& root,
                     double W, double H) {
  const double aspect = W / H;
  fmt::print("{} label pairs (same view, different sun) from {}; {} cases per range; 1 thread; seed {}\n", pairs.size(),
             root, args.cases, args.seed);
  const std::vector<MethodConfig> configs = chosen_configs(args);
  const auto tiers = chosen_tiers(args.tiers);
  std::vector<BenchRow> rows;
  std::vector<RegistrationCase> all_cases;
  std::string csv =
      "range,method,budget,cases,ms_per_pair,ms_median,f1,precision,recall,transform_err_median,transform_err_p90,"
      "ambiguous_fraction\n";
  print_table_legend();
  for (const auto& range : tiers) {
    const std::vector<BenchRow> tier = run_tier(args, pairs, range, configs, W, H, &all_cases, &csv);
    rows.insert(rows.end(), tier.begin(), tier.end());
    fmt::print("\n");
  }
  if (!args.quick) {
    print_scaling(aspect, args.seed);
    print_work_bound(args.seed);
  }
  print_throughput(all_cases, aspect);
  if (!args.csv.empty()) write_file_atomically(args.csv, csv);
  if (!args.plot.empty()) plot_f1_against_time(rows, args.plot);
  return kOk;
}

int run_registration_bench(const RegistrationBenchArgs& args) {
  if (args.scaling_only) {
    print_scaling(1936.0 / 1216.0, args.seed);
    return kOk;
  }
  const std::string root = (std::filesystem::path(args.data) / "labels").string();
  if (!std::filesystem::is_directory(root))
    throw StudyError(root + ": no POLAR-Sim labels here (pass --data DIR; see ../shared/data/polar-sim)");
  const auto pairs = polar_sim_label_pairs(root);
  if (pairs.empty()) throw StudyError(root + ": no label pairs of one view at different sun azimuths");
  const double W = 1936, H = 1216;
  if (args.folds || args.ipd_check) return run_fold_bench(args, pairs, root, W, H);
  return run_method_table(args, pairs, root, W, H);
}

}  // namespace

Runner add_bench_command(CLI::App& app) {
  auto args = std::make_shared<RegistrationBenchArgs>();
  CLI::App* bench = app.add_subcommand("bench", "Benchmarks");
  bench->require_subcommand(1);
  // Each subcommand's callback records which one was chosen; the runner then runs that one.
  auto edits = std::make_shared<Runner>(add_bench_edits(bench));
  auto which = std::make_shared<std::string>("registration");
  bench->get_subcommands({}).front()->callback([which] { *which = "edits"; });
  auto bootstrap = std::make_shared<Runner>(add_bench_bootstrap(bench));
  bench->get_subcommands({}).back()->callback([which] { *which = "bootstrap"; });
  auto study = std::make_shared<Runner>(add_bench_study(bench));
  bench->get_subcommands({}).back()->callback([which] { *which = "study"; });
  auto budget = std::make_shared<Runner>(add_bench_budget(bench));
  bench->get_subcommands({}).back()->callback([which] { *which = "budget"; });
  auto rank = std::make_shared<Runner>(add_bench_rank(bench));
  bench->get_subcommands({}).back()->callback([which] { *which = "rank"; });
  CLI::App* cmd = bench->add_subcommand("registration", "Registration run time against pair F1 and transform error");
  declare_registration_bench_options(cmd, args.get());
  return [args, edits, bootstrap, study, budget, rank, which]() -> int {
    if (*which == "edits") return (*edits)();
    if (*which == "rank") return (*rank)();
    if (*which == "budget") return (*budget)();
    if (*which == "bootstrap") return (*bootstrap)();
    if (*which == "study") return (*study)();
    return run_registration_bench(*args);
  };
}

}  // namespace ipd::cli
