// `ipd rank STUDY --ref real --model det-real`: which renderer setting is closest to the reference, which ones
// can't be told from it, each with its interval and a Holm-corrected paired test against the best.
#include <fmt/format.h>

#include <iostream>

#include "app/cli/cli_common.h"
#include "app/cli/commands.h"
#include "app/cli/rank_study.h"
#include "core/report/rank_format.h"
#include "core/util/contained_file.h"

namespace ipd::cli {

namespace {

struct RankCommandArgs {
  RankArgs rank;
  std::string format = "text", out;
  bool booktabs = false, latex_wide = false;
};

int run_rank(const RankCommandArgs& args) {
  TableFormat format = TableFormat::kText;
  parse_table_format(args.format, &format);
  if (output_is_study_input(args.rank.study.study, args.out)) return kBadInput;
  auto ranked = rank_study(args.rank, [&](const Study& study) {
    if (format == TableFormat::kJson) require_utf8_names(study);  // before the work, naming the file
  });
  if (!ranked) return kBadInput;
  TableFormatOptions fo;
  fo.latex_ci = args.rank.study.ci_given;
  fo.booktabs = args.booktabs;
  fo.latex_wide = args.latex_wide;
  fo.resamples = ranked->loaded.bootstrap.resamples;
  fo.level = ranked->loaded.bootstrap.level;
  fo.seed = ranked->loaded.bootstrap.seed;
  fo.conf_threshold = ranked->loaded.conf_threshold;
  fo.provenance = &ranked->provenance;
  const std::string text = format_ranking(ranked->ranking, format, fo);
  // The machine-readable formats carry the notes as fields; a reader of the terminal still sees them.
  if (format == TableFormat::kCsv || format == TableFormat::kJson)
    for (const std::string& n : ranking_notes(ranked->ranking, fo)) fmt::print(stderr, "note: {}\n", n);
  if (format == TableFormat::kLatex)
    if (const std::string advice = latex_ranking_fit_advice(ranked->ranking, fo); !advice.empty())
      fmt::print(stderr, "note: {}\n", advice);
  if (args.out.empty()) {
    std::cout << text;
  } else {
    write_output_file(ranked->loaded.labels.study.root, args.out, text);
    fmt::print(stderr, "wrote {}\n", args.out);
  }
  keep_until_exit(std::move(*ranked));
  return kOk;
}

}  // namespace

Runner add_rank_command(CLI::App& app) {
  auto args = std::make_shared<RankCommandArgs>();
  CLI::App* cmd = app.add_subcommand(
      "rank", "Rank renderer settings by IPD against a reference: the best, and those not distinguishable from it");
  add_rank_options(cmd, &args->rank);
  cmd->add_option("--format", args->format, "text, csv, json, markdown or latex")
      ->check(CLI::IsMember({"text", "csv", "json", "markdown", "latex"}));
  cmd->add_flag("--booktabs", args->booktabs, "LaTeX: \\toprule/\\midrule/\\bottomrule (needs the booktabs package)");
  cmd->add_flag("--latex-wide", args->latex_wide,
                "LaTeX: settings' names, parameters and intervals on one line, for a table* across both columns "
                "(default: a compact layout for one column)");
  cmd->add_option("--out", args->out, "Write the ranking to this file (atomically) instead of stdout");
  return [args]() -> int { return run_rank(*args); };
}

}  // namespace ipd::cli
