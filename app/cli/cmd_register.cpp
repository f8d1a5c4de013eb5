// `ipd register REAL.txt SYNTH.txt` and `ipd register --list FILE.tsv`: rock pairing of label files.
#include <fmt/format.h>
#include <fmt/ranges.h>

#include <cmath>

#include <algorithm>

#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <vector>

#include "app/cli/cli_common.h"
#include "app/cli/commands.h"
#include "core/registration/registration.h"
#include "core/util/atomic_file.h"
#include "core/util/json_output.h"
#include "core/util/number_text.h"
#include "core/util/parallel.h"

namespace ipd::cli {

namespace {

// A count rounded to a whole number with thousands separators: 1045000 -> "1,045,000" (not "1.05e+06").
std::string grouped_count(double n) { return grouped_thousands(std::llround(n)); }

// "1 trial", "1,000 trials".
std::string counted(double n, const char* singular, const char* plural) {
  return grouped_count(n) + " " + (std::lround(n) == 1 ? singular : plural);
}

// Five decimals, and a number that rounds to zero prints as "0.00000", never "-0.00000".
std::string fixed_no_minus_zero(double v) { return fixed_decimals(v, 5); }

// What a method's search counts, named alike in --json and the text report: cpd runs EM iterations (no trials,
// no hypotheses); paper and consensus draw trials and score hypotheses.
struct SearchCount {
  const char* json_key;
  const char* singular;
  const char* plural;
  int RegistrationReport::*value;
};

std::vector<SearchCount> search_counts(RegistrationMethod method) {
  if (method == RegistrationMethod::kCpd)
    return {{"em_iterations", "EM iteration", "EM iterations", &RegistrationReport::em_iterations}};
  // The samples drawn are "trials", as --trials names their bound.
  return {{"trials", "trial", "trials", &RegistrationReport::samples},
          {"hypotheses", "hypothesis", "hypotheses", &RegistrationReport::hypotheses}};
}

struct Job {
  std::string real, synth;
  int line = 0;
  nlohmann::json result;
  std::vector<LabelError> errors;
};

nlohmann::json report_json(const Job& job, const RegistrationReport& r) {
  nlohmann::json j;
  j["real"] = job.real;
  j["synth"] = job.synth;
  j["method"] = to_string(r.method);
  j["affine"] = {{r.affine(0, 0), r.affine(0, 1), r.affine(0, 2)}, {r.affine(1, 0), r.affine(1, 1), r.affine(1, 2)}};
  j["pairs"] = nlohmann::json::array();
  for (const auto& [a, b] : r.pairs) j["pairs"].push_back({a, b});
  for (const auto& c : search_counts(r.method)) j[c.json_key] = r.*c.value;
  j["inliers"] = r.inliers;
  // null: nothing was scored (a 0 would read as paper's perfect fit). The measure says how to read the number.
  j["score"] = r.fit.scored() ? nlohmann::json(r.fit.value) : nlohmann::json(nullptr);
  j["score_measure"] = r.fit.scored() ? nlohmann::json(fit_measure_key(r.fit.measure)) : nlohmann::json(nullptr);
  j["stop"] = ipd::to_string(r.stop);
  j["confidence"] = r.confidence;
  j["ambiguous"] = r.ambiguous;
  if (r.ambiguous) j["ambiguity"] = ambiguity_reason(r.ambiguity);
  j["work"] = r.work;
  j["work_budget"] = r.work_budget;
  if (!r.note.empty()) j["note"] = r.note;
  j["elapsed_ms"] = r.elapsed_ms;
  j["pairing_ms"] = r.pairing_ms;
  return j;
}

void run_job(Job* job, const RegistrationOptions& opt, int cls, bool skip_bad_lines) {
  LabelFile a = read_labels(job->real, {LabelKind::kGroundTruth});
  LabelFile b = read_labels(job->synth, {LabelKind::kGroundTruth});
  for (const auto* f : {&a, &b}) {
    if (!f->exists) job->errors.push_back({f->path, 0, "no such label file"});
    job->errors.insert(job->errors.end(), f->errors.begin(), f->errors.end());
  }
  // Skipped lines that are most of a file's box lines stop the pair, as a layout that leaves out most of a
  // study's rocks stops ipd table: the pairs would be those of what is left, not of the scene's rocks.
  for (const auto* f : {&a, &b}) {
    long malformed = 0;
    for (const LabelError& e : f->errors) malformed += e.malformed_lines();
    const long lines = malformed + static_cast<long>(f->boxes.size());
    if (skip_bad_lines && 2 * malformed > lines)
      job->errors.push_back({f->path, 0,
                             fmt::format("--skip-bad-lines would leave out {} of its {} box lines, more than half: "
                                         "the pairs would be of what is left, not of the scene's rocks; fix the lines",
                                         malformed, lines)});
  }
  const bool file_problem =
      std::any_of(job->errors.begin(), job->errors.end(), [](const LabelError& e) { return e.malformed_lines() == 0; });
  if (!job->errors.empty() && (!skip_bad_lines || file_problem)) return;
  // A class one file holds none of leaves nothing of that class to pair there: every rock of the other
  // file would read as unpaired, a layout mistake (the wrong --class, shifted class numbers), not a result.
  bool lacks_class = false;
  for (LabelFile* f : {&a, &b}) {
    std::set<int> held;
    for (const Box& x : f->boxes) held.insert(x.cls);
    const size_t before = f->boxes.size();
    keep_class(f, cls);
    if (cls >= 0 && before > 0 && f->boxes.empty()) {
      lacks_class = true;
      job->errors.push_back({f->path, 0,
                             fmt::format("no box of class {} among its {} (it holds class {}): nothing of that class "
                                         "to pair; choose a class both files hold with --class",
                                         cls, before, fmt::join(held, ", "))});
    }
  }
  if (lacks_class) return;
  job->result = report_json(*job, register_rocks(a.boxes, b.boxes, opt));
}

std::vector<Job> read_list(const std::string& path) {
  const std::string text = read_file(path);
  std::vector<Job> jobs;
  std::istringstream in(text);
  std::string line;
  int n = 0, unlisted = 0;
  std::vector<std::string> bad;
  while (std::getline(in, line)) {
    ++n;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.find_first_not_of(" \t") == std::string::npos || line[0] == '#') continue;
    const size_t tab = line.find('\t');
    if (tab == std::string::npos || line.find('\t', tab + 1) != std::string::npos) {
      if (bad.size() < kMaxListedErrors)
        bad.push_back(fmt::format("{}:{}: expected real_path<TAB>synth_path, found '{}'", path, n,
                                  line.size() > 40 ? line.substr(0, 37) + "..." : line));
      else
        ++unlisted;
      continue;
    }
    jobs.push_back({line.substr(0, tab), line.substr(tab + 1), n, {}, {}});
  }
  if (!bad.empty()) {
    std::string all;
    for (const auto& b : bad) all += (all.empty() ? "" : "\n") + b;
    if (unlisted > 0) all += fmt::format("\n{}: {} more malformed line(s) not listed", path, unlisted);
    throw IoError(all);
  }
  return jobs;
}

// What `ipd register` was asked for.
struct RegisterArgs {
  std::string real, synth, list, method = "consensus";
  std::uint64_t seed = 0;
  int cls = -1, trials = 0, threads = 0;
  std::vector<int> image_size;
  double budget_ms = 0, max_rotation = 0, max_anisotropy = 0;
  bool json = false, skip_bad_lines = false;

  // Empty when every option the registration options do not check themselves is in range, else "--option:
  // what is wrong". A value out of range is an error, never the default. --trials, --max-rotation and
  // --max-anisotropy are checked by RegistrationOptions::validate (registration_options).
  std::string validate(const CLI::App& cmd) const {
    auto given = [&](const char* flag) { return cmd.count(flag) > 0; };
    if (given("--class") && cls < 0)
      return fmt::format("--class: must be a class number >= 0 (leave it out for every class), got {}", cls);
    if (given("--budget-ms") && !(budget_ms >= 0 && std::isfinite(budget_ms)))
      return fmt::format("--budget-ms: must be a number of milliseconds >= 0 (0: no limit), got {}", budget_ms);
    if (image_size.size() == 2 && (image_size[0] <= 0 || image_size[1] <= 0))
      return fmt::format("--image-size: width and height must be positive, got {},{}", image_size[0], image_size[1]);
    if (given("--threads") && threads < 0)
      return fmt::format("--threads: must be >= 0 (0: every core), got {}", threads);
    return {};
  }
};

void declare_register_options(CLI::App* cmd, RegisterArgs* args) {
  cmd->add_option("REAL", args->real, "Real image's label file (YOLO txt)");
  cmd->add_option("SYNTH", args->synth, "Synthetic image's label file (YOLO txt)");
  // What --list prints is checked by Cli.RegisterListPrintsWhatItsHelpSays.
  cmd->add_option("--list", args->list,
                  "TSV file of real_path<TAB>synth_path lines (blank and # lines skipped); prints one report per "
                  "pair, in the file's order: text, or with --json one JSON object per line (a pair that fails: "
                  "{real, synth, error})");
  cmd->add_option("--method", args->method, "Registration method:\n" + methods_help())
      ->check(CLI::IsMember(method_names()));
  cmd->add_option("--seed", args->seed, "Random seed (results are deterministic for a seed)")->check(seed_validator());
  cmd->add_option("--class", args->cls, "Only boxes of this class (default: all)");
  // Each method's own search budget, as `ipd bench registration` treats budgets
  // (Cli.RegisterTrialsIsEachMethodsBudget).
  cmd->add_option("--trials", args->trials,
                  "Search budget: paper: K samples (default 1000); consensus: hypothesis cap (default 1000); cpd: EM "
                  "iterations (default 100)");
  cmd->add_option("--budget-ms", args->budget_ms,
                  "Time budget of each registration in milliseconds, set-up and pairing included (0: none)");
  cmd->add_option("--image-size", args->image_size, "W,H of the pictures, so angles are measured in pixels")
      ->delimiter(',')
      ->expected(2);
  cmd->add_option("--max-rotation", args->max_rotation,
                  "consensus: largest plausible rotation in degrees (default 30)");
  cmd->add_option("--max-anisotropy", args->max_anisotropy,
                  "consensus: largest ratio of the affine's two scales (default 2)");
  cmd->add_option("--threads", args->threads, "Worker threads for --list (default: all cores)");
  cmd->add_flag("--json", args->json, "Print JSON, one object per pair on its own line");
  cmd->add_flag("--skip-bad-lines", args->skip_bad_lines, "Warn about malformed label lines and skip them");
}

// The registration the options ask for; throws CLI::ValidationError naming what is out of range. The ranges
// are the options' own (RegistrationOptions::validate): each option given is checked as it is set, so the
// error names it ("--max-rotation: max_rotation_deg must be in (0, 180], got -5").
RegistrationOptions registration_options(const RegisterArgs& args, const CLI::App& cmd) {
  if (const std::string bad = args.validate(cmd); !bad.empty()) throw CLI::ValidationError(bad);
  RegistrationOptions opt;
  parse_method(args.method, &opt.method);
  opt.seed = args.seed;
  auto set = [&](const char* flag, auto apply) {
    if (cmd.count(flag) == 0) return;
    apply();
    if (const std::string bad = opt.validate(); !bad.empty())
      throw CLI::ValidationError(fmt::format("{}: {}", flag, bad));
  };
  set("--trials", [&] { opt.trials() = args.trials; });
  set("--max-rotation", [&] { opt.consensus.max_rotation_deg = args.max_rotation; });
  set("--max-anisotropy", [&] { opt.consensus.max_anisotropy = args.max_anisotropy; });
  if (args.budget_ms > 0) opt.time_budget_ms = args.budget_ms;  // 0: no limit
  if (args.image_size.size() == 2) opt.aspect = static_cast<double>(args.image_size[0]) / args.image_size[1];
  const std::string bad = opt.validate();
  if (!bad.empty()) throw CLI::ValidationError("register", bad);
  return opt;
}

// The text report of one registered pair (its JSON result read back, so both say the same).
void print_report_text(const Job& job, RegistrationMethod method_used, double budget_ms) {
  const auto& r = job.result;
  fmt::print("{} -> {}\n", job.real, job.synth);
  const std::string method = r["method"].get<std::string>();
  // The same counts, under the same names, as --json (the studio's header says the same).
  std::string searched;
  for (const auto& c : search_counts(method_used))
    searched += (searched.empty() ? "" : ", ") + counted(r[c.json_key].get<double>(), c.singular, c.plural);
  const FitScore fit =
      r["score"].is_null() ? FitScore{} : FitScore{fit_measure_of(method_used), r["score"].get<double>()};
  fmt::print("  method {}: {}, {}; stopped: {}\n", method, searched, fit_text(fit, 5), r["stop"].get<std::string>());
  // Two different counts: A centres that land within the gate of some B centre after the alignment,
  // and the one-to-one pairs the method then forms (which the IPD uses).
  fmt::print("  {} within the gate; {} by {}\n", counted(r["inliers"].get<double>(), "centre", "centres"),
             counted(static_cast<double>(r["pairs"].size()), "pair", "pairs"),
             method == "paper" ? "mutual nearest neighbour" : "aligned-box IoU (one-to-one)");
  // The budget is the same for every method: 10^6 + 300 n log2 n point evaluations for n rocks in all.
  fmt::print("  work: {} of {} point evaluations (the bound for this many rocks); confidence {:.3f}{}\n",
             grouped_count(r["work"].get<double>()), grouped_count(r["work_budget"].get<double>()),
             r["confidence"].get<double>(),
             r["ambiguous"].get<bool>() ? "; AMBIGUOUS: " + r["ambiguity"].get<std::string>()
                                        : std::string());  // the reason may have its own "(e.g. ...)"
  if (r.contains("note")) fmt::print("  note: {}\n", r["note"].get<std::string>());
  if (budget_ms > 0) {
    // Under a budget the time is what the user asked about; the pairing is the part the budget cannot end.
    const double elapsed = r["elapsed_ms"].get<double>(), pairing = r["pairing_ms"].get<double>();
    fmt::print("  time: {:.2f} ms of a {:g} ms budget, the final pairing {:.2f} ms of it{}\n", elapsed, budget_ms,
               pairing,
               elapsed > budget_ms ? " (a budget makes the pairing greedy but cannot end it: every rock is paired "
                                     "or left alone)"
                                   : "");
  }
  const auto& a = r["affine"];
  fmt::print("  affine (real -> synth, normalised): [{} {} {}; {} {} {}]\n", fixed_no_minus_zero(a[0][0].get<double>()),
             fixed_no_minus_zero(a[0][1].get<double>()), fixed_no_minus_zero(a[0][2].get<double>()),
             fixed_no_minus_zero(a[1][0].get<double>()), fixed_no_minus_zero(a[1][1].get<double>()),
             fixed_no_minus_zero(a[1][2].get<double>()));
  fmt::print("  pairs (1-based real:synth):");
  for (const auto& p : r["pairs"]) fmt::print(" {}:{}", p[0].get<int>() + 1, p[1].get<int>() + 1);
  fmt::print("\n");
}

// Each job's report, or its error, in the list's order; returns how many failed and counts the text reports.
int print_reports(const std::vector<Job>& jobs, const RegisterArgs& args, RegistrationMethod method, bool list_mode,
                  int* reported) {
  int failed = 0;
  for (const auto& job : jobs) {
    // JSON holds only UTF-8: a path in another encoding is this pair's error, named, not the whole output's.
    if (args.json && (!is_utf8(job.real) || !is_utf8(job.synth))) {
      const std::string why = fmt::format(
          "{}: the name is not UTF-8 text, which JSON output cannot hold; rename "
          "it (the text report takes it as it is)",
          escape_non_utf8(is_utf8(job.real) ? job.synth : job.real));
      fmt::print(stderr, "error: {}\n", why);
      ++failed;
      if (list_mode)
        std::cout << dump_json_output(nlohmann::json{
                         {"real", escape_non_utf8(job.real)}, {"synth", escape_non_utf8(job.synth)}, {"error", why}})
                  << "\n";
      continue;
    }
    const bool fatal = job.result.is_null();
    if (report_label_errors(job.errors, !fatal && args.skip_bad_lines) || fatal) {
      ++failed;
      if (list_mode && args.json) {
        nlohmann::json e = {{"real", job.real}, {"synth", job.synth}};
        e["error"] = job.errors.empty() ? "failed" : job.errors.front().to_string();
        std::cout << dump_json_output(e) << "\n";
      }
      continue;
    }
    if (args.json) {
      std::cout << dump_json_output(job.result) << "\n";
      continue;
    }
    ++*reported;
    print_report_text(job, method, args.budget_ms);
  }
  return failed;
}

int run_register(const RegisterArgs& args, const CLI::App& cmd) {
  const bool list_mode = !args.list.empty();
  if (list_mode == (!args.real.empty() || !args.synth.empty()) || (!list_mode && args.synth.empty()))
    throw CLI::ValidationError("register", "give either REAL SYNTH or --list FILE.tsv");
  const RegistrationOptions opt = registration_options(args, cmd);
  std::vector<Job> jobs;
  if (list_mode)
    jobs = read_list(args.list);
  else
    jobs.push_back({args.real, args.synth, 0, {}, {}});
  parallel_for(jobs.size(), args.threads, [&](size_t k) { run_job(&jobs[k], opt, args.cls, args.skip_bad_lines); });
  int reported = 0;
  const int failed = print_reports(jobs, args, opt.method, list_mode, &reported);
  // Angles and the rotation bound are measured in pixels: without the picture's size a wide picture's
  // alignment reads differently from ipd-studio's and ipd table's, which take it from study.yaml.
  if (reported > 0 && args.image_size.empty())
    fmt::print(stderr,
               "note: pictures taken as square (aspect 1); --image-size W,H measures angles in pixels, "
               "as ipd table and ipd-studio do with study.yaml's image size\n");
  return failed ? kBadInput : kOk;
}

}  // namespace

Runner add_register_command(CLI::App& app) {
  auto args = std::make_shared<RegisterArgs>();
  CLI::App* cmd = app.add_subcommand("register", "Pair the rocks of two GT label files by point-set registration");
  declare_register_options(cmd, args.get());
  return [args, cmd]() -> int { return run_register(*args, *cmd); };
}

}  // namespace ipd::cli
