// ipd-studio's Rank job: the ranking of the study's renderer settings against the left domain for the current
// model (core/session/session_ranking.h), computed with std::async on the immutable session of the latest
// snapshot, as the statistics job does, never on the UI thread. Only while the Rank window is open; a newer
// session or request while one runs is computed right after it (latest wins).
#pragma once

#include <future>
#include <memory>
#include <vector>

#include "app/studio/studio_worker.h"
#include "core/session/session_ranking.h"

namespace ipd::studio {

class RankJob {
 public:
  ~RankJob();
  // Call once per frame while the ranking is shown: collects a finished result, starts the next one when needed.
  void update(const std::shared_ptr<const Snapshot>& snap, const SessionRankRequest& request);
  const SessionRanking* result() const { return result_.get(); }
  bool computing() const { return running_.valid(); }
  // The result is of this session and request (not an earlier one shown meanwhile).
  bool current(const std::shared_ptr<const Snapshot>& snap, const SessionRankRequest& request) const;

 private:
  std::future<std::shared_ptr<const SessionRanking>> running_;
  std::shared_ptr<const SessionRanking> result_;
  std::shared_ptr<const Session> running_session_, done_session_;  // kept alive: identity, never ABA
  SessionRankRequest running_request_, done_request_;
  std::vector<std::shared_ptr<const void>> to_release_;  // freed by the next job, off the UI thread
};

}  // namespace ipd::studio
