// What `ipd-studio --frame-stats` measures and prints: time to the first content and to the whole study,
// frame times, scene changes (request to both full pictures drawn), the worker's time per edit and frames while
// a figure exports.
#pragma once

#include <chrono>
#include <string>
#include <vector>

namespace ipd::studio {

class FrameStats {
 public:
  // A frame's wall-clock time, and the UI thread's own CPU time in it (what the program costs, apart from
  // the rasteriser and from other programs on the machine).
  void add_frame(double ms, double ui_cpu_ms) {
    frame_ms_.push_back(ms);
    frame_cpu_ms_.push_back(ui_cpu_ms);
  }
  void add_scene_change(double ms) { scene_ms_.push_back(ms); }
  // An edit, undo or redo: the worker's time from taking it to publishing the snapshot that shows it, and the
  // worker thread's own CPU time in it.
  void add_edit(double ms, double cpu_ms) {
    edit_ms_.push_back(ms);
    edit_cpu_ms_.push_back(cpu_ms);
  }
  void add_export_frame(double ms, double ui_cpu_ms) {
    export_frame_ms_.push_back(ms);
    export_ui_cpu_ms_.push_back(ui_cpu_ms);
  }
  // A frame drawn in the blink view (also counted in frame_ms), and what the last one drew.
  void add_blink_frame(double ms) { blink_frame_ms_.push_back(ms); }
  void set_blink_line(std::string line) { blink_line_ = std::move(line); }
  // The first call of each records the time since the program started.
  void content_shown() { mark(&content_ms_); }
  void study_loaded() { mark(&loaded_ms_); }
  // The last frame's pictures on screen (left, right: width and height in pixels) and the window's size.
  void set_picture_px(float left_w, float left_h, float right_w, float right_h, float window_w, float window_h) {
    picture_px_ = {left_w, left_h, right_w, right_h, window_w, window_h};
  }
  // `picture_px left=WxH right=WxH window=WxH share=S` (S: the two pictures' part of the window's area).
  std::string picture_line() const;

  // `NAME median=X p95=Y max=Z n=N over_50ms=K` (empty without values).
  static std::string summary(const char* name, std::vector<double> values);
  // open_ms/loaded_ms (with `open_note` after them), then frame_ms, ui_cpu_ms and the export lines when
  // `frames` (blink_frame_ms and the blink line when the blink view was drawn);
  // scene_ms whenever scenes were changed, edit_ms whenever edits were made.
  void print(bool frames, const std::string& open_note) const;

 private:
  void mark(double* slot);
  std::chrono::steady_clock::time_point started_ = std::chrono::steady_clock::now();
  std::vector<double> frame_ms_, frame_cpu_ms_, blink_frame_ms_, scene_ms_, edit_ms_, edit_cpu_ms_, export_frame_ms_,
      export_ui_cpu_ms_;
  double content_ms_ = -1;  // start to the first frame showing the study (a first look at big studies)
  double loaded_ms_ = -1;   // start to the first frame with the whole study in
  std::vector<float> picture_px_;
  std::string blink_line_;  // `blink pane=WxH pane_share=S ...` of the last blink frame
};

}  // namespace ipd::studio
