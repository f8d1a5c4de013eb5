// What the views forget on a scene change (ui/gui/scene_change.h).
#include <gtest/gtest.h>

#include "ui/gui/scene_change.h"

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

}  // namespace
}  // namespace ipd::ui
