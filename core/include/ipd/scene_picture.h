// A picture of one image pair for people: both pictures side by side, GT boxes pink with rock indices,
// predictions red with confidences, partners numbered alike. Drawn with OpenCV (no GL needed).
#pragma once

#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "ipd/geometry.h"
#include "ipd/registration.h"

namespace ipd {

struct ScenePictureSide {
  cv::Mat picture;             // BGR; empty draws a grey placeholder
  int width = 0, height = 0;   // placeholder size when there is no picture
  std::string caption;         // e.g. "real"
  std::vector<Box> gt, predictions;
};

// `pairs` are (index in left, index in right); partners get the same number (the pair's rank).
cv::Mat draw_scene_pair(const ScenePictureSide& left, const ScenePictureSide& right, const RockPairs& pairs,
                        const std::string& title, int out_width);

}  // namespace ipd
