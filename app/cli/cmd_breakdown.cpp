// `ipd breakdown STUDY --by size|region|confidence`: where the gap is — IPD with its interval per bin of a
// property of the reference rock.
#include <fmt/format.h>

#include <iostream>
#include <nlohmann/json.hpp>

#include "app/cli/cli_common.h"
#include "app/cli/commands.h"
#include "app/cli/study_options.h"
#include "core/report/csv.h"
#include "core/report/provenance.h"
#include "core/stats/study_statistics.h"
#include "core/util/json_output.h"
#include "core/util/number_text.h"

namespace ipd::cli {

namespace {
std::string interval_text(const Interval& i) {
  if (std::isnan(i.estimate)) return "n/a";
  if (!i.has_interval()) return fmt::format("{:.4f}", i.estimate);
  return fmt::format("{:.4f} [{:.3f}, {:.3f}]", i.estimate, i.low, i.high);
}
// What `ipd breakdown` was asked for.
struct BreakdownArgs {
  StudyOptions study;
  std::string by = "size", format = "text";
  int bins = 4;
  bool all_cells = false;
};

void declare_breakdown_options(CLI::App* cmd, BreakdownArgs* args) {
  add_study_options(cmd, &args->study, true);
  cmd->add_option("--by", args->by,
                  "size (box area, px²), region (3x3 grid) or confidence (of its best-IoU prediction)")
      ->check(CLI::IsMember({"size", "region", "confidence"}));
  cmd->add_option("--bins", args->bins, "Quantile bins for size and confidence")
      ->check(CLI::Range(1, kMaxBreakdownBins))
      ->default_val(4);
  cmd->add_option("--format", args->format, "text, csv, json or markdown")
      ->check(CLI::IsMember({"text", "csv", "json", "markdown"}));
  cmd->add_flag("--all-cells", args->all_cells, "Also the cells that don't involve the model's training domain");
}

void print_breakdown_json(const std::vector<CellBreakdown>& out, const std::string& by, const BootstrapOptions& boot,
                          const Provenance& provenance) {
  nlohmann::ordered_json j = {
      {"by", by}, {"bootstrap", {{"resamples", boot.resamples}, {"level", boot.level}, {"seed", boot.seed}}}};
  j["cells"] = nlohmann::ordered_json::array();
  for (const auto& c : out) {
    nlohmann::ordered_json bins = nlohmann::ordered_json::array();
    for (const auto& b : c.bins)
      bins.push_back({{"bin", b.label},
                      {"low", json_number(b.low)},
                      {"high", json_number(b.high)},
                      {"ipd", json_number(b.ipd.estimate)},
                      {"ci_low", json_number(b.ipd.low)},
                      {"ci_high", json_number(b.ipd.high)},
                      {"pairs", b.pairs},
                      {"scenes", b.scenes}});
    j["cells"].push_back({{"model", c.model}, {"trained_on", c.trained_on}, {"a", c.a}, {"b", c.b}, {"bins", bins}});
  }
  j["provenance"] = provenance_json(provenance);
  std::cout << dump_json_output(j, 2) << "\n";
}

void print_breakdown_csv(const std::vector<CellBreakdown>& out, const Provenance& provenance) {
  const auto prov = provenance_csv_fields(provenance);
  std::cout << "model,trained_on,a,b,bin,low,high,ipd,ci_low,ci_high,pairs,scenes";
  for (const auto& [name, value] : prov) std::cout << "," << name;
  std::cout << "\n";
  auto n = [](double v) { return std::isnan(v) ? std::string() : fmt::format("{:.6g}", v); };
  for (const auto& c : out)
    for (const auto& b : c.bins) {
      std::vector<std::string> fields = {c.model,
                                         c.trained_on,
                                         c.a,
                                         c.b,
                                         b.label,
                                         n(b.low),
                                         n(b.high),
                                         n(b.ipd.estimate),
                                         n(b.ipd.low),
                                         n(b.ipd.high),
                                         std::to_string(b.pairs),
                                         std::to_string(b.scenes)};
      for (const auto& [name, value] : prov) fields.push_back(value);
      std::cout << csv_row(fields);
    }
}

// Text or Markdown: one block per cell, then the interval settings and where the numbers come from.
void print_breakdown_text(const std::vector<CellBreakdown>& out, const BreakdownArgs& args,
                          const BootstrapOptions& boot, const Provenance& provenance) {
  const std::string ref_note = "bins of the first domain's rock; ";
  const bool md = args.format == "markdown";
  for (const auto& c : out) {
    std::cout << fmt::format("{}{} ({}), |{} - {}|, by {}:\n", md ? "**" : "", c.model, c.trained_on, c.a, c.b,
                             args.by);
    if (c.bins.empty()) {  // no rock pairs: bins of nothing would read "nan–nan"
      std::cout << (md ? "**\n\n" : "  ") << kNoRockPairsToBin << "\n\n";
      continue;
    }
    std::cout << (md ? "**\n\n| bin | IPD [CI] | pairs | scenes |\n|---|---:|---:|---:|\n" : "");
    for (const auto& b : c.bins)
      std::cout << (md ? fmt::format("| {} | {} | {} | {} |\n", b.label, interval_text(b.ipd), b.pairs, b.scenes)
                       : fmt::format("  {:<22} {:<26} {:>5} pairs {:>4} scenes\n", b.label, interval_text(b.ipd),
                                     b.pairs, b.scenes));
    std::cout << "\n";
  }
  std::cout << fmt::format("({}{:g}% scene-bootstrap intervals, {} resamples, seed {})\n", ref_note, 100 * boot.level,
                           grouped_thousands(boot.resamples), boot.seed);
  std::cout << provenance_note(provenance) << "\n";
}

int run_breakdown(const BreakdownArgs& args) {
  // Without --all-cells the breakdown reads the cells of a model's training domain only, as the table shows.
  auto loaded = load_study_table(args.study, false, {!args.all_cells, {}, false});
  if (!loaded) return kBadInput;
  if (args.format == "json") require_utf8_names(loaded->labels.study);
  BreakdownOptions bo;
  parse_breakdown_by(args.by, &bo.by);
  bo.bins = args.bins;
  bo.bootstrap = loaded->bootstrap;
  std::vector<CellBreakdown> out;
  for (const auto& cell : loaded->table.cells) {
    if (cell.missing_predictions || (!cell.involves_training_domain && !args.all_cells)) continue;
    if (!cell.no_value_reason.empty()) {  // bins of two empty prediction sets would all read 0
      fmt::print(stderr, "warning: model '{}': IPD({}, {}) is not a number: {}; no breakdown\n", cell.model, cell.a,
                 cell.b, cell.no_value_reason);
      continue;
    }
    out.push_back(breakdown_cell(loaded->labels, cell, bo));
  }
  // Which label files and hand edits the bins' numbers come from: a JSON object, CSV columns, a text line.
  const Provenance provenance = table_provenance(loaded->table, loaded->labels);
  if (args.format == "json")
    print_breakdown_json(out, args.by, bo.bootstrap, provenance);
  else if (args.format == "csv")
    print_breakdown_csv(out, provenance);
  else
    print_breakdown_text(out, args, bo.bootstrap, provenance);
  return kOk;
}

}  // namespace

Runner add_breakdown_command(CLI::App& app) {
  auto args = std::make_shared<BreakdownArgs>();
  CLI::App* cmd = app.add_subcommand("breakdown", "IPD per bin of the reference rock's size, region or confidence");
  declare_breakdown_options(cmd, args.get());
  return [args]() -> int { return run_breakdown(*args); };
}

}  // namespace ipd::cli
