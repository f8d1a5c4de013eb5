// Background work of ipd-studio, so the UI thread never waits on disk: decoding pictures (downscaled once
// for display) and writing edits.
#pragma once

#include <condition_variable>
#include <deque>
#include <map>
#include <mutex>
#include <opencv2/core.hpp>
#include <string>
#include <thread>
#include <vector>

#include "ipd/session.h"

namespace ipd::studio {

struct DecodedPicture {
  std::string key;
  cv::Mat rgba;            // empty when it could not be read
  int width = 0, height = 0;  // of the original file
  std::string error;
};

class PictureLoader {
 public:
  explicit PictureLoader(int max_width = 2048);
  ~PictureLoader();
  // Newest requests first (the current scene beats prefetching); a key already queued moves to the front.
  void request(const std::string& key, const std::string& path, bool urgent);
  std::vector<DecodedPicture> take_ready();
  bool idle();

 private:
  void run();
  int max_width_;
  std::mutex mu_;
  std::condition_variable cv_;
  std::deque<std::pair<std::string, std::string>> queue_;
  std::vector<DecodedPicture> ready_;
  bool stop_ = false, busy_ = false;
  std::thread thread_;
};

// Writes save jobs in order, the newest contents of a path winning; reports failures.
class Saver {
 public:
  Saver();
  ~Saver();  // finishes every queued job first: nothing is lost on a normal exit
  void submit(SaveJob job);
  std::vector<std::string> take_errors();
  int pending();

 private:
  void run();
  std::mutex mu_;
  std::condition_variable cv_;
  std::deque<SaveJob> queue_;
  std::vector<std::string> errors_;
  bool stop_ = false;
  int busy_ = 0;
  std::thread thread_;
};

}  // namespace ipd::studio
