// `ipd figure pairs STUDY`: a picture of one image pair (Fig. 1 of the paper), drawn with OpenCV.
#include <fmt/format.h>

#include <cmath>
#include <opencv2/imgcodecs.hpp>

#include "cli_common.h"
#include "commands.h"
#include "ipd/atomic_file.h"
#include "ipd/ipd.h"
#include "ipd/scene_picture.h"

namespace ipd::cli {

namespace {

ScenePictureSide load_side(const StudyLabels& labels, const std::string& domain, const std::string& model,
                           const std::string& stem) {
  ScenePictureSide s;
  s.caption = domain;
  s.gt = labels.gt_of(domain, stem).boxes;
  s.predictions = labels.predictions_of(domain, model, stem).boxes;
  s.width = labels.study.config.image_width;
  s.height = labels.study.config.image_height;
  const Domain* d = labels.study.domain(domain);
  const auto it = d->images.find(stem);
  if (it != d->images.end()) {
    s.picture = cv::imread(it->second, cv::IMREAD_COLOR);
    if (s.picture.empty()) fmt::print(stderr, "warning: {}: cannot decode the picture; drawing a placeholder\n", it->second);
  }
  return s;
}

}  // namespace

Runner add_figure_command(CLI::App& app) {
  struct Args {
    std::string study, scene, a, b, model, out;
    int width = 2400;
    bool skip_bad_lines = false;
  };
  auto args = std::make_shared<Args>();
  CLI::App* fig = app.add_subcommand("figure", "Draw figures for papers");
  fig->require_subcommand(1);
  CLI::App* cmd = fig->add_subcommand("pairs", "Both pictures side by side with GT, predictions and rock pairs");
  cmd->add_option("STUDY", args->study, "Study directory")->required();
  cmd->add_option("--scene", args->scene, "Scene stem (default: the one contributing most to the IPD)");
  cmd->add_option("--a", args->a, "Left domain (default: the first, usually real)");
  cmd->add_option("--b", args->b, "Right domain (default: the second)");
  cmd->add_option("--model", args->model, "Model whose predictions to draw (default: one trained on --a)");
  cmd->add_option("--out", args->out, "PNG file to write")->required();
  cmd->add_option("--width", args->width, "Width of the figure in pixels")->check(CLI::Range(320, 16000));
  cmd->add_flag("--skip-bad-lines", args->skip_bad_lines, "Warn about malformed label lines and skip them");
  return [args]() -> int {
    const Study study = open_study(args->study);
    const StudyLabels labels = load_labels(study);
    if (report_label_errors(labels.errors, args->skip_bad_lines)) return kBadInput;
    if (study.domains.size() < 2) throw StudyError(study.root + ": a figure of a pair needs two domains");
    const std::string a = args->a.empty() ? study.domains[0].name : args->a;
    const std::string b = args->b.empty() ? (study.domains[0].name == a ? study.domains[1].name : study.domains[0].name)
                                          : args->b;
    for (const auto& d : {a, b})
      if (!study.domain(d)) throw StudyError(fmt::format("{}: no domain '{}' in this study", study.root, d));
    std::string model = args->model;
    if (model.empty()) {
      for (const auto& m : study.models)
        if (m.trained_on == a) model = m.name;
      if (model.empty() && !study.models.empty()) model = study.models.front().name;
    }
    TableOptions opt;
    opt.domains = {a, b};
    if (!model.empty()) opt.models = {model};
    opt.registration = study.config.registration;
    const CrossTable table = compute_cross_table(labels, opt);
    const TableCell* cell = table.cell(model, a, b);
    std::string stem = args->scene;
    if (stem.empty()) {
      double worst = -1;
      for (const auto& s : cell->per_scene)
        if (s.sum_abs_diff > worst) worst = s.sum_abs_diff, stem = s.stem;
      if (stem.empty()) throw StudyError(fmt::format("{}: no scene is present in both '{}' and '{}'", study.root, a, b));
      fmt::print(stderr, "scene {}: it contributes most to IPD({}, {}) for {}\n", stem, a, b, model);
    }
    const SceneMatch match = match_scenes(*study.domain(a), *study.domain(b));
    if (std::find(match.common.begin(), match.common.end(), stem) == match.common.end())
      throw StudyError(fmt::format("{}: no scene '{}' in both '{}' and '{}'", study.root, stem, a, b));
    RegistrationOptions reg = study.config.registration;
    reg.aspect = study.aspect();
    const ScenePairing pairing = pair_scene(labels, a, b, stem, reg);
    const SceneIpd s = scene_ipd(pairing, labels.gt_of(a, stem).boxes, labels.predictions_of(a, model, stem).boxes,
                                 labels.gt_of(b, stem).boxes, labels.predictions_of(b, model, stem).boxes);
    const std::string title = fmt::format("{}: {} vs {}, model {}, scene IPD {}, {} pairs", stem, a, b, model,
                                          std::isnan(s.ipd()) ? std::string("n/a") : fmt::format("{:.4f}", s.ipd()),
                                          s.pairs);
    const cv::Mat img = draw_scene_pair(load_side(labels, a, model, stem), load_side(labels, b, model, stem),
                                        pairing.pairs, title, args->width);
    std::vector<uchar> png;
    if (!cv::imencode(".png", img, png)) throw IoError(args->out + ": PNG encoding failed");
    write_file_atomically(args->out, std::string(png.begin(), png.end()));
    fmt::print("{}\n", args->out);
    return kOk;
  };
}

}  // namespace ipd::cli
