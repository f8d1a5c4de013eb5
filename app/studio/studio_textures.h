// Pictures for ipd-studio: decoded off the UI thread (a reduced version first, then the full one with its
// mipmap chain built on the decoder thread, so the UI thread only copies levels into textures), and kept
// in a texture cache bounded by bytes, least recently used out first.
#pragma once

#include <condition_variable>
#include <cstdint>
#include <deque>
#include <list>
#include <map>
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
  void request(const std::string& key, const std::string& path, bool urgent);
  std::vector<DecodedPicture> take_ready();
  bool idle();

 private:
  void run();
  int max_width_;
  std::mutex mu_;
  std::condition_variable cv_;
  struct Job {
    std::string key, path;
    bool urgent;
  };
  std::deque<Job> queue_;
  std::vector<DecodedPicture> ready_;
  bool stop_ = false;
  int busy_ = 0;
  std::vector<std::thread> threads_;
};

// What the view draws: a texture id (0: none yet) and why there is none.
struct TextureRef {
  std::uintptr_t id = 0;
  int width = 0, height = 0;
  bool full = false;
  std::string placeholder;
};

// GL textures by key, bounded by bytes (LRU). Call only from the GL thread.
class TextureCache {
 public:
  explicit TextureCache(std::size_t budget_bytes = std::size_t(512) << 20) : budget_(budget_bytes) {}
  ~TextureCache();
  // The texture for `key`, requesting it from `loader` when absent (path empty: labels-only scene).
  TextureRef get(const std::string& key, const std::string& path, bool urgent, PictureLoader& loader);
  void upload(DecodedPicture&& d);  // from PictureLoader::take_ready()
  void end_frame();                 // evicts least recently used textures over the budget
  std::size_t bytes() const { return bytes_; }

 private:
  struct Entry {
    unsigned id = 0;
    int width = 0, height = 0;
    bool full = false, requested = false, urgent = false;
    long used_frame = -1;
    std::string error;
    std::size_t bytes = 0;
    std::list<std::string>::iterator lru;
  };
  std::map<std::string, Entry> entries_;
  std::list<std::string> lru_;  // most recent first
  std::size_t budget_, bytes_ = 0;
  long frame_ = 0;
};

}  // namespace ipd::studio
