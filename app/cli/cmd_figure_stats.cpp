// `ipd figure table|compare|distribution|breakdown|gallery STUDY --out FILE.pdf|svg|png`: the study-wide
// figures, built on the statistics of ipd/study_statistics.h (the numbers `ipd table --ci` prints) and, for
// the gallery, on the counted rock pairs (core/session/rock_pair_points.h).
#include <fmt/format.h>

#include "app/cli/cli_common.h"
#include "app/cli/commands.h"
#include "app/cli/figure_cli.h"
#include "app/cli/study_options.h"
#include "core/stats/study_statistics.h"
#include "ui/figures/figure_study.h"

namespace ipd::cli {

namespace {

struct StatsArgs {
  StudyOptions study;
  FigureOutputArgs output;
  std::string ref, a, b, by = "size", sort = "diff", scene;
  int permutations = 2000, worst = 2, bins = 4, count = 8, rock = 0;
};

int run(const std::string& kind, const StatsArgs& args) {
  ui::FigureOptions o;
  if (const int rc = figure_options(args.output, &o)) return rc;
  if (output_is_study_input(args.study.study, args.output.out)) return kBadInput;
  o.ci = args.study.ci_given;
  o.by = args.by;
  ui::StudyFigureRequest r;
  r.kind = kind;
  if (!args.study.models.empty()) r.model = args.study.models.front();
  r.models = args.study.models;
  r.ref = args.ref;
  r.a = args.a;
  r.b = args.b;
  r.permutations = args.permutations;
  r.worst = args.worst;
  r.bins = args.bins;
  r.count = args.count;
  r.scene = args.scene;
  r.rock = args.rock;
  if (args.rock > 0 && args.scene.empty()) {
    fmt::print(stderr, "error: --rock {} needs --scene: rock numbers are a scene's\n", args.rock);
    return kUsage;
  }
  parse_gallery_sort(args.sort, &r.gallery_sort);
  if (kind == "gallery" && !args.study.domains.empty()) {
    if (args.study.domains.size() != 2) {
      fmt::print(stderr, "error: --domains: a gallery shows one domain pair, got {} domains\n",
                 args.study.domains.size());
      return kUsage;
    }
    r.a = args.study.domains[0], r.b = args.study.domains[1];
  }
  Study study = open_study_with_conf(args.study);
  // Only the domain pairs the figure draws are registered: a table's cells of a training domain, a
  // comparison's two pairs, a breakdown's or a gallery's one.
  const ShownPairs shown{kind == "table", ui::study_figure_domain_pairs(study, r), false};
  auto loaded = load_study_table(std::move(study), args.study, kind != "gallery", shown);  // a gallery: no intervals
  if (!loaded) return kBadInput;
  r.bootstrap = loaded->bootstrap;
  r.conf_threshold = loaded->conf_threshold;
  const ui::FontMetrics metrics(o.font_file);
  ui::DisplayList fig(metrics);
  const std::string title = ui::draw_study_figure(fig, loaded->table, loaded->labels, r, o);
  write_figure(fig, metrics, o, loaded->labels.study.root, args.output.out, title);
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
  CLI::App* cmp =
      add("compare", "Which renderer is closer to the reference: ΔIPD with its interval per model, p-values");
  cmp->add_option("--ref", args->ref, "Reference domain (default: the first, usually real)");
  cmp->add_option("--a", args->a, "First renderer (default: the second domain)");
  cmp->add_option("--b", args->b, "Second renderer (default: the third domain)");
  cmp->add_option("--permutations", args->permutations, "Sign-flip permutations for the p-value")
      ->check(CLI::NonNegativeNumber);
  CLI::App* dist =
      add("distribution", "Per-scene IPD of one model for each domain pair (box plots, worst scenes named)");
  dist->add_option("--worst", args->worst, "How many worst scenes to name per domain pair")->check(CLI::Range(0, 20));
  CLI::App* br = add("breakdown", "IPD of one model and domain pair per bin of rock size, region or confidence");
  br->add_option("--by", args->by, "size, region or confidence")
      ->check(CLI::IsMember({"size", "region", "confidence"}));
  br->add_option("--bins", args->bins, "Quantile bins for size and confidence")
      ->check(CLI::Range(1, kMaxBreakdownBins));
  br->add_option("--a", args->a, "Reference domain (default: the first)");
  br->add_option("--b", args->b, "Other domain (default: the second)");
  CLI::App* gallery = fig->add_subcommand(
      "gallery",
      "Crops of the rock pairs with the largest |perf A - perf B|, A | B side by side (GT and best prediction)");
  add_study_options(gallery, &args->study, false);
  add_figure_output_options(gallery, &args->output);
  gallery->callback([which] { *which = "gallery"; });
  gallery->add_option("--count", args->count, "How many pairs (default 8)")->check(CLI::Range(1, 200));
  gallery->add_option("--scene", args->scene, "Only this scene's pairs (its file stem)");
  gallery
      ->add_option("--rock", args->rock,
                   "With --scene: only the pair of this rock of the first domain (from 1), drawn across the column")
      ->check(CLI::Range(1, 1000000));
  gallery->add_option("--sort", args->sort, "diff, size, perf-a or perf-b (largest first; default diff)")
      ->check(CLI::IsMember({"diff", "size", "perf-a", "perf-b"}));
  return [args, which]() -> int { return run(*which, *args); };
}

}  // namespace ipd::cli
