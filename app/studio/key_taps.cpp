#include "app/studio/key_taps.h"

#include <algorithm>

namespace ipd::studio {

void KeyTaps::pressed(int key) {
  if (!in_range(key)) return;
  physically_down_[key] = 1;
  pressed_since_frame_[key] = 1;
}

void KeyTaps::released(int key) {
  if (!in_range(key)) return;
  physically_down_[key] = 0;
  if (pressed_since_frame_[key]) tapped_.push_back(key);
}

void KeyTaps::apply(bool* keys_down, int key_count) {
  for (int key : holding_)
    if (key < key_count && !physically_down_[key]) keys_down[key] = false;
  holding_.clear();
  for (int key : tapped_)
    if (key < key_count) {
      keys_down[key] = true;
      holding_.push_back(key);
    }
  tapped_.clear();
  std::fill(pressed_since_frame_.begin(), pressed_since_frame_.end(), 0);
}

}  // namespace ipd::studio
