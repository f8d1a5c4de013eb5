// Options shared by the commands that compute IPD from a study (table, compare, breakdown, metrics, export):
// STUDY, --model, --domains, --class, --class-map, --method, --seed, --conf, --bootstrap, --ci, --threads,
// --skip-bad-lines.
#pragma once

#include <CLI/CLI.hpp>
#include <cstdint>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/ipd/ipd.h"
#include "core/ipd/label_fingerprint.h"
#include "core/stats/statistics.h"

namespace ipd::cli {

struct StudyOptions {
  std::string study;
  std::vector<std::string> models, domains;
  std::string method;
  // --budget-ms: each registration's time budget, 0 none; NaN (not given): study.yaml's. Not -1, which typed is
  // as wrong as -5.
  double budget_ms = std::numeric_limits<double>::quiet_NaN();
  std::optional<std::uint64_t> seed;  // registration and bootstrap seed; not given: study.yaml's, else 0
  double conf = -1;                   // --conf X: prediction threshold (as the GUI slider); -1: study.yaml's
  int bootstrap = 2000;               // resamples; 0 = off
  double level = 0.95;                // --ci LEVEL
  bool ci_given = false;              // --ci appeared (LaTeX prints intervals)
  std::string ci_text;                // --ci's text as parsed (level holds its value)
  int threads = 0;
  bool skip_bad_lines = false;
  bool no_cache = false;               // --no-cache: register every scene again
  std::string class_word;              // --class NAME|NUMBER|all; empty: study.yaml's rock_class
  std::vector<std::string> class_map;  // --class-map FROM:TO (prediction class FROM is the study's TO)
  std::string task_word;               // --task detect|segment; empty: study.yaml's task

  BootstrapOptions bootstrap_options() const;
  // Empty when every value is in range (or the "not given" value), else "--option: what is wrong": a value
  // out of range is an error, never the default.
  std::string validate() const;
};

// Adds the options to `cmd`. `with_bootstrap`: also --bootstrap and --ci.
void add_study_options(CLI::App* cmd, StudyOptions* o, bool with_bootstrap);

// The study with --conf applied, its labels (label errors reported; nullopt when they are fatal) and the
// cross table with intervals (when o.bootstrap > 0).
struct LoadedStudy {
  StudyLabels labels;
  CrossTable table;
  double conf_threshold = 0;
  double registration_budget_ms = 0;  // the time budget each registration had (0: none)
  BootstrapOptions bootstrap;         // as used: the seed is --seed, else the study's registration seed
  // The label set's fingerprint's state after each domain, as the parsed-study cache keeps it (label_fingerprint.h).
  std::vector<FingerprintCheckpoint> fingerprint_checkpoints;
};
// The domain pairs a command's output reads: only those are registered and computed.
struct ShownPairs {
  bool training_domain_cells = false;  // TableOptions::shown_cells_only: a table that prints "–" elsewhere
  DomainPairFilter only;               // TableOptions::only_pairs
  // A pair whose layouts can't be compared is a warning, not a stop (a ranking names the candidate it can't rank).
  bool layout_problems_are_warnings = false;
};
std::optional<LoadedStudy> load_study_table(const StudyOptions& o, bool with_intervals, const ShownPairs& shown = {});
// The same on a study the command has opened already (open_study_with_conf).
std::optional<LoadedStudy> load_study_table(Study study, const StudyOptions& o, bool with_intervals,
                                            const ShownPairs& shown);

// The registration options of a run: study.yaml's, with --method, --seed and --budget-ms applied.
RegistrationOptions registration_options(const Study& study, const StudyOptions& o);
// The bootstrap of a run's intervals (--bootstrap, --ci): its seed is --seed, else the registration's.
BootstrapOptions run_bootstrap(const StudyOptions& o, const RegistrationOptions& registration);

// Opens the study and applies --conf, --class and --class-map (for commands that read labels themselves).
Study open_study_with_conf(const StudyOptions& o);
// Applies --class, --class-map and --task to an open study (StudyError for a class it does not know).
void apply_class_options(const std::string& class_word, const std::vector<std::string>& class_map,
                         const std::string& task_word, Study* study);
// Adds --class, --class-map and --task to a command that has no other study option.
void add_class_options(CLI::App* cmd, std::string* class_word, std::vector<std::string>* class_map,
                       std::string* task_word);

}  // namespace ipd::cli
