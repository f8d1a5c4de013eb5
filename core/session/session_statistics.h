// The statistics of ipd/study_statistics.h on ipd-studio's live session: its current pairs (hand edits
// included) and threshold as a CrossTable, every cell's interval, the current cell's per-scene IPD and size
// breakdown, and a renderer comparison. Pure: run it off the UI thread on an immutable Session.
#pragma once

#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/session/session.h"
#include "core/stats/study_statistics.h"

namespace ipd {

struct SessionStatisticsRequest {
  std::string model;  // the current cell: model and domain pair index
  int pair = 0;
  std::string ref, a, b;  // the comparison; empty ref: none
  BootstrapOptions bootstrap;
  int permutations = 2000;
  int threads = 1;
  bool operator==(const SessionStatisticsRequest& o) const;
};

struct SessionStatistics {
  SessionStatisticsRequest request;
  CrossTable table;  // the session's cells (per_scene from the session) with ci_low / ci_high / se
  std::vector<std::pair<std::string, double>> scene_ipd;  // current cell: (stem, IPD) of scenes with pairs
  std::optional<CellBreakdown> size;                      // current cell by rock size (quantile bins)
  std::optional<RendererComparison> comparison;
  std::string comparison_error;  // why there is none, when one was asked for
};

// The session's cross table: models × domain pairs, per_scene = its contributions (no pairings).
CrossTable session_table(const Session& session);
SessionStatistics compute_session_statistics(const Session& session, const SessionStatisticsRequest& request);

}  // namespace ipd
