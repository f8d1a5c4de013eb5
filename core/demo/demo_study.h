// The built-in demo study: a small generated study (three domains, six scenes each) with pictures, GT
// labels and predictions of a classical detector tuned on each domain. Deterministic for a seed.
#pragma once

#include <cstdint>
#include <string>

namespace ipd {

struct DemoStudyOptions {
  int scenes = 6;
  int min_rocks = 9, max_rocks = 18;  // per scene
  int width = 960, height = 600;
  std::uint64_t seed = 7;
  // No pictures: GT boxes from the scene geometry and synthetic predictions (GT jittered, some missed,
  // a few false alarms), fast enough for 10,000-scene benchmark studies.
  bool labels_only = false;
  // task: segment: every rock also has its outline (the drawn ellipse's, GT) and the detector's predictions are
  // its contours, so the IPD is about masks. Needs the pictures (not with labels_only).
  bool segment = false;

  // Empty when usable; otherwise the field that is wrong and the accepted range, in one sentence.
  std::string validate() const;
  // Throws std::invalid_argument("demo study options: " + validate()) when not usable.
  void check() const;
};

// Writes the study into `dir`, a new or empty folder (demo_files.h: its files are new; study.yaml comes last). Throws
// IoError on failure, naming a file that is already there.
void write_demo_study(const std::string& dir, const DemoStudyOptions& options = {});

}  // namespace ipd
