// ipd-studio's background jobs: a computation on the immutable session of the latest snapshot, run with
// std::async and never on the UI thread. The result is swapped in whole; a newer session or request while one
// runs is computed right after it (latest wins). The statistics panels, the Rock pairs window and the Rank window
// each own one, with their own request and result types.
#pragma once

#include <chrono>
#include <functional>
#include <future>
#include <memory>
#include <utility>
#include <vector>

#include "app/studio/studio_worker.h"

namespace ipd::studio {

template <class Request, class Result>
class SessionJob {
 public:
  using Compute = std::function<Result(const Session&, const Request&)>;

  explicit SessionJob(Compute compute) : compute_(std::move(compute)) {}
  SessionJob(const SessionJob&) = delete;
  SessionJob& operator=(const SessionJob&) = delete;
  ~SessionJob() {
    if (running_.valid()) running_.wait();
  }

  // Call once per frame while the result is shown: collects a finished result, starts the next computation
  // when the snapshot's session or the request differ from the last computed ones.
  void update(const std::shared_ptr<const Snapshot>& snap, const Request& request) {
    if (running_.valid() && running_.wait_for(std::chrono::seconds(0)) == std::future_status::ready) collect();
    if (running_.valid() || !snap || !snap->session) return;
    // A computation that threw is not retried every frame: only a new session or request starts another.
    if (done_session_ == snap->session && done_request_ == request) return;
    to_release_.push_back(std::move(running_session_));
    running_session_ = snap->session;
    running_request_ = request;
    running_ = std::async(std::launch::async, [session = snap->session, request, compute = compute_,
                                               garbage = std::exchange(to_release_, {})]() mutable {
      yield_to_the_view();
      garbage.clear();  // here, not on the UI thread
      return std::make_shared<const Result>(compute(*session, request));
    });
  }

  // The latest result (null before the first, or when the last computation threw); it may be of an older
  // session or request while computing().
  const std::shared_ptr<const Result>& result() const { return result_; }
  bool computing() const { return running_.valid(); }
  // The result is of exactly this session and request (not an earlier one shown meanwhile).
  bool current(const std::shared_ptr<const Snapshot>& snap, const Request& request) const {
    return result_ && snap && done_session_ == snap->session && done_request_ == request;
  }

 private:
  void collect() {
    to_release_.push_back(std::move(result_));
    try {
      result_ = running_.get();
    } catch (const std::exception&) {
      result_.reset();  // e.g. bad options: the view shows "computing" rather than stale numbers
    }
    to_release_.push_back(std::move(done_session_));
    done_session_ = running_session_;
    done_request_ = running_request_;
  }

  Compute compute_;
  std::future<std::shared_ptr<const Result>> running_;
  std::shared_ptr<const Result> result_;
  std::shared_ptr<const Session> running_session_, done_session_;  // kept alive: identity, never ABA
  Request running_request_{}, done_request_{};
  // Sessions and results let go of: freed by the next job, off the UI thread (freeing a 10,000-scene session
  // took a 690 ms frame).
  std::vector<std::shared_ptr<const void>> to_release_;
};

}  // namespace ipd::studio
