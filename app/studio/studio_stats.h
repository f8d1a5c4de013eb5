// ipd-studio's statistics job: computes SessionStatistics (intervals, histogram, size breakdown, comparison)
// with std::async on the immutable session of the latest snapshot, never on the UI thread; the result is
// swapped in whole. A newer session or request while one runs is computed right after it (latest wins).
#pragma once

#include <future>
#include <memory>
#include <vector>

#include "app/studio/studio_worker.h"
#include "core/session/session_statistics.h"

namespace ipd::studio {

class StatsJob {
 public:
  ~StatsJob();
  // Call once per frame: collects a finished result, starts the next computation when needed.
  void update(const std::shared_ptr<const Snapshot>& snap, const SessionStatisticsRequest& request);
  const SessionStatistics* result() const { return result_.get(); }
  bool computing() const { return running_.valid(); }

 private:
  std::future<std::shared_ptr<const SessionStatistics>> running_;
  std::shared_ptr<const SessionStatistics> result_;
  std::shared_ptr<const Session> running_session_, done_session_;  // kept alive: identity, never ABA
  SessionStatisticsRequest running_request_, done_request_;
  // Sessions and results let go of: freed by the next job, off the UI thread (freeing a 10,000-scene session
  // took a 690 ms frame).
  std::vector<std::shared_ptr<const void>> to_release_;
};

}  // namespace ipd::studio
