// `ipd figure sweep STUDY --ref real --model det-real --out sweep.pdf`: IPD(ref, variant) along the parameter the
// variants differ in, from the ranking `ipd rank` prints (the same numbers, the same best and group).
#include <fmt/format.h>

#include "app/cli/cli_common.h"
#include "app/cli/commands.h"
#include "app/cli/figure_cli.h"
#include "app/cli/rank_study.h"
#include "ui/figures/figure_provenance.h"
#include "ui/figures/figure_sweep.h"

namespace ipd::cli {

Runner add_figure_sweep_command(CLI::App* fig, std::shared_ptr<std::string> which) {
  struct Args {
    RankArgs rank;
    FigureOutputArgs output;
  };
  auto args = std::make_shared<Args>();
  CLI::App* cmd = fig->add_subcommand(
      "sweep",
      "IPD(ref, variant) along the parameter the variants differ in (study.yaml's domains params), the interval as "
      "a band, the best and the settings not distinguishable from it marked; two parameters: a heat map");
  add_rank_options(cmd, &args->rank);
  add_figure_output_options(cmd, &args->output);
  cmd->callback([which] { *which = "sweep"; });
  return [args]() -> int {
    ui::FigureOptions o;
    if (const int rc = figure_options(args->output, &o)) return rc;
    if (output_is_study_input(args->rank.study.study, args->output.out)) return kBadInput;
    auto ranked = rank_study(args->rank);
    if (!ranked) return kBadInput;
    const ui::SweepChart chart = ui::sweep_chart(ranked->ranking);
    const ui::FontMetrics metrics(o.font_file);
    ui::DisplayList figure(metrics);
    ui::draw_sweep_chart(figure, chart, o);
    ui::add_provenance(figure, ranked->provenance, o);
    write_figure(figure, metrics, o, ranked->loaded.labels.study.root, args->output.out, chart.title);
    return kOk;
  };
}

}  // namespace ipd::cli
