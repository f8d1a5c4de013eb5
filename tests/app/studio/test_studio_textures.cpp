// The studio's pictures without a window: the decoder threads (preview first, then the full mipmap chain;
// why a picture is missing) and the texture cache's rules (what it asks for, what it keeps, what it evicts),
// with a backend that counts textures instead of making them.
#include <gtest/gtest.h>

#include <chrono>
#include <memory>
#include <opencv2/imgcodecs.hpp>
#include <thread>

#include "app/studio/picture_loader.h"
#include "app/studio/studio_textures.h"
#include "tests/support/test_support.h"

namespace ipd::studio {
namespace {

// Everything the loader delivers until it is idle (bounded: a hung loader fails instead of hanging).
std::vector<DecodedPicture> drain(PictureLoader& loader) {
  std::vector<DecodedPicture> out;
  for (int k = 0; k < 2000 && !loader.idle(); ++k) {
    for (auto& d : loader.take_ready()) out.push_back(std::move(d));
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  for (auto& d : loader.take_ready()) out.push_back(std::move(d));
  EXPECT_TRUE(loader.idle()) << "the loader never finished";
  return out;
}

std::string write_png(const test::TempDir& d, int w, int h) {
  const std::string path = d / "picture.png";
  cv::imwrite(path, cv::Mat(h, w, CV_8UC3, cv::Scalar(10, 20, 30)));
  return path;
}

TEST(PictureLoader, AnUrgentPictureComesAsAPreviewThenInFullWithItsMipmaps) {
  test::TempDir d;
  const std::string path = write_png(d, 800, 600);
  PictureLoader loader(1);
  loader.request("real/s1", path, true);
  const auto got = drain(loader);
  ASSERT_EQ(got.size(), 2u);
  EXPECT_FALSE(got[0].full);
  ASSERT_EQ(got[0].levels.size(), 1u);
  EXPECT_EQ(got[0].levels[0].cols, 200);  // a quarter, to show something at once
  EXPECT_EQ(got[0].levels[0].rows, 150);
  EXPECT_EQ(got[0].width, 800);  // the original's size, so the view lays out the real picture
  EXPECT_TRUE(got[1].full);
  EXPECT_EQ(got[1].key, "real/s1");
  EXPECT_EQ(got[1].error, "");
  // 800x600, 400x300, ..., 3x2, 1x1: each level half the one before, down to one pixel.
  ASSERT_EQ(got[1].levels.size(), 10u);
  EXPECT_EQ(got[1].levels[1].cols, 400);
  EXPECT_EQ(got[1].levels[1].rows, 300);
  EXPECT_EQ(got[1].levels.back().cols, 1);
  EXPECT_EQ(got[1].levels.back().rows, 1);
  EXPECT_EQ(got[1].levels[0].channels(), 4);  // RGBA, as the textures take it
  const cv::Vec4b px = got[1].levels[0].at<cv::Vec4b>(0, 0);
  EXPECT_EQ(px, cv::Vec4b(30, 20, 10, 255));  // BGR (10, 20, 30) read as RGB
}

TEST(PictureLoader, AWidePictureIsReducedButKeepsItsSize) {
  test::TempDir d;
  const std::string path = write_png(d, 800, 600);
  PictureLoader loader(1, 400);
  loader.request("k", path, false);
  const auto got = drain(loader);
  ASSERT_EQ(got.size(), 1u);  // not urgent: no preview
  EXPECT_EQ(got[0].levels[0].cols, 400);
  EXPECT_EQ(got[0].levels[0].rows, 300);
  EXPECT_EQ(got[0].width, 800);
  EXPECT_EQ(got[0].height, 600);
}

TEST(PictureLoader, SaysWhyThereIsNoPicture) {
  test::TempDir d;
  test::write_text(d / "broken.png", "not a PNG");
  PictureLoader loader(1);
  loader.request("labels-only", "", true);
  loader.request("gone", d / "gone.png", true);
  loader.request("broken", d / "broken.png", false);
  std::map<std::string, std::string> why;
  for (const auto& p : drain(loader)) {
    EXPECT_TRUE(p.levels.empty());
    why[p.key] = p.error;
  }
  EXPECT_EQ(why["labels-only"], "no picture for this scene (labels only)");
  EXPECT_EQ(why["gone"], "missing picture: " + d / "gone.png");
  EXPECT_EQ(why["broken"], "cannot decode " + d / "broken.png");
}

// Counts textures: the ids it made and still holds, and every id it was asked to free.
struct Textures {
  std::set<unsigned> live;
  std::vector<unsigned> destroyed;
  unsigned next = 1;
};

class CountingBackend : public TextureBackend {
 public:
  explicit CountingBackend(Textures* t) : t_(t) {}
  unsigned create(const std::vector<cv::Mat>&) override {
    t_->live.insert(t_->next);
    return t_->next++;
  }
  void destroy(unsigned id) override {
    EXPECT_EQ(t_->live.erase(id), 1u) << "texture " << id << " freed twice or never made";
    t_->destroyed.push_back(id);
  }

 private:
  Textures* t_;
};

// A decoded 100x100 picture: 40,000 bytes of RGBA in one level.
DecodedPicture decoded(const std::string& key, bool full = true) {
  DecodedPicture d;
  d.key = key;
  d.full = full;
  d.width = d.height = 100;
  d.levels.push_back(cv::Mat(100, 100, CV_8UC4, cv::Scalar::all(0)));
  return d;
}

TEST(TextureCache, KeepsWhatWasDrawnAndEvictsTheLeastRecentlyUsedOverItsBudget) {
  Textures t;
  PictureLoader idle(0);  // no decoder threads: requests wait, the test uploads by hand
  {
    TextureCache cache(std::make_unique<CountingBackend>(&t), 100000);  // room for two 40,000-byte pictures
    TextureRef r = cache.get("a", "a.png", true, idle);
    EXPECT_EQ(r.id, 0u);
    EXPECT_EQ(r.placeholder, "loading...");
    cache.upload(decoded("a"));
    r = cache.get("a", "a.png", true, idle);
    EXPECT_EQ(r.id, 1u);
    EXPECT_TRUE(r.full);
    EXPECT_EQ(r.placeholder, "");
    EXPECT_EQ(cache.bytes(), 40000u);
    cache.end_frame();
    for (const char* k : {"b", "c"}) {
      cache.get(k, "", false, idle);
      cache.upload(decoded(k));
    }
    // Three pictures drawn in one frame stay, over the budget: what is on screen is never evicted.
    cache.get("a", "a.png", false, idle);
    cache.end_frame();
    EXPECT_EQ(cache.bytes(), 120000u);
    EXPECT_TRUE(t.destroyed.empty());
    // Next frame draws only c: the least recently used go until the rest fits (b is enough).
    cache.get("c", "", false, idle);
    cache.end_frame();
    EXPECT_EQ(t.destroyed, (std::vector<unsigned>{2}));  // b, drawn before a's last use
    EXPECT_EQ(cache.bytes(), 80000u);
    // An evicted picture is asked for again, not shown stale.
    r = cache.get("b", "", false, idle);
    EXPECT_EQ(r.id, 0u);
    EXPECT_EQ(r.placeholder, "loading...");
  }
  EXPECT_TRUE(t.live.empty()) << "the cache frees its textures";
}

TEST(TextureCache, APreviewAfterTheFullPictureIsIgnoredAndAnErrorIsShown) {
  Textures t;
  PictureLoader idle(0);
  TextureCache cache(std::make_unique<CountingBackend>(&t));
  cache.get("a", "a.png", true, idle);
  cache.upload(decoded("a", false));  // the preview
  EXPECT_FALSE(cache.get("a", "a.png", true, idle).full);
  cache.upload(decoded("a", true));  // the full picture replaces it
  EXPECT_EQ(t.destroyed, (std::vector<unsigned>{1}));
  cache.upload(decoded("a", false));  // a late preview
  const TextureRef r = cache.get("a", "a.png", true, idle);
  EXPECT_EQ(r.id, 2u);
  EXPECT_TRUE(r.full);
  EXPECT_EQ(t.live.size(), 1u);

  DecodedPicture gone;
  gone.key = "b";
  gone.full = true;
  gone.error = "missing picture: b.png";
  cache.get("b", "b.png", true, idle);
  cache.upload(std::move(gone));
  const TextureRef e = cache.get("b", "b.png", true, idle);
  EXPECT_EQ(e.id, 0u);
  EXPECT_TRUE(e.full);  // nothing more will come
  EXPECT_EQ(e.placeholder, "missing picture: b.png");
  cache.upload(decoded("never-asked"));  // evicted or never requested: dropped
  EXPECT_EQ(t.live.size(), 1u);
}

}  // namespace
}  // namespace ipd::studio
