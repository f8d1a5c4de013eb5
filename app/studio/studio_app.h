// ipd-studio's application object: the worker (study data), the texture cache (pictures), the view state,
// and the one function that applies what the views asked for. main() only runs the window loop around it.
#pragma once

#include <atomic>
#include <chrono>
#include <future>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "app/studio/frame_stats.h"
#include "app/studio/studio_options.h"
#include "app/studio/studio_points.h"
#include "app/studio/studio_rank.h"
#include "app/studio/studio_replay.h"
#include "app/studio/studio_stats.h"
#include "app/studio/studio_textures.h"
#include "app/studio/studio_worker.h"
#include "ui/gui/export_dialog.h"
#include "ui/gui/rank_view.h"
#include "ui/gui/rock_view.h"
#include "ui/gui/stats_panels.h"
#include "ui/gui/views.h"

namespace ipd::studio {

class StudioApp {
 public:
  explicit StudioApp(StudioOptions options);  // throws std::runtime_error for a bad replay file
  // Builds this frame's windows (between ImGui::NewFrame and ImGui::Render).
  void frame();
  // After the frame was rendered and finished: timing (wall clock, and the UI thread's own CPU time),
  // replay progress; returns the screenshot path to save now (empty: none).
  std::string after_render(double frame_ms, double ui_cpu_ms);
  bool done() const { return done_; }
  bool loading() const;  // the worker is opening a study
  void request_quit() { ui_.show_quit = true; }
  // The window backend's key index of F1, which opens the shortcuts (StudioWindow::help_key).
  void set_help_key(int key) { ui_.help_key = key; }
  int print_stats() const;  // prints frame_ms / scene_ms; returns the exit code

 private:
  void apply(const ui::UiCommands& cmd);  // the one place commands take effect
  void submit_edits(const ui::UiCommands& cmd);
  void adopt_snapshot();
  // The frame's parts (studio_app_frame.cpp).
  ui::StudyView study_view();
  void draw_open_error(const std::string& error, float h);
  void draw_opening(const OpenProgress& p, float h);
  void draw_study(ui::StudyView& v, float h, ui::UiCommands& cmd);
  void scene_pictures(const Session& s, ui::Picture* left, ui::Picture* right);  // and the neighbours' prefetch
  void next_suspect();
  void goto_scene(int scene);
  bool replay_step();  // one action of --replay; false while waiting
  ui::Picture picture(const std::string& domain, const std::string& stem, bool urgent, bool* full);
  void list_browse_dir();
  void export_figure(const ui::ExportRequest& request);
  // The view's export context, its gallery in the order the Rock pairs gallery shows.
  ui::ExportViewContext export_context() const;  // on the worker, from the current snapshot
  // What a finished replay left undone (failed or unsaved edits, failed or unfinished exports), one line each.
  std::vector<std::string> replay_problems() const;
  void note_picture_problem(const DecodedPicture& d);
  void goto_problem(const Problem& p);
  void goto_pair(int scene, int left, int right);
  // Sync zoom: when the selected left rock or its partner changed (a click, N, a re-pairing), the right picture
  // shows the partner where the left one shows the rock (through the affine when it has none).
  void follow_selected_partner();
  // The blink view and the Rank window as a script drives them (studio_app_replay.cpp), and the state dump.
  bool replay_blink(const ReplayAction& a);
  bool replay_rank(const ReplayAction& a, ui::UiCommands* cmd);
  std::string write_state(const std::string& file) const;
  // Replay verbs of the rock view (studio_replay.h): its axes, a drag box, the scene list written out.
  void replay_rock_axes(const std::string& x, const std::string& y);
  void replay_select(double x0, double y0, double x1, double y1);
  void replay_gallery(const std::vector<std::string>& args);
  std::string write_scene_list(const std::string& file) const;  // the rock view's click: the pair selected, in view
  // One replay action of a verb group (studio_app_replay.cpp); each returns false when the verb is not of its
  // group. View: what is shown and how it is computed; edits: pairs, undo and the review marks; outputs: the
  // rock view, the scene list, figures and screenshots.
  bool replay_view_action(const ReplayAction& a, ui::UiCommands* cmd);
  bool replay_edit_action(const ReplayAction& a, ui::UiCommands* cmd);
  bool replay_output_action(const ReplayAction& a);
  void replay_fail(const ReplayAction& a, const std::string& why);  // reports it and ends the replay, failed
  int replay_rock(const ReplayAction& a, const std::string& number, Side side);  // 0-based; -1: none (failed)
  bool replay_input_action(const ReplayAction& a, ui::UiCommands* cmd);          // click, dialog, type, key
  // `type` and `key`: a key pressed on one frame, its character and its release on the next.
  bool release_typed_key();  // true when a key was let go (the frame is taken)
  void press_next_typed_key();

  StudioOptions o_;
  StudyWorker worker_;
  PictureLoader loader_;
  TextureCache textures_;
  ui::UiState ui_;
  ui::ExportDialogState export_dialog_;
  ui::StatsPanelState stats_ui_;
  ui::RockViewState rock_view_;
  StatsJob stats_;             // intervals, histogram, breakdown, comparison: off the UI thread
  RockPointsJob rock_points_;  // the Rock pairs window's pairs: off the UI thread
  RankJob rank_;               // the Rank window's ranking: off the UI thread
  std::string followed_;       // the selection sync zoom last followed: "pair/swapped/scene/left/partner"
  std::shared_ptr<const Snapshot> snap_;
  // The session's problems and then the pictures that could not be read (found as they are shown).
  std::vector<Problem> problems_, picture_problems_;
  std::string pending_scene_;   // shown once the worker has switched: a problem's scene, or the one in view before a
                                // class switch
  std::string pending_status_;  // and the problem, on the status line then
  std::string history_verb_;    // "undid the last change", for the status line once the worker has undone it
  long order_version_ = -1;
  std::string order_filter_;
  int order_sort_ = -1;
  bool order_desc_ = true;
  long jump_serial_ = 0;
  std::string traced_;       // "pair/stem" whose search was asked to be recorded
  std::string registering_;  // "pair/stem" of the hand-paired scene the worker was asked to register
  // The discarded re-run whose place the study's own search was asked to take back (once per discard).
  const RegistrationReport* discarded_rerun_ = nullptr;
  std::string listed_dir_;
  bool done_ = false, open_failed_ = false, replay_failed_ = false;
  // Timing
  FrameStats stats_out_;
  // Exports running on the worker: frames drawn meanwhile are timed apart.
  std::shared_ptr<std::atomic<int>> exports_running_ = std::make_shared<std::atomic<int>>(0);
  struct ExportFailures {
    std::mutex mu;
    std::vector<std::string> messages;  // guarded by mu
  };
  std::shared_ptr<ExportFailures> export_failures_ = std::make_shared<ExportFailures>();
  int counted_ = 0, settle_ = 0, since_change_ = 0;
  bool changing_ = false, change_shown_ = false, pictures_full_ = false;
  std::chrono::steady_clock::time_point change_started_;
  // Replay
  std::vector<ReplayAction> replay_;
  size_t replay_next_ = 0;
  int replay_wait_ = 0;
  std::string typing_;       // characters still to type ('\n' Enter, '\x1b' Esc, '\t' Tab)
  int typed_key_ = -1;       // the key pressed last frame (an index of ImGuiIO::KeysDown)
  unsigned typed_char_ = 0;  // and the character it sends
  std::string screenshot_now_;
  std::future<void> recent_write_;  // the recent-studies list being written (waited for before the next)
};

}  // namespace ipd::studio
