#include "app/studio/frame_stats.h"

#include <fmt/format.h>

#include <algorithm>

namespace ipd::studio {

void FrameStats::mark(double* slot) {
  if (*slot < 0) *slot = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - started_).count();
}

std::string FrameStats::summary(const char* name, std::vector<double> v) {
  if (v.empty()) return {};
  std::sort(v.begin(), v.end());
  const long over = std::count_if(v.begin(), v.end(), [](double ms) { return ms > 50; });
  return fmt::format("{} median={:.2f} p95={:.2f} max={:.2f} n={} over_50ms={}", name, v[v.size() / 2],
                     v[std::min(v.size() - 1, v.size() * 95 / 100)], v.back(), v.size(), over);
}

std::string FrameStats::picture_line() const {
  if (picture_px_.size() != 6) return {};
  const auto& p = picture_px_;
  const double window = double(p[4]) * p[5];
  const double share = window > 0 ? (double(p[0]) * p[1] + double(p[2]) * p[3]) / window : 0;
  return fmt::format("picture_px left={:.0f}x{:.0f} right={:.0f}x{:.0f} window={:.0f}x{:.0f} share={:.3f}", p[0], p[1],
                     p[2], p[3], p[4], p[5], share);
}

void FrameStats::print(bool frames, const std::string& open_note) const {
  auto line = [](const std::string& s) {
    if (!s.empty()) fmt::print("{}\n", s);
  };
  if (frames && content_ms_ >= 0)
    fmt::print("open_ms={:.0f} (first content on screen) loaded_ms={:.0f} (whole study; {})\n", content_ms_, loaded_ms_,
               open_note);
  if (frames) line(summary("frame_ms", frame_ms_)), line(summary("ui_cpu_ms", frame_cpu_ms_));
  if (frames) line(picture_line());
  if (frames) line(summary("blink_frame_ms", blink_frame_ms_)), line(blink_line_);
  line(summary("scene_ms", scene_ms_));
  // Measurements, as frame_ms: only when asked for.
  if (frames) line(summary("edit_ms", edit_ms_)), line(summary("edit_cpu_ms", edit_cpu_ms_));
  if (frames) line(summary("export_frame_ms", export_frame_ms_)), line(summary("export_ui_cpu_ms", export_ui_cpu_ms_));
}

}  // namespace ipd::studio
