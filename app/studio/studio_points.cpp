#include "app/studio/studio_points.h"

namespace ipd::studio {

RockPointSet gather_rock_points(const Session& session, const std::vector<int>& scenes) {
  RockPointSet out;
  out.scenes = scenes;
  if (!scenes.empty()) out.points = rock_pair_points(session, scenes);  // (rock_pair_points takes empty as all)
  out.pair = session.pair_index();
  out.swapped = session.swapped();
  out.model = session.model();
  return out;
}

}  // namespace ipd::studio
