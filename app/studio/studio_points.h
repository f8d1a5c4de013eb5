// ipd-studio's Rock pairs job: the counted pairs of a scene list (rock_pair_points), gathered off the UI thread
// (session_job.h) while the Rock pairs window is open: 300,000 pairs of a 10,000-scene study take longer than a
// frame to gather. The request is the sorted list of scene indices (empty asks for none).
#pragma once

#include <vector>

#include "app/studio/session_job.h"
#include "core/session/rock_pair_points.h"

namespace ipd::studio {

// The pairs of `scenes` with the session's pair, swap and model they were gathered under.
RockPointSet gather_rock_points(const Session& session, const std::vector<int>& scenes);

class RockPointsJob : public SessionJob<std::vector<int>, RockPointSet> {
 public:
  RockPointsJob() : SessionJob(gather_rock_points) {}
};

}  // namespace ipd::studio
