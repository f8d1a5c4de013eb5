// What the views forget on a scene change (ui/gui/scene_change.h).
#include <gtest/gtest.h>

#include "ui/gui/scene_change.h"

#include "tests/support/test_support.h"

namespace ipd::ui {
namespace {

UiState zoomed_in_scene_3() {
  UiState ui;
  ui.scene = 3;
  ui.left_view = {4.0f, {0.25f, -0.125f}};
  ui.right_view = {4.0f, {0.3f, -0.1f}};
  ui.selected_left = 7;
  ui.replay.position = 12;
  ui.rerun_discarded = true;
  ui.status = "suspect pair 8 in scene_00003";
  return ui;
}

TEST(SceneChange, FitsBothPicturesAndClearsTheStatusLine) {
  UiState ui = zoomed_in_scene_3();
  enter_scene(ui, 5);
  EXPECT_EQ(ui.scene, 5);
  EXPECT_FLOAT_EQ(ui.left_view.zoom, 1.0f);
  EXPECT_FLOAT_EQ(ui.left_view.pan.x, 0.0f);
  EXPECT_FLOAT_EQ(ui.right_view.zoom, 1.0f);
  EXPECT_FLOAT_EQ(ui.right_view.pan.y, 0.0f);
  EXPECT_EQ(ui.selected_left, -1);
  EXPECT_FLOAT_EQ(ui.replay.position, 0.0f);
  EXPECT_FALSE(ui.rerun_discarded);
  EXPECT_EQ(ui.status, "");
}

TEST(SceneChange, KeepsTheZoomWhenAsked) {
  UiState ui = zoomed_in_scene_3();
  ui.keep_zoom_across_scenes = true;
  enter_scene(ui, 5);
  EXPECT_FLOAT_EQ(ui.left_view.zoom, 4.0f);
  EXPECT_FLOAT_EQ(ui.left_view.pan.x, 0.25f);
  EXPECT_FLOAT_EQ(ui.right_view.pan.x, 0.3f);
  EXPECT_EQ(ui.status, "");
}

// Undo or redo on the scene in view (a review mark taken back, say) keeps what the user was looking at; on
// another scene it is a scene change.
TEST(SceneChange, AnEditOfTheSceneInViewKeepsSelectionZoomAndReplay) {
  UiState ui = zoomed_in_scene_3();
  show_scene_of_edit(ui, 3);
  EXPECT_EQ(ui.selected_left, 7);
  EXPECT_FLOAT_EQ(ui.left_view.zoom, 4.0f);
  EXPECT_FLOAT_EQ(ui.replay.position, 12.0f);
  EXPECT_TRUE(ui.rerun_discarded);
  EXPECT_EQ(ui.status, "");  // it was about the action undone
  show_scene_of_edit(ui, 5);
  EXPECT_EQ(ui.scene, 5);
  EXPECT_EQ(ui.selected_left, -1);
  EXPECT_FLOAT_EQ(ui.left_view.zoom, 1.0f);
}

// The status line speaks of the edit just sent (a refusal of an earlier one no longer applies), rocks
// numbered from 1 and named by their domain as the pictures show them; the swapped view names its own left.
TEST(SceneChange, TheStatusLineSaysWhichEditWasSent) {
  test::TempDir d;
  test::write_two_rock_study(d);
  Session s = Session::open(d.path());
  EXPECT_EQ(edit_status(s, 0, Edit::pair(0, 1)), "paired real rock 1 with synth rock 2 in s1");
  EXPECT_EQ(edit_status(s, 0, Edit::unpair(Side::kB, 0)), "unpaired synth rock 1 in s1");
  EXPECT_EQ(edit_status(s, 0, Edit::toggle_exclude(Side::kA, 1)), "real rock 2 excluded from the IPD in s1");
  s.apply(0, Edit::toggle_exclude(Side::kA, 1));
  EXPECT_EQ(edit_status(s, 0, Edit::toggle_exclude(Side::kA, 1)), "real rock 2 counted again in s1");
  EXPECT_EQ(edit_status(s, 0, Edit::reset()), "s1 reset to the automatic pairs");
  EXPECT_EQ(edit_status(s, 0, Edit::replace({{0, 1}})), "s1 paired as the re-run registration pairs it");
  EXPECT_EQ(edit_status(s, 1, Edit::reset()), "");  // no such scene
  ASSERT_TRUE(s.select_domains("synth", "real"));
  EXPECT_EQ(edit_status(s, 0, Edit::unpair(Side::kA, 0)), "unpaired synth rock 1 in s1");
}

}  // namespace
}  // namespace ipd::ui
