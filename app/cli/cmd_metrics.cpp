// `ipd metrics STUDY [--images]`: AP@0.5, AP@0.5:0.95, precision / recall / F1 per model and domain, and with
// --images SSIM / PSNR per domain pair with the Spearman correlation of per-scene SSIM and IPD.
#include <fmt/format.h>

#include <iostream>
#include <map>
#include <nlohmann/json.hpp>

#include "app/cli/cli_common.h"
#include "app/cli/commands.h"
#include "app/cli/study_options.h"
#include "core/stats/detection_metrics.h"
#include "core/stats/image_metrics.h"
#include "core/stats/study_statistics.h"
#include "core/util/json_output.h"

namespace ipd::cli {

namespace {
std::string fixed(double v, int digits) { return std::isnan(v) ? "n/a" : fmt::format("{:.{}f}", v, digits); }
std::string with_ci(const Interval& i, int digits) {
  if (!i.has_interval()) return fixed(i.estimate, digits);
  return fmt::format("{:.{}f} [{:.{}f}, {:.{}f}]", i.estimate, digits, i.low, digits, i.high, digits);
}
// Mean of per-scene values with its scene-bootstrap interval (each scene weighs one).
Interval mean_with_ci(const std::vector<double>& v, const BootstrapOptions& o, const std::string& key) {
  std::vector<SceneSum> s;
  for (double x : v)
    if (std::isfinite(x)) s.push_back({x, 1});
  return bootstrap_pooled_mean(s, o, key);
}

// What `ipd metrics` was asked for.
struct MetricsArgs {
  StudyOptions study;
  bool json = false, images = false;
};

void declare_metrics_options(CLI::App* cmd, MetricsArgs* args) {
  add_study_options(cmd, &args->study, true);
  cmd->add_flag("--json", args->json, "JSON: {\"metrics\": [...], \"images\": [...]}");
  cmd->add_flag("--images", args->images, "Also SSIM and PSNR of each scene pair's pictures (B warped onto A)");
}

// One row: JSON always names the class; the text names it beside the domain only when there are several.
void add_metrics_row(const std::string& model, const std::string& domain, const std::string& cls, bool several,
                     const DetectionMetrics& r, nlohmann::ordered_json* j, std::string* text);

// AP and precision / recall / F1 of each chosen model on each chosen domain, as JSON rows and text lines.
void add_detection_metrics(const Study& study, const StudyOptions& so, const StudyLabels& labels, double threshold,
                           nlohmann::ordered_json* j, std::string* text) {
  for (const auto& m : study.models) {
    if (!so.models.empty() && std::find(so.models.begin(), so.models.end(), m.name) == so.models.end()) continue;
    for (const auto& d : study.domains) {
      if (!so.domains.empty() && std::find(so.domains.begin(), so.domains.end(), d.name) == so.domains.end()) continue;
      if (!labels.has_predictions(d.name, m.name)) continue;
      // Per class, as pycocotools evaluates per category; class-blind (--class all) adds the mean over classes.
      std::vector<int> classes;
      if (labels.study.config.rock_class == kAllClasses)
        for (const auto& [cls, n] : labels.gt_boxes_by_class) classes.push_back(cls);
      else
        classes.push_back(labels.study.config.rock_class);
      double sum50 = 0, sum5095 = 0;
      int counted = 0;
      for (int cls : classes) {
        std::vector<DetectionImage> images;
        for (const auto& stem : d.stems) {
          DetectionImage im{labels.gt_of(d.name, stem).boxes, labels.predictions_of(d.name, m.name, stem).boxes,
                            labels.study.config.task};
          if (classes.size() > 1) {
            auto other = [cls](const Box& b) { return b.cls != cls; };
            im.gt.erase(std::remove_if(im.gt.begin(), im.gt.end(), other), im.gt.end());
            im.detections.erase(std::remove_if(im.detections.begin(), im.detections.end(), other), im.detections.end());
          }
          images.push_back(std::move(im));
        }
        const DetectionMetrics r = detection_metrics(images, threshold);
        if (std::isfinite(r.ap50)) sum50 += r.ap50, sum5095 += r.ap50_95, ++counted;
        add_metrics_row(m.name, d.name, cls < 0 ? std::string() : labels.study.classes.name_of(cls), classes.size() > 1,
                        r, j, text);
      }
      if (classes.size() > 1) {
        DetectionMetrics mean;
        if (counted > 0) mean.ap50 = sum50 / counted, mean.ap50_95 = sum5095 / counted;
        add_metrics_row(m.name, d.name, "mean", true, mean, j, text);
      }
    }
  }
  *text += fmt::format(
      "({}; AP: pycocotools' rules over the {} most confident detections of each picture, within a class; "
      "precision/recall/F1 over every detection at confidence >= {:g} and IoU 0.5{})\n",
      class_statement(labels), kCocoMaxDetections, threshold,
      labels.study.config.task == Task::kSegment ? "; every IoU a mask IoU (task segment, pycocotools' iouType "
                                                   "'segm')"
                                                 : "");
}

void add_metrics_row(const std::string& model, const std::string& domain, const std::string& cls, bool several,
                     const DetectionMetrics& r, nlohmann::ordered_json* j, std::string* text) {
  (*j)["metrics"].push_back({{"model", model},
                             {"domain", domain},
                             {"class", cls},
                             {"ap50", json_number(r.ap50)},
                             {"ap50_95", json_number(r.ap50_95)},
                             {"precision", json_number(r.precision)},
                             {"recall", json_number(r.recall)},
                             {"f1", json_number(r.f1)},
                             {"gt", r.gt},
                             {"detections", r.detections}});
  *text += fmt::format("{:<24} {:<12} {:>7} {:>9} {:>9} {:>7} {:>7} {:>6} {:>6}\n", model,
                       several ? domain + " " + cls : domain, fixed(r.ap50, 4), fixed(r.ap50_95, 4),
                       fixed(r.precision, 4), fixed(r.recall, 4), fixed(r.f1, 4), r.gt, r.detections);
}

// Spearman's rho of per-scene SSIM against per-scene IPD, for each model with predictions in column c: whether
// scenes that look less alike also score less alike.
void add_ssim_ipd_correlations(const CrossTable& t, size_t c, const std::vector<ScenePixelMetrics>& px,
                               nlohmann::ordered_json* rho, std::string* rho_text) {
  const auto& [a, b] = t.columns[c];
  for (const auto& m : t.models) {
    const TableCell* cell = t.cell(m.name, a, b);
    if (!cell || cell->missing_predictions) continue;
    std::map<std::string, double> scene_ipd;
    for (const auto& s : cell->per_scene)
      if (s.pairs > 0) scene_ipd[s.stem] = s.ipd();
    std::vector<double> x, y;
    for (const auto& s : px)
      if (scene_ipd.count(s.stem)) {
        x.push_back(s.ssim);
        y.push_back(scene_ipd[s.stem]);
      }
    const double r = spearman(x, y);
    rho->push_back({{"model", m.name}, {"rho", json_number(r)}, {"scenes", x.size()}});
    *rho_text += fmt::format("{}{} {}", rho_text->empty() ? "" : ", ", m.name, fixed(r, 2));
  }
}

// SSIM and PSNR of each domain pair's pictures with their intervals, as JSON rows and text lines; false when the
// study's table could not be loaded (the problem is already reported).
bool add_image_metrics(const StudyOptions& so, nlohmann::ordered_json* j, std::string* text) {
  auto loaded = load_study_table(so, false);
  if (!loaded) return false;
  const CrossTable& t = loaded->table;
  (*j)["images"] = nlohmann::ordered_json::array();
  *text += fmt::format("\n{:<26} {:>6} {:<26} {:<26} {}\n", "domain pair", "scenes", "SSIM [CI]", "PSNR dB [CI]",
                       "Spearman(SSIM, scene IPD)");
  std::vector<std::string> problems;
  const StudyPixelMetrics all = pixel_metrics_all_columns(loaded->labels, t, so.threads, &problems);
  for (const auto& p : problems) fmt::print(stderr, "warning: {}\n", p);
  for (size_t c = 0; c < t.columns.size(); ++c) {
    const auto& [a, b] = t.columns[c];
    const auto& px = all.columns[c];
    std::vector<double> ssims, psnrs;
    for (const auto& s : px) {
      ssims.push_back(s.ssim);
      psnrs.push_back(s.psnr);
    }
    const std::string key = a + "|" + b;
    const Interval ssim_ci = mean_with_ci(ssims, loaded->bootstrap, key + "|ssim");
    const Interval psnr_ci = mean_with_ci(psnrs, loaded->bootstrap, key + "|psnr");
    nlohmann::ordered_json rho = nlohmann::ordered_json::array();
    std::string rho_text;
    add_ssim_ipd_correlations(t, c, px, &rho, &rho_text);
    (*j)["images"].push_back({{"a", a},
                              {"b", b},
                              {"scenes", px.size()},
                              {"ssim", json_number(ssim_ci.estimate)},
                              {"ssim_ci_low", json_number(ssim_ci.low)},
                              {"ssim_ci_high", json_number(ssim_ci.high)},
                              {"psnr", json_number(psnr_ci.estimate)},
                              {"psnr_ci_low", json_number(psnr_ci.low)},
                              {"psnr_ci_high", json_number(psnr_ci.high)},
                              {"spearman", rho}});
    *text += fmt::format("{:<26} {:>6} {:<26} {:<26} {}\n", a + " - " + b, px.size(), with_ci(ssim_ci, 3),
                         with_ci(psnr_ci, 2), rho_text.empty() ? "n/a" : rho_text);
  }
  *text += fmt::format(
      "(SSIM: Gaussian σ = 1.5, 11 taps, grey levels, over the overlap after warping B onto A "
      "with the registration affine; {:g}% scene-bootstrap intervals)\n",
      100 * loaded->bootstrap.level);
  return true;
}

int run_metrics(const MetricsArgs& args) {
  const StudyOptions& so = args.study;
  Study study = open_study_with_conf(so);
  if (args.json) require_utf8_names(study);  // before the work, naming the file
  const double threshold = study.config.conf_threshold;
  // AP ranks the detections in the files as pycocotools would be given them (at most kCocoMaxDetections a
  // picture); P/R/F1 use the threshold.
  Study all_detections = study;
  all_detections.config.conf_threshold = 0;
  const StudyLabels labels = load_labels(all_detections);
  if (report_label_errors(labels.errors, so.skip_bad_lines)) return kBadInput;
  require_choices(labels);
  report_class_notes(labels);
  nlohmann::ordered_json j;
  j["conf_threshold"] = threshold;
  j["task"] = task_name(labels.study.config.task);  // box or mask IoU: the same keys hold either
  j["metrics"] = nlohmann::ordered_json::array();
  std::string text = fmt::format("{:<24} {:<12} {:>7} {:>9} {:>9} {:>7} {:>7} {:>6} {:>6}\n", "model", "domain", "AP50",
                                 "AP50:95", "precision", "recall", "F1", "GT", "dets");
  add_detection_metrics(study, so, labels, threshold, &j, &text);
  if (args.images && !add_image_metrics(so, &j, &text)) return kBadInput;
  std::cout << (args.json ? dump_json_output(j, 2) + "\n" : text);
  return kOk;
}

}  // namespace

Runner add_metrics_command(CLI::App& app) {
  auto args = std::make_shared<MetricsArgs>();
  CLI::App* cmd = app.add_subcommand("metrics", "AP, precision/recall/F1 per model and domain; --images: SSIM/PSNR");
  declare_metrics_options(cmd, args.get());
  return [args]() -> int { return run_metrics(*args); };
}

}  // namespace ipd::cli
