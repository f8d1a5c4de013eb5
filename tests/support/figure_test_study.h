// The small study the figure tests draw: two domains, one scene, pictures optional.
//   GT (both):        0 0.30 0.40 0.20 0.25      prediction real: 0 0.35 0.40 0.20 0.25 0.87
//   second rock real: 0 0.75 0.70 0.10 0.12      prediction synth: 0 0.32 0.40 0.20 0.25 0.93
#pragma once

#include <filesystem>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "core/demo/demo_study.h"
#include "tests/support/test_support.h"

namespace ipd::test {

inline void write_figure_study(const TempDir& d, bool pictures) {
  write_text(d / "study.yaml", "domains: [real, synth]\nimage_size: [640, 400]\nmodels: {det: {trained_on: real}}\n");
  write_text(d / "real/labels/s1.txt", "0 0.30 0.40 0.20 0.25\n0 0.75 0.70 0.10 0.12\n");
  write_text(d / "synth/labels/s1.txt", "0 0.30 0.40 0.20 0.25\n");
  write_text(d / "real/predictions/det/s1.txt", "0 0.35 0.40 0.20 0.25 0.87\n");
  write_text(d / "synth/predictions/det/s1.txt", "0 0.32 0.40 0.20 0.25 0.93\n");
  if (!pictures) return;
  for (const std::string dom : {"real", "synth"}) {
    cv::Mat img(400, 640, CV_8UC3, cv::Scalar(90, 95, 100));
    cv::circle(img, {192, 160}, 50, cv::Scalar(170, 175, 180), cv::FILLED, cv::LINE_AA);
    std::filesystem::create_directories(d / (dom + "/images"));
    cv::imwrite(d / (dom + "/images/s1.png"), img);
  }
}

// The demo study's first `scenes` scenes, labels only (no pictures): Table I and the statistics figures of
// the demo, quick to write (one scene: no interval, no test).
inline void write_small_demo_study(const TempDir& d, int scenes = 3) {
  DemoStudyOptions demo;
  demo.scenes = scenes;
  demo.labels_only = true;
  write_demo_study(d.path(), demo);
}

}  // namespace ipd::test
