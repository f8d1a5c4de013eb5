// `ipd table STUDY`: the paper's Table I for a study, with scene-bootstrap intervals.
#include <fmt/format.h>

#include <iostream>

#include "cli_common.h"
#include "commands.h"
#include "ipd/atomic_file.h"
#include "ipd/table_format.h"
#include "study_options.h"

namespace ipd::cli {

Runner add_table_command(CLI::App& app) {
  struct Args {
    StudyOptions study;
    std::string format = "text", out;
    bool booktabs = false;
  };
  auto args = std::make_shared<Args>();
  CLI::App* cmd = app.add_subcommand("table", "Compute the IPD cross table (rows: models, columns: domain pairs)");
  add_study_options(cmd, &args->study, true);
  cmd->add_option("--format", args->format, "text, csv, json, markdown or latex")
      ->check(CLI::IsMember({"text", "csv", "json", "markdown", "latex"}));
  cmd->add_flag("--booktabs", args->booktabs, "LaTeX: \\toprule/\\midrule/\\bottomrule (needs the booktabs package)");
  cmd->add_option("--out", args->out, "Write the table to this file (atomically) instead of stdout");
  return [args]() -> int {
    auto loaded = load_study_table(args->study, true);
    if (!loaded) return kBadInput;
    TableFormat format = TableFormat::kText;
    parse_table_format(args->format, &format);
    TableFormatOptions fo;
    fo.latex_ci = args->study.ci_given;
    fo.booktabs = args->booktabs;
    fo.resamples = loaded->bootstrap.resamples;
    fo.level = loaded->bootstrap.level;
    fo.seed = loaded->bootstrap.seed;
    fo.conf_threshold = loaded->conf_threshold;
    const std::string text = format_table(loaded->table, format, fo);
    if (args->out.empty()) {
      std::cout << text;
    } else {
      write_file_atomically(args->out, text);
      fmt::print(stderr, "wrote {}\n", args->out);
    }
    return kOk;
  };
}

}  // namespace ipd::cli
