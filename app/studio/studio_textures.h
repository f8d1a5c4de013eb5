// The studio's texture cache: textures by key, bounded by bytes, least recently used out first. The cache's
// rules (what to request, what to keep, what to evict) are GL-free and tested; a TextureBackend makes and
// frees the textures themselves (OpenGL in ipd-studio, studio_gl_textures.cpp).
#pragma once

#include <cstddef>
#include <cstdint>
#include <list>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "app/studio/picture_loader.h"

namespace ipd::studio {

// Makes a texture from a mipmap chain (RGBA, level 0 first) and frees one: 0 is "no texture".
class TextureBackend {
 public:
  virtual ~TextureBackend() = default;
  virtual unsigned create(const std::vector<cv::Mat>& levels) = 0;
  virtual void destroy(unsigned id) = 0;
};

// What the view draws: a texture id (0: none yet) and why there is none.
struct TextureRef {
  std::uintptr_t id = 0;
  int width = 0, height = 0;
  bool full = false;
  std::string placeholder;
};

// Textures by key, bounded by bytes (LRU). Call only from the thread that owns the backend's context.
class TextureCache {
 public:
  explicit TextureCache(std::unique_ptr<TextureBackend> backend, std::size_t budget_bytes = std::size_t(512) << 20)
      : backend_(std::move(backend)), budget_(budget_bytes) {}
  ~TextureCache();
  TextureCache(const TextureCache&) = delete;
  TextureCache& operator=(const TextureCache&) = delete;
  // The texture for `key`, requesting it from `loader` when absent (path empty: labels-only scene).
  TextureRef get(const std::string& key, const std::string& path, bool urgent, PictureLoader& loader,
                 const std::string& root = "");
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
  std::unique_ptr<TextureBackend> backend_;
  std::map<std::string, Entry> entries_;
  std::list<std::string> lru_;  // most recent first
  std::size_t budget_, bytes_ = 0;
  long frame_ = 0;
};

}  // namespace ipd::studio
