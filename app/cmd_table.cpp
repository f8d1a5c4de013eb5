// `ipd table STUDY`: the paper's Table I for a study.
#include <fmt/format.h>

#include <iostream>

#include "cli_common.h"
#include "commands.h"
#include "ipd/atomic_file.h"
#include "ipd/registration_cache.h"
#include "ipd/table_format.h"

namespace ipd::cli {

Runner add_table_command(CLI::App& app) {
  struct Args {
    std::string study, format = "text", method, out;
    std::vector<std::string> models, domains;
    long long seed = -1;
    bool skip_bad_lines = false, no_cache = false;
  };
  auto args = std::make_shared<Args>();
  CLI::App* cmd = app.add_subcommand("table", "Compute the IPD cross table (rows: models, columns: domain pairs)");
  cmd->add_option("STUDY", args->study, "Study directory")->required();
  cmd->add_option("--format", args->format, "text, csv, json, markdown or latex")
      ->check(CLI::IsMember({"text", "csv", "json", "markdown", "latex"}));
  cmd->add_option("--model", args->models, "Only these models (repeat or comma-separate)")->delimiter(',');
  cmd->add_option("--domains", args->domains, "Only these domains, e.g. real,principled")->delimiter(',');
  cmd->add_option("--method", args->method, "Registration method (default from study.yaml, else consensus)")
      ->check(CLI::IsMember({"paper", "consensus", "cpd"}));
  cmd->add_option("--seed", args->seed, "Registration seed (default from study.yaml, else 0)");
  cmd->add_option("--out", args->out, "Write the table to this file (atomically) instead of stdout");
  cmd->add_flag("--no-cache", args->no_cache, "Register every scene again (ignore STUDY/.ipd-cache/)");
  cmd->add_flag("--skip-bad-lines", args->skip_bad_lines, "Warn about malformed label lines and skip them");
  return [args]() -> int {
    const Study study = open_study(args->study);
    const StudyLabels labels = load_labels(study);
    if (report_label_errors(labels.errors, args->skip_bad_lines)) return kBadInput;
    TableOptions opt;
    opt.models = args->models;
    opt.domains = args->domains;
    opt.registration = study.config.registration;
    if (!args->method.empty()) parse_method(args->method, &opt.registration.method);
    if (args->seed >= 0) opt.registration.seed = static_cast<std::uint64_t>(args->seed);
    if (!args->no_cache) opt.cache_dir = registration_cache_dir(study.root);
    Progress progress("registering");
    opt.progress = [&](int d, int t) { progress.update(d, t); };
    const CrossTable table = compute_cross_table(labels, opt);
    for (const auto& w : table.warnings) fmt::print(stderr, "warning: {}\n", w);
    TableFormat format = TableFormat::kText;
    parse_table_format(args->format, &format);
    const std::string text = format_table(table, format);
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
