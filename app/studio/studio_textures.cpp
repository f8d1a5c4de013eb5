#include "app/studio/studio_textures.h"

namespace ipd::studio {

TextureCache::~TextureCache() {
  for (auto& [k, e] : entries_)
    if (e.id) backend_->destroy(e.id);
}

TextureRef TextureCache::get(const std::string& key, const std::string& path, bool urgent, PictureLoader& loader,
                             const std::string& root) {
  auto it = entries_.find(key);
  if (it == entries_.end()) {
    Entry e;
    lru_.push_front(key);
    e.lru = lru_.begin();
    it = entries_.emplace(key, e).first;
  } else {
    lru_.splice(lru_.begin(), lru_, it->second.lru);
  }
  Entry& e = it->second;
  // Ask again when a prefetched picture becomes the current one (it jumps the queue).
  if (!e.requested || (urgent && !e.urgent && !e.id && e.error.empty())) {
    loader.request(key, path, urgent, root);
    e.requested = true;
    e.urgent = urgent;
  }
  e.used_frame = frame_;
  TextureRef r;
  r.id = e.id;
  r.width = e.width;
  r.height = e.height;
  r.full = e.full || !e.error.empty();
  r.placeholder = e.id ? "" : (e.error.empty() ? "loading..." : e.error);
  return r;
}

void TextureCache::upload(DecodedPicture&& d) {
  auto it = entries_.find(d.key);
  if (it == entries_.end()) return;  // evicted meanwhile
  Entry& e = it->second;
  if (e.full && !d.full) return;  // a preview arriving after the full picture
  if (e.id) {
    backend_->destroy(e.id);
    bytes_ -= e.bytes;
    e.id = 0;
    e.bytes = 0;
  }
  e.width = d.width;
  e.height = d.height;
  e.full = d.full;
  e.error = d.error;
  if (d.levels.empty()) return;
  e.id = backend_->create(d.levels);
  if (!e.id) return;
  for (const cv::Mat& m : d.levels) e.bytes += m.total() * 4;
  bytes_ += e.bytes;
}

void TextureCache::end_frame() {
  // Oldest first; what this frame drew always stays.
  while (bytes_ > budget_ && !lru_.empty()) {
    const std::string key = lru_.back();
    auto it = entries_.find(key);
    if (it->second.used_frame == frame_) break;
    lru_.pop_back();
    if (it->second.id) backend_->destroy(it->second.id);
    bytes_ -= it->second.bytes;
    entries_.erase(it);
  }
  ++frame_;
}

}  // namespace ipd::studio
