#include "app/studio/studio_stats.h"

#include "app/studio/studio_worker.h"

#include <chrono>

namespace ipd::studio {

StatsJob::~StatsJob() {
  if (running_.valid()) running_.wait();
}

void StatsJob::update(const std::shared_ptr<const Snapshot>& snap, const SessionStatisticsRequest& request) {
  if (running_.valid() && running_.wait_for(std::chrono::seconds(0)) == std::future_status::ready) {
    try {
      to_release_.push_back(std::move(result_));
      result_ = running_.get();
    } catch (const std::exception&) {
      result_.reset();  // e.g. bad options: the panels show "computing" rather than stale numbers
    }
    to_release_.push_back(std::move(done_session_));
    done_session_ = running_session_;
    done_request_ = running_request_;
  }
  if (running_.valid() || !snap || !snap->session) return;
  if (done_session_ == snap->session && done_request_ == request) return;
  to_release_.push_back(std::move(running_session_));
  running_session_ = snap->session;
  running_request_ = request;
  running_ = std::async(
      std::launch::async, [session = snap->session, request, garbage = std::exchange(to_release_, {})]() mutable {
        yield_to_the_view();
        garbage.clear();  // here, not on the UI thread
        return std::make_shared<const SessionStatistics>(compute_session_statistics(*session, request));
      });
}

}  // namespace ipd::studio
