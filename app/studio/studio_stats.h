// ipd-studio's statistics job: SessionStatistics (intervals, histogram, size breakdown, comparison) of the
// latest snapshot's session, computed off the UI thread (session_job.h).
#pragma once

#include "app/studio/session_job.h"
#include "core/session/session_statistics.h"

namespace ipd::studio {

class StatsJob : public SessionJob<SessionStatisticsRequest, SessionStatistics> {
 public:
  StatsJob() : SessionJob(compute_session_statistics) {}
};

}  // namespace ipd::studio
