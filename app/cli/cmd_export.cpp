// `ipd export rocks STUDY`: one row per rock pair, the numbers behind every IPD.
#include <fmt/format.h>

#include <iostream>

#include "app/cli/cli_common.h"
#include "app/cli/commands.h"
#include "app/cli/study_options.h"
#include "core/report/rock_export.h"
#include "core/util/atomic_file.h"
#include "core/util/contained_file.h"

namespace ipd::cli {

Runner add_export_command(CLI::App& app) {
  struct Args {
    StudyOptions study;
    std::string format = "csv", out;
    bool unpaired = false;
  };
  auto args = std::make_shared<Args>();
  CLI::App* cmd = app.add_subcommand("export", "Export the data behind the IPD (`ipd export rocks STUDY`)");
  cmd->require_subcommand(1);
  CLI::App* rocks = cmd->add_subcommand("rocks", "One row per rock pair per model and domain pair");
  add_study_options(rocks, &args->study, false);
  rocks->add_option("--format", args->format, "csv or json")->check(CLI::IsMember({"csv", "json"}));
  rocks->add_flag("--unpaired", args->unpaired, "Also rows for unpaired rocks (partner fields empty)");
  rocks->add_option("--out", args->out, "Write to this file (atomically) instead of stdout");
  return [args]() -> int {
    if (output_is_study_input(args->study.study, args->out)) return kBadInput;
    auto loaded = load_study_table(args->study, false);
    if (!loaded) return kBadInput;
    if (args->format == "json") require_utf8_names(loaded->labels.study);
    RockExportOptions eo;
    eo.unpaired = args->unpaired;
    const auto rows = rock_rows(loaded->labels, loaded->table, eo);
    // Every row carries the label fingerprint and hand-edit counts: an exported number can be told from an
    // automatic one without the table beside it.
    const Provenance provenance = table_provenance(loaded->table, loaded->labels);
    const std::string text =
        args->format == "json" ? rock_rows_json(rows, &provenance) : rock_rows_csv(rows, &provenance);
    if (args->out.empty()) {
      std::cout << text;
    } else {
      write_output_file(loaded->labels.study.root, args->out, text);
      fmt::print(stderr, "wrote {} rows to {}\n", rows.size(), args->out);
    }
    return kOk;
  };
}

}  // namespace ipd::cli
