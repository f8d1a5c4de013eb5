// `ipd figure pairs|registration|table STUDY`: the paper's figures, rendered headless (OSMesa) with the same
// drawing code as ipd-studio.
#include <fmt/format.h>

#include <Eigen/Core>
#include <cmath>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "cli_common.h"
#include "commands.h"
#include "figures.h"
#include "ipd/affine_estimator.h"
#include "ipd/atomic_file.h"
#include "ipd/ipd.h"
#include "offscreen_renderer.h"

namespace ipd::cli {

namespace {

struct Args {
  std::string study, scene, a, b, model, out;
  int width = 2400;
  bool skip_bad_lines = false;
};

// The study, the chosen domain pair and model, the scene and its pairing.
struct FigureScene {
  StudyLabels labels;
  std::string a, b, model, stem;
  ScenePairing pairing;
  SceneIpd ipd;
};

FigureScene resolve(const Args& args, bool needs_scene) {
  FigureScene f{load_labels(open_study(args.study)), {}, {}, {}, {}, {}, {}};
  const Study& st = f.labels.study;
  if (report_label_errors(f.labels.errors, args.skip_bad_lines))
    throw StudyError(st.root + ": malformed label lines (listed above)");
  if (st.domains.size() < 2) throw StudyError(st.root + ": a figure needs two domains, this study has one");
  f.a = args.a.empty() ? st.domains[0].name : args.a;
  f.b = args.b.empty() ? (st.domains[0].name == f.a ? st.domains[1].name : st.domains[0].name) : args.b;
  for (const auto& d : {f.a, f.b})
    if (!st.domain(d)) throw StudyError(fmt::format("{}: no domain '{}' in this study", st.root, d));
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
  RegistrationOptions reg = st.config.registration;
  reg.aspect = st.aspect();
  f.stem = args.scene;
  if (!f.stem.empty() && std::find(match.common.begin(), match.common.end(), f.stem) == match.common.end())
    throw StudyError(fmt::format("{}: no scene '{}' in both '{}' and '{}'", st.root, f.stem, f.a, f.b));
  if (f.stem.empty() && !f.model.empty()) {
    // The scene a reviewer asks about: the largest contribution to IPD(a, b).
    TableOptions opt;
    opt.domains = {f.a, f.b};
    opt.models = {f.model};
    opt.registration = reg;
    const CrossTable t = compute_cross_table(f.labels, opt);
    double worst = -1;
    for (const auto& s : t.cells.front().per_scene)
      if (s.sum_abs_diff > worst) worst = s.sum_abs_diff, f.stem = s.stem;
    fmt::print(stderr, "scene {}: it contributes most to IPD({}, {}) for {}\n", f.stem, f.a, f.b, f.model);
  }
  if (f.stem.empty()) f.stem = match.common.front();
  f.pairing = pair_scene(f.labels, f.a, f.b, f.stem, reg);
  f.ipd = scene_ipd(f.pairing, f.labels.gt_of(f.a, f.stem).boxes, f.labels.predictions_of(f.a, f.model, f.stem).boxes,
                    f.labels.gt_of(f.b, f.stem).boxes, f.labels.predictions_of(f.b, f.model, f.stem).boxes);
  return f;
}

float font_px_for(int width) { return std::max(13.0f, width / 75.0f); }

void write_png(const cv::Mat& img, const std::string& path) {
  std::vector<uchar> png;
  if (!cv::imencode(".png", img, png)) throw IoError(path + ": PNG encoding failed");
  write_file_atomically(path, std::string(png.begin(), png.end()));
  fmt::print("{}\n", path);
}

int pairs_figure(const Args& args) {
  const FigureScene f = resolve(args, true);
  const Study& st = f.labels.study;
  struct Loaded {
    cv::Mat picture;
    std::string problem;
  };
  auto load = [&](const std::string& domain) {
    Loaded l;
    const auto it = st.domain(domain)->images.find(f.stem);
    if (it == st.domain(domain)->images.end()) return l;
    l.picture = cv::imread(it->second, cv::IMREAD_COLOR);
    if (l.picture.empty()) l.problem = "cannot decode " + it->second;
    return l;
  };
  const Loaded la = load(f.a), lb = load(f.b);
  int iw = st.config.image_width, ih = st.config.image_height;
  if (!la.picture.empty()) iw = la.picture.cols, ih = la.picture.rows;
  const float px = font_px_for(args.width);
  const int height = static_cast<int>(std::ceil(ui::pairs_figure_height(args.width, px, iw, ih)));
  figure::OffscreenRenderer r(args.width, height, px, figure::figure_font_file());
  auto side = [&](const std::string& domain, const Loaded& l, bool left) {
    ui::SideInput in;
    if (!l.picture.empty()) in.texture = r.upload(l.picture, args.width);
    in.image_w = iw;
    in.image_h = ih;
    in.placeholder = l.problem.empty() && l.picture.empty() ? "no picture" : l.problem;
    in.gt = &f.labels.gt_of(domain, f.stem).boxes;
    in.predictions = &f.labels.predictions_of(domain, f.model, f.stem).boxes;
    in.best_prediction = performance_values(*in.gt, *in.predictions).best_prediction;
    in.number = ui::pair_numbers(f.pairing.pairs, in.gt->size(), left);
    in.caption = domain;
    return in;
  };
  ui::PairsFigure fig;
  fig.left = side(f.a, la, true);
  fig.right = side(f.b, lb, false);
  fig.title = fmt::format("{}: {} vs {}, model {}, scene IPD {} ({} pairs){}", f.stem, f.a, f.b,
                          f.model.empty() ? "none" : f.model,
                          std::isnan(f.ipd.ipd()) ? std::string("n/a") : fmt::format("{:.4f}", f.ipd.ipd()),
                          f.ipd.pairs, f.pairing.fixed ? ", pairs fixed by hand" : "");
  write_png(r.render([&](ImDrawList* dl, ImVec2 size) { ui::draw_pairs_figure(dl, size, px, fig); }), args.out);
  return kOk;
}

int registration_figure(const Args& args) {
  const FigureScene f = resolve(args, true);
  const Study& st = f.labels.study;
  ui::RegistrationFigure fig;
  fig.name_a = f.a;
  fig.name_b = f.b;
  for (const auto& b : f.labels.gt_of(f.a, f.stem).boxes) fig.a.push_back(b.centre());
  for (const auto& b : f.labels.gt_of(f.b, f.stem).boxes) fig.b.push_back(b.centre());
  fig.pairs = f.pairing.pairs;
  fig.affine = f.pairing.registration.affine;
  if (f.pairing.fixed) {
    // Pairs fixed by hand: show the affine that best fits them.
    std::vector<Eigen::Vector2d> src, dst;
    for (const auto& [i, j] : fig.pairs) src.push_back(fig.a[i]), dst.push_back(fig.b[j]);
    Affine2 m;
    fig.affine = affine_least_squares(src, dst, &m) ? m : identity_affine();
  }
  if (st.config.image_width > 0) fig.image_w = st.config.image_width, fig.image_h = st.config.image_height;
  fig.title = fmt::format("{}: GT box centres of {} and {}, {} ({} pairs)", f.stem, f.a, f.b,
                          f.pairing.fixed ? "pairs fixed by hand" : std::string("registration: ") +
                                                                          to_string(f.pairing.registration.method),
                          fig.pairs.size());
  const float px = font_px_for(args.width);
  const int height = static_cast<int>(std::ceil(ui::registration_figure_height(args.width, px, fig.image_w, fig.image_h)));
  figure::OffscreenRenderer r(args.width, height, px, figure::figure_font_file());
  write_png(r.render([&](ImDrawList* dl, ImVec2 size) { ui::draw_registration_figure(dl, size, px, fig); }), args.out);
  return kOk;
}

int table_figure(const Args& args) {
  const FigureScene f = resolve(args, false);
  TableOptions opt;
  opt.registration = f.labels.study.config.registration;
  const CrossTable t = compute_cross_table(f.labels, opt);
  for (const auto& w : t.warnings) fmt::print(stderr, "warning: {}\n", w);
  ui::TableFigure fig;
  fig.title = "Instance Performance Difference (lower is better)";
  fig.header.push_back("Train \\ Eval");
  for (const auto& [a, b] : t.columns) fig.header.push_back("|" + a + " - " + b + "|");
  const size_t nc = t.columns.size();
  for (size_t r = 0; r < t.models.size(); ++r) {
    const auto& m = t.models[r];
    std::vector<std::string> row = {m.trained_on.empty() ? m.name : m.name + " (" + m.trained_on + ")"};
    std::vector<char> bold(nc + 1, 0);
    double best = INFINITY;
    for (size_t c = 0; c < nc; ++c) {
      const auto& cell = t.cells[r * nc + c];
      if (cell.involves_training_domain && !std::isnan(cell.ipd)) best = std::min(best, cell.ipd);
    }
    for (size_t c = 0; c < nc; ++c) {
      const auto& cell = t.cells[r * nc + c];
      row.push_back(!cell.involves_training_domain ? "-" : std::isnan(cell.ipd) ? "n/a" : fmt::format("{:.4f}", cell.ipd));
      bold[c + 1] = cell.involves_training_domain && cell.ipd == best;
    }
    fig.rows.push_back(row);
    fig.bold.push_back(bold);
  }
  fig.note = "Rows: detector and its training domain. \"-\": pair not involving the training domain.";
  const float px = font_px_for(std::min(args.width, 1600));
  const int height = static_cast<int>(std::ceil(ui::table_figure_height(px, fig)));
  figure::OffscreenRenderer r(args.width, height, px, figure::figure_font_file());
  cv::Mat img = r.render([&](ImDrawList* dl, ImVec2 size) { ui::draw_table_figure(dl, size, px, fig); });
  // A table is usually narrower than --width: crop the white margin on the right.
  cv::Mat grey, ink;
  cv::cvtColor(img, grey, cv::COLOR_BGR2GRAY);
  cv::findNonZero(grey < 250, ink);
  if (!ink.empty()) {
    const cv::Rect box = cv::boundingRect(ink);
    img = img(cv::Rect(0, 0, std::min(img.cols, box.x + box.width + static_cast<int>(px)), img.rows)).clone();
  }
  write_png(img, args.out);
  return kOk;
}

}  // namespace

Runner add_figure_command(CLI::App& app) {
  auto args = std::make_shared<Args>();
  auto which = std::make_shared<std::string>();
  CLI::App* fig = app.add_subcommand("figure", "Figures for papers, rendered headless (OSMesa)");
  fig->require_subcommand(1);
  auto add = [&](const char* name, const char* what, bool scene_options) {
    CLI::App* cmd = fig->add_subcommand(name, what);
    cmd->add_option("STUDY", args->study, "Study directory")->required();
    if (scene_options) {
      cmd->add_option("--scene", args->scene, "Scene stem (default: the one contributing most to the IPD)");
      cmd->add_option("--a", args->a, "Left domain (default: the first, usually real)");
      cmd->add_option("--b", args->b, "Right domain (default: the second)");
      cmd->add_option("--model", args->model, "Model whose predictions count (default: one trained on --a)");
    }
    cmd->add_option("--out", args->out, "PNG file to write (atomically)")->required();
    cmd->add_option("--width", args->width, "Width in pixels; text scales with it")->check(CLI::Range(320, 8000));
    cmd->add_flag("--skip-bad-lines", args->skip_bad_lines, "Warn about malformed label lines and skip them");
    cmd->callback([which, name] { *which = name; });
  };
  add("pairs", "Fig. 1: both pictures side by side, GT (pink, pair numbers) and predictions (red, confidence)", true);
  add("registration", "Fig. 2: GT centres before and after registration, lines between partners", true);
  add("table", "The cross table (Table I) as a picture", false);
  return [args, which]() -> int {
    if (*which == "pairs") return pairs_figure(*args);
    if (*which == "registration") return registration_figure(*args);
    return table_figure(*args);
  };
}

}  // namespace ipd::cli
