// `ipd table STUDY`: the paper's Table I for a study, with scene-bootstrap intervals.
#include <fmt/format.h>

#include <iostream>

#include "app/cli/cli_common.h"
#include "app/cli/commands.h"
#include "app/cli/study_options.h"
#include "core/report/table_format.h"
#include "core/util/atomic_file.h"
#include "core/util/contained_file.h"

namespace ipd::cli {
namespace {

// What `ipd table` was asked for.
struct TableArgs {
  StudyOptions study;
  std::string format = "text", out;
  bool booktabs = false, latex_wide = false, verbose = false;
};

void declare_table_options(CLI::App* cmd, TableArgs* args) {
  add_study_options(cmd, &args->study, true);
  cmd->add_option("--format", args->format, "text, csv, json, markdown or latex")
      ->check(CLI::IsMember({"text", "csv", "json", "markdown", "latex"}));
  cmd->add_flag("--booktabs", args->booktabs, "LaTeX: \\toprule/\\midrule/\\bottomrule (needs the booktabs package)");
  cmd->add_flag("--latex-wide", args->latex_wide,
                "LaTeX: the wide layout (names spelled out, intervals beside the values) for a table* across both "
                "columns; the default fits one IEEE column for up to 3 domains");
  cmd->add_option("--out", args->out, "Write the table to this file (atomically) instead of stdout");
  cmd->add_flag("--verbose", args->verbose,
                "List the scenes whose registration was ambiguous and the scenes whose pairs were set by hand");
}

// What a reader must know to trust the numbers: the prediction threshold used, and the scenes whose
// registration could not decide between alignments (their pairs may be wrong). In the text table
// itself; beside the machine-readable formats, on stderr.
std::vector<std::string> table_notes(const TableArgs& args, const LoadedStudy& loaded, const Provenance& provenance) {
  std::vector<std::string> notes;
  if (loaded.conf_threshold > 0)
    notes.push_back(
        fmt::format("Predictions with confidence below {:g} dropped (--conf, else study.yaml's "
                    "conf_threshold).",
                    loaded.conf_threshold));
  std::vector<std::string> ambiguous;
  const CrossTable& t = loaded.table;
  for (size_t c = 0; c < t.columns.size() && c < t.pairings.size(); ++c)
    for (const ScenePairing& p : t.pairings[c])
      if (!p.fixed && p.registration.ambiguous)
        ambiguous.push_back(fmt::format("  {} vs {}: {}: {}", t.columns[c].first, t.columns[c].second, p.stem,
                                        ambiguity_reason(p.registration.ambiguity)));
  if (!ambiguous.empty()) {
    notes.push_back(fmt::format("{} scene{}: registration ambiguous (see ipd-studio '?'){}", ambiguous.size(),
                                ambiguous.size() == 1 ? "" : "s", args.verbose ? ":" : "; --verbose lists them"));
    if (args.verbose) notes.insert(notes.end(), ambiguous.begin(), ambiguous.end());
  }
  // A search the time budget ended answers with what it had when the time ran out: on a slower or busier
  // machine, or another run, its pairs may differ.
  int budget_ended = 0;
  for (size_t c = 0; c < t.columns.size() && c < t.pairings.size(); ++c)
    for (const ScenePairing& p : t.pairings[c])
      if (!p.fixed && p.registration.stop == StopReason::kTimeBudget) ++budget_ended;
  if (budget_ended > 0)
    notes.push_back(
        fmt::format("{} registration{} (a scene in a domain pair) ended by the time budget of {:g} ms (--budget-ms, "
                    "else study.yaml's registration.budget_ms); their pairs may differ on another machine or run (a "
                    "larger budget, or 0 for none, lets the search finish)",
                    budget_ended, budget_ended == 1 ? "" : "s", loaded.registration_budget_ms));
  notes.push_back(provenance_note(provenance));
  if (args.verbose)
    for (const EditedScene& e : provenance.edited_scenes)
      notes.push_back(fmt::format("  {} vs {}: {}: pairs set by hand", e.a, e.b, e.stem));
  return notes;
}

int run_table(const TableArgs& args) {
  TableFormat format = TableFormat::kText;
  parse_table_format(args.format, &format);
  // CSV and JSON list every cell's value; the other formats print "–" where no chosen model trained.
  const bool every_cell = format == TableFormat::kCsv || format == TableFormat::kJson;
  if (output_is_study_input(args.study.study, args.out)) return kBadInput;
  auto loaded = load_study_table(args.study, true, {!every_cell, {}, false});
  if (!loaded) return kBadInput;
  if (args.format == "json") require_utf8_names(loaded->labels.study);
  TableFormatOptions fo;
  fo.latex_ci = args.study.ci_given;
  fo.booktabs = args.booktabs;
  fo.latex_wide = args.latex_wide;
  fo.resamples = loaded->bootstrap.resamples;
  fo.level = loaded->bootstrap.level;
  fo.seed = loaded->bootstrap.seed;
  fo.conf_threshold = loaded->conf_threshold;
  // Which numbers are automatic and which edited, and which labels they came from, travel with the table.
  const Provenance provenance = table_provenance(loaded->table, loaded->labels);
  fo.provenance = &provenance;
  std::string text = format_table(loaded->table, format, fo);
  std::vector<std::string> notes = table_notes(args, *loaded, provenance);
  if (format == TableFormat::kLatex) {
    std::string width = latex_fit_advice(loaded->table, fo);
    if (!width.empty()) notes.push_back(width);
  }
  for (const std::string& n : notes) {
    if (format == TableFormat::kText)
      text += n + "\n";
    else
      fmt::print(stderr, "note: {}\n", n);
  }
  if (args.out.empty()) {
    std::cout << text;
  } else {
    write_output_file(loaded->labels.study.root, args.out, text);
    fmt::print(stderr, "wrote {}\n", args.out);
  }
  keep_until_exit(std::move(*loaded));
  return kOk;
}

}  // namespace

Runner add_table_command(CLI::App& app) {
  auto args = std::make_shared<TableArgs>();
  CLI::App* cmd = app.add_subcommand("table", "Compute the IPD cross table (rows: models, columns: domain pairs)");
  declare_table_options(cmd, args.get());
  return [args]() -> int { return run_table(*args); };
}

}  // namespace ipd::cli
