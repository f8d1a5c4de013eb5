#include "app/studio/studio_rank.h"

#include <chrono>

namespace ipd::studio {

RankJob::~RankJob() {
  if (running_.valid()) running_.wait();
}

bool RankJob::current(const std::shared_ptr<const Snapshot>& snap, const SessionRankRequest& request) const {
  return result_ && snap && done_session_ == snap->session && done_request_ == request;
}

void RankJob::update(const std::shared_ptr<const Snapshot>& snap, const SessionRankRequest& request) {
  if (running_.valid() && running_.wait_for(std::chrono::seconds(0)) == std::future_status::ready) {
    to_release_.push_back(std::move(result_));
    result_ = running_.get();  // compute_session_ranking says its errors in the result
    to_release_.push_back(std::move(done_session_));
    done_session_ = running_session_;
    done_request_ = running_request_;
  }
  if (running_.valid() || !snap || !snap->session) return;
  if (done_session_ == snap->session && done_request_ == request) return;
  to_release_.push_back(std::move(running_session_));
  running_session_ = snap->session;
  running_request_ = request;
  running_ = std::async(std::launch::async,
                        [session = snap->session, request, garbage = std::exchange(to_release_, {})]() mutable {
                          yield_to_the_view();
                          garbage.clear();
                          return std::make_shared<const SessionRanking>(compute_session_ranking(*session, request));
                        });
}

}  // namespace ipd::studio
