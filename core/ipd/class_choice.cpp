// The class every number is about (ipd.h: settle_class), and the signature of prediction sets whose class
// numbers are shifted against the ground truth's.
#include <fmt/format.h>

#include <map>

#include "core/ipd/ipd.h"

namespace ipd {

namespace {

// A prediction overlapping a GT box this much is a detection of it (COCO's AP50 rule).
constexpr double kSignatureIou = 0.5;
// A prediction class is "shifted" when at least this many of its detections land on GT of one other class, that
// other class takes this share of them, and it outnumbers detections of the prediction's own class this often.
constexpr long kSignatureMinDetections = 20;
constexpr double kSignatureShare = 0.8;
constexpr double kSignatureRatio = 4.0;

}  // namespace

std::vector<std::string> shifted_class_warnings(const StudyLabels& labels) {
  std::vector<std::string> out;
  for (const auto& [domain, models] : labels.predictions)
    for (const auto& [model, stems] : models) {
      std::map<int, std::map<int, long>> hits;  // prediction class -> GT class it detects -> count
      for (const auto& [stem, pred] : stems) {
        const LabelFile& gt = labels.gt_of(domain, stem);
        for (const Box& p : pred.boxes) {
          double best = kSignatureIou;
          int cls = -1;
          for (const Box& g : gt.boxes)
            if (const double v = iou(p, g); v >= best) best = v, cls = g.cls;
          if (cls >= 0) ++hits[p.cls][cls];
        }
      }
      std::string map, detail;
      for (const auto& [pc, by_gt] : hits) {
        long total = 0, own = 0, top = 0;
        int top_cls = -1;
        for (const auto& [gc, n] : by_gt) {
          total += n;
          if (gc == pc) own = n;
          if (gc != pc && n > top) top = n, top_cls = gc;
        }
        if (top < kSignatureMinDetections || top < kSignatureShare * static_cast<double>(total) ||
            top < kSignatureRatio * static_cast<double>(own))
          continue;
        map += fmt::format("{}{}:{}", map.empty() ? "" : ",", pc, top_cls);
        detail += fmt::format("{}{} of its {} boxes detect {} and {} {}", detail.empty() ? "" : "; ", top,
                              labels.study.classes.name_of(pc), labels.study.classes.name_of(top_cls), own,
                              labels.study.classes.name_of(pc));
      }
      if (map.empty()) continue;
      out.push_back(fmt::format(
          "{}/predictions/{}: the class numbers look shifted against the ground truth's ({} at IoU >= 0.5); if "
          "this model numbers its classes differently, give it a classes.txt or --class-map {}",
          domain, model, detail, map));
    }
  return out;
}

void settle_class(StudyLabels* labels) {
  labels->requested_class = labels->study.config.rock_class;
  labels->gt_boxes_by_class.clear();
  for (const auto& [d, stems] : labels->gt)
    for (const auto& [stem, f] : stems)
      for (const Box& b : f.boxes) ++labels->gt_boxes_by_class[b.cls];
  labels->class_choice_needed.clear();
  labels->class_warnings.clear();
  // Other classes are still there to compare with only when no single class was read.
  if (labels->requested_class == kAllClasses ||
      (labels->requested_class == kNoClassChosen && labels->gt_boxes_by_class.size() > 1))
    labels->class_warnings = shifted_class_warnings(*labels);
  if (labels->requested_class != kNoClassChosen) return;
  if (labels->gt_boxes_by_class.size() > 1) {
    labels->class_choice_needed = class_choice_message(*labels);
    return;
  }
  if (labels->gt_boxes_by_class.empty()) return;
  // One class in the ground truth: that is the class, and predictions of other classes can't score it.
  const int only = labels->gt_boxes_by_class.begin()->first;
  labels->study.config.rock_class = only;
  for (auto& [d, models] : labels->predictions)
    for (auto& [m, stems] : models)
      for (auto& [stem, f] : stems) keep_class(&f, only);
}

std::string class_choice_message(const StudyLabels& labels) {
  const StudyClasses& c = labels.study.classes;
  std::string counts, first;
  for (const auto& [cls, n] : labels.gt_boxes_by_class) {
    counts += fmt::format("{}{}: {} boxes", counts.empty() ? "" : ", ", c.describe(cls), n);
    if (first.empty()) first = c.name_of(cls) == fmt::format("class {}", cls) ? std::to_string(cls) : c.name_of(cls);
  }
  std::string message = fmt::format(
      "{}: the labels hold {} classes ({}), and an IPD that mixed them would score and pair one class against "
      "another; choose one with --class {} (or rock_class: {} in study.yaml), or --class all for a class-blind "
      "number",
      labels.study.root, labels.gt_boxes_by_class.size(), counts, first, first);
  for (const std::string& w : labels.class_warnings) message += "\n" + w;
  return message;
}

void require_class_choice(const StudyLabels& labels) {
  if (!labels.class_choice_needed.empty()) throw StudyError(labels.class_choice_needed);
}

std::string class_statement(const StudyLabels& labels) {
  const int cls = labels.study.config.rock_class;
  if (cls == kAllClasses) return "all, class-blind (--class all)";
  if (cls == kNoClassChosen) return "no class (no ground truth boxes)";
  return labels.study.classes.describe(cls);
}

}  // namespace ipd
