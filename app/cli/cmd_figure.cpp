// `ipd figure pairs|registration STUDY --out FILE.pdf|svg|png`: the scene figures at a physical size, drawn
// once through the figure canvas (ui/canvas/canvas.h): cairo for PDF and SVG, OSMesa + ImGui for PNG. The study-wide
// kinds (table, compare, distribution, breakdown) are in cmd_figure_stats.cpp.
#include <fmt/format.h>

#include <cmath>
#include <filesystem>

#include "app/cli/cli_common.h"
#include "app/cli/commands.h"
#include "app/cli/figure_cli.h"
#include "app/cli/study_options.h"
#include "core/io/label_io.h"
#include "core/ipd/ipd.h"
#include "core/util/atomic_file.h"
#include "ui/figures/figure_export.h"

namespace ipd::cli {

namespace {

struct Args {
  std::string study, scene, a, b, model;
  double conf = 0;
  bool skip_bad_lines = false;
  std::string class_word;
  std::string task_word;
  std::vector<std::string> class_map;
  FigureOutputArgs output;
};

// The chosen domains, model and scene of a study.
struct Chosen {
  StudyLabels labels;
  std::string a, b, model, stem;
};

// The labels with `model`'s predictions below `conf` left out, as the figure draws them.
StudyLabels confident_labels(const StudyLabels& labels, const std::string& model, double conf) {
  StudyLabels out = labels;
  for (auto& [domain, models] : out.predictions)
    if (const auto m = models.find(model); m != models.end())
      for (auto& [stem, file] : m->second) keep_confident(&file, conf);
  return out;
}

Chosen resolve(const Args& args, bool needs_scene) {
  Study study = open_study(args.study);
  apply_class_options(args.class_word, args.class_map, args.task_word, &study);
  Chosen f{load_labels(study), {}, {}, {}, {}};
  const Study& st = f.labels.study;
  if (report_label_errors(f.labels.errors, args.skip_bad_lines))
    throw StudyError(st.root + ": malformed label lines (listed above)");
  require_choices(f.labels);
  report_class_notes(f.labels);
  if (st.domains.size() < 2) throw StudyError(st.root + ": a figure needs two domains, this study has one");
  f.a = args.a.empty() ? st.domains[0].name : args.a;
  f.b = args.b.empty() ? (st.domains[0].name == f.a ? st.domains[1].name : st.domains[0].name) : args.b;
  for (const auto& d : {f.a, f.b}) st.require_domain(d);
  if (f.a == f.b) throw StudyError(fmt::format("{}: --a and --b are both '{}'", st.root, f.a));
  f.model = args.model;
  if (f.model.empty()) {
    for (const auto& m : st.models)
      if (m.trained_on == f.a && f.model.empty()) f.model = m.name;
    if (f.model.empty() && !st.models.empty()) f.model = st.models.front().name;
  }
  if (!needs_scene) return f;
  const SceneMatch match = match_scenes(*st.domain(f.a), *st.domain(f.b));
  if (match.common.empty())
    throw StudyError(fmt::format("{}: no scene is present in both '{}' and '{}'", st.root, f.a, f.b));
  f.stem = args.scene;
  if (!f.stem.empty() && std::find(match.common.begin(), match.common.end(), f.stem) == match.common.end())
    throw StudyError(fmt::format("{}: no scene '{}' in both '{}' and '{}'", st.root, f.stem, f.a, f.b));
  if (f.stem.empty() && !f.model.empty()) {
    // The scene a reader of the paper asks about first: the largest contribution to IPD(a, b).
    TableOptions opt;
    opt.domains = {f.a, f.b};
    opt.models = {f.model};
    opt.registration = st.config.registration;
    opt.registration.aspect = st.aspect();
    // Chosen among the predictions the figure draws: --conf above the study's threshold hides some, and the
    // scene that contributes most can change with them.
    const bool raised = args.conf > st.config.conf_threshold;
    const CrossTable t = compute_cross_table(raised ? confident_labels(f.labels, f.model, args.conf) : f.labels, opt);
    double worst = -1;
    for (const auto& s : t.cells.front().per_scene)
      if (s.sum_abs_diff > worst) worst = s.sum_abs_diff, f.stem = s.stem;
    fmt::print(stderr, "scene {}: it contributes most to IPD({}, {}) for {}{}\n", f.stem, f.a, f.b, f.model,
               raised ? fmt::format(" at conf \u2265 {:g}", args.conf) : "");
  }
  if (f.stem.empty()) f.stem = match.common.front();
  // The scene's hand pairs as `ipd table` judges them: moved rocks are a warning, unusable pairs an error
  // (the figure would otherwise show registration's pairs without a word).
  for (const PairsProblem& p :
       load_fixed_pairs(st, f.a, f.b, f.stem, f.labels.gt_of(f.a, f.stem).boxes, f.labels.gt_of(f.b, f.stem).boxes)
           .problems) {
    if (p.unusable && !args.skip_bad_lines)
      throw StudyError(p.to_string() + " (pass --skip-bad-lines to draw registration's pairs)");
    fmt::print(stderr, "warning: {}\n", p.to_string());
  }
  return f;
}

int scene_figure(const std::string& kind, const Args& args, const ui::FigureOptions& o) {
  const Chosen c = resolve(args, true);
  RegistrationOptions reg = c.labels.study.config.registration;
  reg.aspect = c.labels.study.aspect();
  ui::SceneFigureInput in = ui::scene_input_from_study(c.labels, c.a, c.b, c.model, c.stem, args.conf, reg);
  if (kind == "pairs") {
    ui::load_pictures(in, c.labels.study);
    // The figure still comes out (the picture's place says why it is empty): said here too, not only in the PDF.
    for (const std::string* problem : {&in.problem_a, &in.problem_b})
      if (!problem->empty()) fmt::print(stderr, "warning: {}\n", *problem);
  }
  const ui::FontMetrics metrics(o.font_file);
  write_figure(ui::scene_figure(kind, in, o, metrics), metrics, o, c.labels.study.root, args.output.out,
               c.stem + " " + c.a + " vs " + c.b);
  return kOk;
}

}  // namespace

Runner add_figure_command(CLI::App& app) {
  auto args = std::make_shared<Args>();
  auto which = std::make_shared<std::string>();
  CLI::App* fig = app.add_subcommand("figure", "Figures for papers: PDF, SVG or PNG at a column's width");
  fig->require_subcommand(1);
  auto add = [&](const char* name, const char* what) {
    CLI::App* cmd = fig->add_subcommand(name, what);
    cmd->add_option("STUDY", args->study, "Study directory")->required();
    cmd->add_option("--scene", args->scene, "Scene stem (default: the one contributing most to the IPD)");
    cmd->add_option("--a", args->a, "Left domain (default: the first, usually real)");
    cmd->add_option("--b", args->b, "Right domain (default: the second)");
    cmd->add_option("--model", args->model, "Model whose predictions count (default: one trained on --a)");
    cmd->add_option("--layers", args->output.layers,
                    "Comma-separated subset of gt,pred,conf,indices,pairs,legend (default: all but conf for a "
                    "single column)");
    cmd->add_option("--crop", args->output.crop,
                    "X0,Y0,X1,Y1: a region of the pictures, normalised to 0..1; auto: the rocks' extent");
    cmd->add_option("--panels", args->output.panels,
                    "auto (default), side or stacked: the two pictures side by side or one under the other")
        ->check(CLI::IsMember({"auto", "side", "stacked"}));
    cmd->add_option("--conf", args->conf, "Hide predictions below this confidence")->check(CLI::Range(0.0, 1.0));
    cmd->add_flag("--skip-bad-lines", args->skip_bad_lines, "Warn about malformed label lines and skip them");
    add_class_options(cmd, &args->class_word, &args->class_map, &args->task_word);
    add_figure_output_options(cmd, &args->output);
    cmd->callback([which, name] { *which = name; });
  };
  add("pairs",
      "Fig. 1: both pictures side by side, GT (yellow, solid, pair numbers) and predictions (blue, dashed, "
      "confidence)");
  add("registration", "Fig. 2: GT centres before and after registration, lines between partners");
  const Runner stats = add_figure_stats_commands(fig, which);
  const Runner sweep = add_figure_sweep_command(fig, which);
  return [args, which, stats, sweep]() -> int {
    if (*which == "sweep") return sweep();
    if (*which != "pairs" && *which != "registration") return stats();
    ui::FigureOptions o;
    if (const int rc = figure_options(args->output, &o)) return rc;
    if (output_is_study_input(args->study, args->output.out)) return kBadInput;
    return scene_figure(*which, *args, o);
  };
}

}  // namespace ipd::cli
