// Key taps that begin and end between two frames. ImGui 1.86 reads the keys' state once per frame, so a key
// pressed and released within one round of events (a quick tap, or any tap while llvmpipe draws a slow frame)
// was never seen down: Esc on the Shortcuts window, say, did nothing. Such a tap is held down for one frame.
// GL-free, so the tests drive it with hand-made events.
#pragma once

#include <vector>

namespace ipd::studio {

class KeyTaps {
 public:
  // From the window's key callback, before ImGui's own (which sets the key's state as it is).
  void pressed(int key);
  void released(int key);
  // After a frame's events, before its ImGui frame: each key tapped during them is down for this frame, and
  // one held down for a tap in the previous frame is let go (unless it is down again).
  void apply(bool* keys_down, int key_count);

 private:
  bool in_range(int key) const { return key >= 0 && key < static_cast<int>(physically_down_.size()); }
  std::vector<char> physically_down_ = std::vector<char>(512, 0), pressed_since_frame_ = std::vector<char>(512, 0);
  std::vector<int> tapped_, holding_;
};

}  // namespace ipd::studio
