// `ipd figure table|compare|distribution|breakdown STUDY --out FILE.pdf|svg|png`: the study-wide figures,
// built on the statistics of ipd/study_statistics.h (the numbers `ipd table --ci` prints).
#include <fmt/format.h>

#include "cli_common.h"
#include "commands.h"
#include "figure_cli.h"
#include "figure_stats.h"
#include "figure_table.h"
#include "study_options.h"

namespace ipd::cli {

namespace {

struct StatsArgs {
  StudyOptions study;
  FigureOutputArgs output;
  std::string ref, a, b, by = "size";
  int permutations = 2000, worst = 2, bins = 4;
};

// The model a one-model figure shows: --model, else one trained on `domain`, else the first.
std::string pick_model(const CrossTable& t, const StudyOptions& o, const std::string& domain) {
  if (!o.models.empty()) return o.models.front();
  for (const auto& m : t.models)
    if (m.trained_on == domain) return m.name;
  if (t.models.empty()) throw StudyError("the study has no model predictions to draw");
  return t.models.front().name;
}

int run(const std::string& kind, const StatsArgs& args) {
  ui::FigureOptions o;
  if (const int rc = figure_options(args.output, &o)) return rc;
  auto loaded = load_study_table(args.study, true);
  if (!loaded) return kBadInput;
  const CrossTable& t = loaded->table;
  const Study& st = loaded->labels.study;
  const ui::FontMetrics metrics(o.font_file);
  ui::DisplayList fig(metrics);
  std::string title;
  if (kind == "table") {
    ui::draw_table_figure(fig, ui::table_figure_of(t, args.study.ci_given), o);
    title = "IPD cross table";
  } else if (kind == "compare") {
    if (st.domains.size() < 3 && (args.ref.empty() || args.a.empty() || args.b.empty()))
      throw StudyError(st.root + ": compare needs three domains (a reference and two renderers)");
    const std::string ref = args.ref.empty() ? st.domains[0].name : args.ref;
    std::vector<std::string> others;
    for (const auto& d : st.domains)
      if (d.name != ref) others.push_back(d.name);
    const std::string a = args.a.empty() ? others.at(0) : args.a, b = args.b.empty() ? others.at(1) : args.b;
    CompareOptions co;
    co.bootstrap = loaded->bootstrap;
    co.permutations = args.permutations;
    if (const std::string bad = co.validate(); !bad.empty()) throw StudyError(bad);
    ui::draw_dot_whisker_chart(fig, ui::compare_chart(t, args.study.models, ref, a, b, co), o);
    title = fmt::format("IPD({0}, {1}) - IPD({0}, {2})", ref, a, b);
  } else if (kind == "distribution") {
    const std::string model = pick_model(t, args.study, st.domains.front().name);
    ui::draw_distribution_chart(fig, ui::distribution_chart(t, model, args.worst), o);
    title = "Per-scene IPD of " + model;
  } else {
    const std::string a = args.a.empty() ? st.domains.at(0).name : args.a;
    const std::string b = args.b.empty() ? (st.domains.at(0).name == a ? st.domains.at(1).name : st.domains.at(0).name) : args.b;
    const std::string model = pick_model(t, args.study, a);
    const TableCell* cell = t.cell(model, a, b);
    if (!cell) throw StudyError(fmt::format("{}: no IPD({}, {}) for model {} in this study", st.root, a, b, model));
    BreakdownOptions bo;
    if (!parse_breakdown_by(args.by, &bo.by)) {
      fmt::print(stderr, "error: --by: expected size, region or confidence, found '{}'\n", args.by);
      return kUsage;
    }
    bo.bins = args.bins;
    bo.bootstrap = loaded->bootstrap;
    if (const std::string bad = bo.validate(); !bad.empty()) throw StudyError(bad);
    ui::draw_dot_whisker_chart(fig, ui::breakdown_chart(breakdown_cell(loaded->labels, *cell, bo), bo.bootstrap.level), o);
    title = fmt::format("IPD({}, {}) by {}", a, b, args.by);
  }
  write_figure(fig, metrics, o, args.output.out, title);
  return kOk;
}

}  // namespace

Runner add_figure_stats_commands(CLI::App* fig, std::shared_ptr<std::string> which) {
  auto args = std::make_shared<StatsArgs>();
  auto add = [&](const char* name, const char* what) {
    CLI::App* cmd = fig->add_subcommand(name, what);
    add_study_options(cmd, &args->study, true);
    add_figure_output_options(cmd, &args->output);
    cmd->callback([which, name] { *which = name; });
    return cmd;
  };
  add("table", "The cross table (Table I) as a figure; --ci adds each cell's interval");
  CLI::App* cmp = add("compare", "Which renderer is closer to the reference: ΔIPD with its interval per model, p-values");
  cmp->add_option("--ref", args->ref, "Reference domain (default: the first, usually real)");
  cmp->add_option("--a", args->a, "First renderer (default: the second domain)");
  cmp->add_option("--b", args->b, "Second renderer (default: the third domain)");
  cmp->add_option("--permutations", args->permutations, "Sign-flip permutations for the p-value")->check(CLI::NonNegativeNumber);
  CLI::App* dist = add("distribution", "Per-scene IPD of one model for each domain pair (box plots, worst scenes named)");
  dist->add_option("--worst", args->worst, "How many worst scenes to name per domain pair")->check(CLI::Range(0, 20));
  CLI::App* br = add("breakdown", "IPD of one model and domain pair per bin of rock size, region or confidence");
  br->add_option("--by", args->by, "size, region or confidence")->check(CLI::IsMember({"size", "region", "confidence"}));
  br->add_option("--bins", args->bins, "Quantile bins for size and confidence")->check(CLI::Range(1, 20));
  br->add_option("--a", args->a, "Reference domain (default: the first)");
  br->add_option("--b", args->b, "Other domain (default: the second)");
  return [args, which]() -> int { return run(*which, *args); };
}

}  // namespace ipd::cli
