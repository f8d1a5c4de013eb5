// The statistics of a study (ipd/study_statistics.h) as figures: `compare` (ΔIPD with its interval per
// model, p-values), `distribution` (per-scene IPD of one model per domain pair, worst scenes named) and
// `breakdown` (IPD per bin of rock size, region or confidence, with intervals).
#pragma once

#include <string>
#include <vector>

#include "core/stats/study_statistics.h"
#include "ui/figures/figure_charts.h"

namespace ipd::ui {

// One row per model with predictions in ref, a and b; models that can't be compared are named in the
// footnote.
DotWhiskerChart compare_chart(const CrossTable& table, const std::vector<std::string>& models, const std::string& ref,
                              const std::string& a, const std::string& b, const CompareOptions& options);

// One box per domain pair (column) of `model`'s row.
DistributionChart distribution_chart(const CrossTable& table, const std::string& model, int worst = 2);

DotWhiskerChart breakdown_chart(const CellBreakdown& breakdown, double level);

}  // namespace ipd::ui
