// ipd-studio's Rank job: the ranking of the study's renderer settings against the left domain for the current
// model (core/session/session_ranking.h), computed off the UI thread (session_job.h) while the Rank window is
// open.
#pragma once

#include "app/studio/session_job.h"
#include "core/session/session_ranking.h"

namespace ipd::studio {

class RankJob : public SessionJob<SessionRankRequest, SessionRanking> {
 public:
  RankJob() : SessionJob(compute_session_ranking) {}
};

}  // namespace ipd::studio
