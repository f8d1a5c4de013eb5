// ipd-studio's Rock pairs job: gathers the counted pairs of a scene list (rock_pair_points) with std::async on
// the immutable session of the latest snapshot, never on the UI thread (300,000 pairs of a 10,000-scene study
// take longer than a frame to gather). The result is swapped in whole; a newer session or scene list while
// one runs is gathered right after it (latest wins), as StatsJob does for the statistics.
#pragma once

#include <future>
#include <memory>
#include <vector>

#include "app/studio/studio_worker.h"
#include "core/session/rock_pair_points.h"

namespace ipd::studio {

class RockPointsJob {
 public:
  ~RockPointsJob();
  // Call once per frame while the Rock pairs window is open: collects a finished result, starts the next
  // gathering when the snapshot's session or `scenes` (sorted scene indices) differ from the last one's.
  void update(const std::shared_ptr<const Snapshot>& snap, const std::vector<int>& scenes);
  // The latest gathered points (null before the first); they may be of an older session or list while
  // computing().
  const std::shared_ptr<const RockPointSet>& result() const { return result_; }
  bool computing() const { return running_.valid(); }
  // The result is of exactly this session and list.
  bool current(const std::shared_ptr<const Snapshot>& snap, const std::vector<int>& scenes) const;

 private:
  std::future<std::shared_ptr<const RockPointSet>> running_;
  std::shared_ptr<const RockPointSet> result_;
  std::shared_ptr<const Session> running_session_, done_session_;  // kept alive: identity, never ABA
  std::vector<int> running_scenes_;
  std::vector<std::shared_ptr<const void>> to_release_;  // freed by the next job, off the UI thread
};

}  // namespace ipd::studio
