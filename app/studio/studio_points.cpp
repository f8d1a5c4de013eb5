#include "app/studio/studio_points.h"

#include <chrono>

namespace ipd::studio {

RockPointsJob::~RockPointsJob() {
  if (running_.valid()) running_.wait();
}

bool RockPointsJob::current(const std::shared_ptr<const Snapshot>& snap, const std::vector<int>& scenes) const {
  return result_ && snap && done_session_ == snap->session && result_->scenes == scenes;
}

void RockPointsJob::update(const std::shared_ptr<const Snapshot>& snap, const std::vector<int>& scenes) {
  if (running_.valid() && running_.wait_for(std::chrono::seconds(0)) == std::future_status::ready) {
    to_release_.push_back(std::move(result_));
    result_ = running_.get();
    to_release_.push_back(std::move(done_session_));
    done_session_ = running_session_;
  }
  if (running_.valid() || !snap || !snap->session || current(snap, scenes)) return;
  to_release_.push_back(std::move(running_session_));
  running_session_ = snap->session;
  running_scenes_ = scenes;
  running_ = std::async(std::launch::async,
                        [session = snap->session, scenes, garbage = std::exchange(to_release_, {})]() mutable {
                          yield_to_the_view();
                          garbage.clear();  // here, not on the UI thread
                          auto out = std::make_shared<RockPointSet>();
                          out->scenes = scenes;
                          if (!scenes.empty())
                            out->points = rock_pair_points(*session, scenes);  // (empty asks for all)
                          out->pair = session->pair_index();
                          out->swapped = session->swapped();
                          out->model = session->model();
                          return std::shared_ptr<const RockPointSet>(std::move(out));
                        });
}

}  // namespace ipd::studio
