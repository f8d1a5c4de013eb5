// The ranking of `ipd rank` on ipd-studio's live session: the renderer settings (every domain but the reference)
// ranked by their IPD against the reference for one model, with the session's pairs (hand edits included) and
// threshold. The same rule as the command line (core/rank/ranking.h, rank_candidates) on the session's cells
// (session_table), only the (reference, candidate) cells given intervals. Pure: run it off the UI thread.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "core/rank/ranking.h"
#include "core/session/session.h"

namespace ipd {

struct SessionRankRequest {
  std::string model, ref;  // empty model: nothing to rank
  BootstrapOptions bootstrap;
  int permutations = 2000;
  double level = kSignificanceLevel;
  bool operator==(const SessionRankRequest& o) const;
};

struct SessionRanking {
  SessionRankRequest request;
  std::optional<Ranking> ranking;
  std::string error;  // why there is no ranking ("nothing to rank: ...")
};

// The session's (model, ref, candidate) cells with their intervals, as `ipd rank` reads them from `ipd table`.
CrossTable session_rank_table(const Session& session, const std::string& model, const std::string& ref,
                              const BootstrapOptions& bootstrap);
SessionRanking compute_session_ranking(const Session& session, const SessionRankRequest& request);

}  // namespace ipd
