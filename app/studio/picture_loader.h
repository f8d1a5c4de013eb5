// Pictures for ipd-studio, decoded off the UI thread: a reduced version first, then the full one with its
// mipmap chain built on the decoder thread, so the UI thread only copies levels into textures. GL-free.
#pragma once

#include <condition_variable>
#include <deque>
#include <mutex>
#include <opencv2/core.hpp>
#include <string>
#include <thread>
#include <vector>

namespace ipd::studio {
struct DecodedPicture {
  std::string key;
  std::vector<cv::Mat> levels;  // RGBA, level 0 first; empty when it could not be read
  int width = 0, height = 0;    // of the original file
  bool full = false;            // false: a reduced preview, the full picture follows
  std::string error;
  std::string path;  // the picture's file; empty for a labels-only scene
};

class PictureLoader {
 public:
  explicit PictureLoader(int threads = 2, int max_width = 2048);
  ~PictureLoader();
  // Urgent requests go first and get a reduced preview; a key already queued moves to the front.
  // `root`: the study the picture belongs to, which it is read beneath (picture_codec.h: read_study_picture);
  // empty: the picture's own folder.
  void request(const std::string& key, const std::string& path, bool urgent, const std::string& root = "");
  std::vector<DecodedPicture> take_ready();
  bool idle();

 private:
  void run();
  int max_width_;
  std::mutex mu_;
  std::condition_variable cv_;
  struct Job {
    std::string key, path, root;
    bool urgent;
  };
  std::deque<Job> queue_;
  std::vector<DecodedPicture> ready_;
  bool stop_ = false;
  int busy_ = 0;
  std::vector<std::thread> threads_;
};

}  // namespace ipd::studio
