// The task every number is about (ipd.h: settle_task): box IoU, or mask IoU when every instance has an outline.
#include <fmt/format.h>

#include "core/ipd/ipd.h"

namespace ipd {

namespace {

struct OutlineCount {
  long with = 0, without = 0;
  std::string first_without;  // FILE:LINE of the first instance without an outline
  void add(const LabelFile& f) {
    for (size_t k = 0; k < f.boxes.size(); ++k) {
      if (f.boxes[k].outline) {
        ++with;
        continue;
      }
      if (without++ == 0) first_without = fmt::format("{}:{}", f.path, f.line_of_box[k]);
    }
  }
};

}  // namespace

void settle_task(StudyLabels* labels) {
  OutlineCount gt, pred;
  for (const auto& [d, stems] : labels->gt)
    for (const auto& [stem, f] : stems) gt.add(f);
  for (const auto& [d, models] : labels->predictions)
    for (const auto& [m, stems] : models)
      for (const auto& [stem, f] : stems) pred.add(f);
  labels->task_needs_outlines.clear();
  labels->task_note.clear();
  if (labels->study.config.task == Task::kDetect) {
    if (gt.with + pred.with > 0)
      labels->task_note = fmt::format(
          "{} of the instances have outlines (masks); every number here is about their boxes (the outlines' "
          "bounds) as task detect; --task segment (or task: segment in study.yaml) scores them by mask IoU",
          gt.with + pred.with);
    return;
  }
  // A box without an outline would be scored as the mask of its rectangle: a number that mixes box and mask
  // IoU. Refused, with where the first one is, as a class mix is.
  if (gt.without + pred.without == 0) return;
  std::string counts;
  if (gt.without > 0)
    counts +=
        fmt::format("{} of {} ground-truth instances (first: {})", gt.without, gt.with + gt.without, gt.first_without);
  if (pred.without > 0)
    counts += fmt::format("{}{} of {} predictions (first: {})", counts.empty() ? "" : " and ", pred.without,
                          pred.with + pred.without, pred.first_without);
  labels->task_needs_outlines = fmt::format(
      "{}: task segment scores each instance by mask IoU, but {} are boxes without an outline (a YOLO-seg line "
      "`class x1 y1 ... xn yn`); give them outlines, or use --task detect for box IoU",
      labels->study.root, counts);
}

void require_choices(const StudyLabels& labels) {
  require_class_choice(labels);
  if (!labels.task_needs_outlines.empty()) throw StudyError(labels.task_needs_outlines);
}

}  // namespace ipd
