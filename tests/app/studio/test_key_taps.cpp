#include "app/studio/key_taps.h"

#include <gtest/gtest.h>

namespace ipd::studio {
namespace {

constexpr int kEsc = 256;

// The events ImGui's own callback leaves: a key's state as it was last reported.
struct Keys {
  bool down[512] = {};
};

// Esc pressed and released between two frames: down for the next frame only, as a press ImGui can see.
TEST(KeyTaps, ATapBetweenFramesIsDownForOneFrame) {
  KeyTaps taps;
  Keys k;
  taps.pressed(kEsc);
  taps.released(kEsc);  // ImGui's callback: up again before the frame reads it
  taps.apply(k.down, 512);
  EXPECT_TRUE(k.down[kEsc]);
  taps.apply(k.down, 512);  // the next frame, no events
  EXPECT_FALSE(k.down[kEsc]);
}

// A key held across frames is ImGui's: no frame of it is changed, and its release is not delayed.
TEST(KeyTaps, AHeldKeyIsLeftAsReported) {
  KeyTaps taps;
  Keys k;
  taps.pressed('A');
  k.down['A'] = true;
  taps.apply(k.down, 512);
  EXPECT_TRUE(k.down['A']);
  taps.released('A');
  k.down['A'] = false;
  taps.apply(k.down, 512);
  EXPECT_FALSE(k.down['A']);
}

// Held down for a tap, then pressed and held before the next frame: it stays down (not let go under the user).
TEST(KeyTaps, ATappedKeyPressedAgainStaysDown) {
  KeyTaps taps;
  Keys k;
  taps.pressed('Z');
  taps.released('Z');
  taps.apply(k.down, 512);
  taps.pressed('Z');
  k.down['Z'] = true;
  taps.apply(k.down, 512);
  EXPECT_TRUE(k.down['Z']);
  // Keys outside the table (GLFW_KEY_UNKNOWN is -1) are ignored.
  taps.pressed(-1);
  taps.released(-1);
  taps.pressed(100000);
  taps.apply(k.down, 512);
}

}  // namespace
}  // namespace ipd::studio
