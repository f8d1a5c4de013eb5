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

// The status line speaks of the edit just sent (a refusal of an earlier one no longer applies), in the
// pictures' terms: rocks numbered from 1 and named by their domain, a pair by its left rock's number (the number
// both pictures show on it), and the partners an edit leaves unpaired. The swapped view names its own left.
TEST(SceneChange, TheStatusLineSaysWhichEditWasSent) {
  test::TempDir d;
  test::write_two_rock_study(d);  // real 1 | synth 2 is pair 1, real 2 | synth 1 is pair 2
  Session s = Session::open(d.path());
  EXPECT_EQ(edit_status(s, 0, Edit::pair(0, 1)), "pair 1 is now real rock 1 | synth rock 2 in s1");
  EXPECT_EQ(edit_status(s, 0, Edit::pair(0, 0)),
            "pair 1 is now real rock 1 | synth rock 1 in s1; synth rock 2 and real rock 2 unpaired");
  EXPECT_EQ(edit_status(s, 0, Edit::unpair(Side::kB, 0)), "pair 2 unpaired in s1 (real rock 2 | synth rock 1)");
  EXPECT_EQ(edit_status(s, 0, Edit::toggle_exclude(Side::kA, 1)), "real rock 2 excluded from the IPD in s1");
  EXPECT_EQ(edit_status(s, 0, Edit::toggle_exclude(Side::kB, 0)), "synth rock 1 (pair 2) excluded from the IPD in s1");
  s.apply(0, Edit::toggle_exclude(Side::kA, 1));
  EXPECT_EQ(edit_status(s, 0, Edit::toggle_exclude(Side::kA, 1)), "real rock 2 counted again in s1");
  EXPECT_EQ(edit_status(s, 0, Edit::reset()), "s1 reset to the automatic pairs");
  EXPECT_EQ(edit_status(s, 0, Edit::replace({{0, 1}})), "s1 paired as the re-run registration pairs it");
  EXPECT_EQ(edit_status(s, 1, Edit::reset()), "");  // no such scene
  ASSERT_TRUE(s.select_domains("synth", "real"));
  EXPECT_EQ(edit_status(s, 0, Edit::unpair(Side::kA, 0)), "pair 1 unpaired in s1 (synth rock 1 | real rock 2)");
  s.apply(0, Edit::unpair(Side::kA, 0));
  EXPECT_EQ(edit_status(s, 0, Edit::unpair(Side::kA, 0)), "synth rock 1 is in no pair in s1");
  EXPECT_EQ(unchanged_by_edit(s, 0, Edit::unpair(Side::kA, 0)), "synth rock 1 is in no pair in s1: nothing changed");
  EXPECT_EQ(unchanged_by_edit(s, 0, Edit::unpair(Side::kB, 0)), "");
}

// An edit that changes nothing is not sent: pairing two partners again, or resetting a scene that has the
// automatic pairs, would write a pairs file and make the scene count as edited by hand.
TEST(SceneChange, AnEditThatChangesNothingIsSaidAndNotSent) {
  test::TempDir d;
  test::write_two_rock_study(d);  // automatic pairs (0, 1), (1, 0)
  Session s = Session::open(d.path());
  EXPECT_EQ(unchanged_by_edit(s, 0, Edit::pair(0, 1)),
            "real rock 1 and synth rock 2 are a pair already in s1: nothing changed");
  EXPECT_EQ(unchanged_by_edit(s, 0, Edit::pair(0, 0)), "");
  EXPECT_EQ(unchanged_by_edit(s, 0, Edit::reset()), "s1 has the automatic pairs already: nothing changed");
  EXPECT_EQ(unchanged_by_edit(s, 0, Edit::unpair(Side::kA, 0)), "");
  s.apply(0, Edit::toggle_exclude(Side::kA, 0));  // an excluded rock paired again is counted again: a change
  EXPECT_EQ(unchanged_by_edit(s, 0, Edit::pair(0, 1)), "");
  EXPECT_EQ(unchanged_by_edit(s, 0, Edit::reset()), "");  // the scene is edited now
  // The view's own orientation: synth 1 | real 2 is the pair real 2 | synth 1; real rock 1 is the excluded one.
  ASSERT_TRUE(s.select_domains("synth", "real"));
  EXPECT_EQ(unchanged_by_edit(s, 0, Edit::pair(0, 1)),
            "synth rock 1 and real rock 2 are a pair already in s1: nothing changed");
  EXPECT_EQ(unchanged_by_edit(s, 0, Edit::pair(1, 0)), "");
  // A stale pairs file (its stored synth rock left the label file) shows registration's pairs, unedited:
  // reset still goes through, as it discards the file.
  test::write_text(
      d / "pairs/real__synth/s1.json",
      R"({"pairs": [[0, 1]], "rocks_a": [[0, 0.2, 0.2, 0.1, 0.1]], "rocks_b": [[1, 0.3, 0.3, 0.1, 0.1]]})");
  const Session stale = Session::open(d.path());
  ASSERT_TRUE(stale.scenes()[0].pairs_unusable);
  EXPECT_EQ(unchanged_by_edit(stale, 0, Edit::reset()), "");
}

}  // namespace
}  // namespace ipd::ui
