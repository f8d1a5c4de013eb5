#include "app/cli/study_options.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "app/cli/cli_common.h"
#include "core/ipd/study_cache.h"
#include "core/registration/registration_cache.h"
#include "core/stats/study_statistics.h"
#include "core/util/number_text.h"

namespace ipd::cli {

BootstrapOptions StudyOptions::bootstrap_options() const {
  BootstrapOptions b;
  b.resamples = bootstrap;
  b.level = level;
  b.seed = seed.value_or(0);
  return b;
}

std::string StudyOptions::validate() const {
  if (conf != -1 && !(conf >= 0 && conf <= 1)) return fmt::format("--conf: must be in [0, 1], got {}", conf);
  // The resamples' rule is the engine's own (BootstrapOptions::validate).
  BootstrapOptions resamples;
  resamples.resamples = bootstrap;
  if (const std::string bad = resamples.validate(); !bad.empty()) return "--bootstrap: " + bad;
  if (!(level >= 0.5 && level <= 0.9999)) return fmt::format("--ci: must be in [0.5, 0.9999], got {}", level);
  if (threads < 0) return fmt::format("--threads: must be >= 0 (0: every core), got {}", threads);
  for (size_t k = 0; k < domains.size(); ++k)
    if (std::find(domains.begin(), domains.begin() + static_cast<std::ptrdiff_t>(k), domains[k]) !=
        domains.begin() + static_cast<std::ptrdiff_t>(k))
      return fmt::format("--domains: names '{}' twice (a domain is compared with another)",
                         quoted_for_message(domains[k]));
  if (!std::isnan(budget_ms) && !(budget_ms >= 0 && std::isfinite(budget_ms)))
    return fmt::format("--budget-ms: must be a number of milliseconds >= 0 (0: no limit), got {}", budget_ms);
  return {};
}

void add_study_options(CLI::App* cmd, StudyOptions* o, bool with_bootstrap) {
  cmd->add_option("STUDY", o->study, "Study directory")->required();
  cmd->add_option("--model", o->models, "Only these models (repeat or comma-separate)")->delimiter(',');
  cmd->add_option("--domains", o->domains, "Only these domains, e.g. real,principled")->delimiter(',');
  cmd->add_option(
         "--method", o->method,
         "Registration method (default from study.yaml, else " + method_names().front() + "):\n" + methods_help())
      ->check(CLI::IsMember(method_names()));
  cmd->add_option("--budget-ms", o->budget_ms,
                  "Time budget of each registration in milliseconds, set-up and pairing included (0: none; default "
                  "from study.yaml's registration.budget_ms, else none). A search it ends keeps its best so far, "
                  "so pairs may then differ between machines and runs")
      ->check(CLI::Validator(
          [](std::string& s) {
            return is_non_finite_word(s) ? "must be a number of milliseconds >= 0 (0: no limit), got " + s
                                         : std::string();
          },
          "MS >= 0"));
  // The whole 64-bit range, as study.yaml's registration.seed: a seed given either way is the same seed.
  cmd->add_option_function<std::uint64_t>(
         "--seed", [o](const std::uint64_t& seed) { o->seed = seed; },
         "Registration and bootstrap seed, 0 to 18446744073709551615 (default from study.yaml, else 0)")
      ->check(seed_validator());
  cmd->add_option("--conf", o->conf,
                  "Drop predictions below this confidence (the GUI slider; default: study.yaml's conf_threshold)")
      ->check(CLI::Range(0.0, 1.0));
  cmd->add_option("--threads", o->threads, "Worker threads (0: every core); results don't depend on it")
      ->check(CLI::NonNegativeNumber);
  add_class_options(cmd, &o->class_word, &o->class_map, &o->task_word);
  cmd->add_flag("--no-cache", o->no_cache, "Register every scene again (ignore STUDY/.ipd-cache/)");
  cmd->add_flag("--skip-bad-lines", o->skip_bad_lines, "Warn about malformed label lines and skip them");
  if (!with_bootstrap) return;
  cmd->add_option("--bootstrap", o->bootstrap, "Scene-bootstrap resamples for intervals (0: none; else at least 2)")
      ->check(CLI::NonNegativeNumber)
      ->default_val(2000);
  // A flag with an optional level (`--ci`, `--ci=0.9`; main() turns `--ci 0.9` into `--ci=0.9`), so it
  // never takes the STUDY after it for a level, whatever follows.
  cmd->add_flag("--ci{0.95}", o->ci_text,
                "Interval level (default 0.95; --ci=LEVEL or --ci LEVEL); with --format latex, print the intervals")
      ->check(CLI::Range(0.5, 0.9999))
      ->each([o](const std::string& level) {
        o->level = std::stod(level);
        o->ci_given = true;
      });
}

void add_class_options(CLI::App* cmd, std::string* class_word, std::vector<std::string>* class_map,
                       std::string* task_word) {
  cmd->add_option("--task", *task_word,
                  "What a performance value is: detect (box IoU, the paper's) or segment (mask IoU of the outlines "
                  "that YOLO-seg lines give; every instance needs one). Default: study.yaml's task, else detect")
      ->check(CLI::IsMember({"detect", "segment"}));
  cmd->add_option("--class", *class_word,
                  "The class every number is about: a name from classes.txt or study.yaml, a class number, or 'all' "
                  "for a class-blind number (default: study.yaml's rock_class; required when the labels hold more "
                  "than one class)");
  cmd->add_option("--class-map", *class_map,
                  "FROM:TO, repeatable: prediction class FROM is the study's class TO, for prediction sets without "
                  "a classes.txt whose numbers are shifted (e.g. 0:1 for YOLO predictions beside 1-based CVAT labels)")
      ->delimiter(',');
}

void apply_class_options(const std::string& class_word, const std::vector<std::string>& class_map,
                         const std::string& task_word, Study* study) {
  if (!task_word.empty() && !parse_task(task_word, &study->config.task))
    throw CLI::ValidationError(fmt::format("--task: expected detect or segment, got '{}'", task_word));
  std::map<int, int> from_to;
  for (const std::string& m : class_map) {
    const auto colon = m.find(':');
    int from = -1, to = -1;
    try {
      if (colon != std::string::npos) {
        size_t used = 0;
        from = std::stoi(m.substr(0, colon), &used);
        if (used != colon) from = -1;
        const std::string rest = m.substr(colon + 1);
        to = std::stoi(rest, &used);
        if (used != rest.size()) to = -1;
      }
    } catch (const std::exception&) {
      from = to = -1;
    }
    if (from < 0 || to < 0 || from > 1000 || to > 1000)
      throw CLI::ValidationError(
          fmt::format("--class-map: expected FROM:TO with class numbers 0 to 1000, got '{}'", m));
    from_to[from] = to;
  }
  apply_prediction_class_map(from_to, study->domains, &study->classes);
  if (!class_word.empty()) study->config.rock_class = study->classes.resolve(class_word);
}

Study open_study_with_conf(const StudyOptions& o) {
  if (const std::string bad = o.validate(); !bad.empty()) throw CLI::ValidationError(bad);
  Study study = open_study(o.study);
  if (o.conf >= 0) study.config.conf_threshold = o.conf;
  apply_class_options(o.class_word, o.class_map, o.task_word, &study);
  return study;
}

RegistrationOptions registration_options(const Study& study, const StudyOptions& o) {
  RegistrationOptions r = study.config.registration;
  if (!o.method.empty()) parse_method(o.method, &r.method);
  if (o.seed) r.seed = *o.seed;
  if (o.budget_ms == 0) r.time_budget_ms.reset();
  if (o.budget_ms > 0) r.time_budget_ms = o.budget_ms;
  return r;
}

BootstrapOptions run_bootstrap(const StudyOptions& o, const RegistrationOptions& registration) {
  BootstrapOptions b = o.bootstrap_options();
  if (!o.seed) b.seed = registration.seed;
  return b;
}

std::optional<LoadedStudy> load_study_table(const StudyOptions& o, bool with_intervals, const ShownPairs& shown) {
  return load_study_table(open_study_with_conf(o), o, with_intervals, shown);
}

std::optional<LoadedStudy> load_study_table(Study study, const StudyOptions& o, bool with_intervals,
                                            const ShownPairs& shown) {
  // The GUI's parsed-study cache (study_cache.h): unchanged label files and registrations are read back.
  StudyCache parsed(o.no_cache ? std::string() : parsed_study_cache_path(study.root), study.root);
  LoadedStudy out{parsed.load_labels(study), {}, study.config.conf_threshold, 0, {}, {}};
  if (report_label_errors(out.labels.errors, o.skip_bad_lines)) return std::nullopt;
  require_choices(out.labels);
  report_class_notes(out.labels);
  RegistrationCache registration(o.no_cache ? std::string() : registration_cache_dir(study.root));
  parsed.hand_registrations_to(registration);
  TableOptions opt;
  opt.models = o.models;
  opt.domains = o.domains;
  opt.threads = o.threads;
  opt.registration = registration_options(study, o);
  out.registration_budget_ms = opt.registration.time_budget_ms.value_or(0);
  opt.cache_dir = registration.dir();
  opt.registration_cache = &registration;
  opt.shown_cells_only = shown.training_domain_cells;
  opt.only_pairs = shown.only;
  Progress progress("registering");
  opt.progress = [&](int d, int t) { progress.update(d, t); };
  out.table = compute_cross_table(out.labels, opt);
  parsed.save(out.labels, registration);
  if (report_unusable_pairs(out.table.pairs_problems, o.skip_bad_lines, &out.table.warnings)) return std::nullopt;
  // The layout of the domain pairs computed only: a ranking says of each candidate it can't rank why (a
  // candidate sharing no scene with the reference is one row, not a stop).
  std::vector<std::pair<std::string, std::string>> computed;
  for (const auto& [a, b] : out.table.columns)
    if (includes_pair(shown.only, a, b)) computed.emplace_back(a, b);
  if (report_layout_problems(layout_problems(out.labels, computed, out.table.models),
                             o.skip_bad_lines || shown.layout_problems_are_warnings, &out.table.warnings))
    return std::nullopt;
  for (const auto& w : out.table.warnings) fmt::print(stderr, "warning: {}\n", w);
  out.bootstrap = run_bootstrap(o, opt.registration);
  out.fingerprint_checkpoints = parsed.fingerprint_checkpoints();
  if (with_intervals && o.bootstrap > 0) add_confidence_intervals(&out.table, out.bootstrap, o.threads);
  return out;
}

}  // namespace ipd::cli
