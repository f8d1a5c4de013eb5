// What makes a registration cache entry unusable, whatever seals it: another key's entry under this key's
// name, and stored pairs that name a rock the scene no longer has.
#include <gtest/gtest.h>

#include <filesystem>

#include "core/registration/registration_cache.h"
#include "tests/support/test_support.h"

namespace fs = std::filesystem;

namespace ipd {
namespace {

using test::box;

std::vector<Box> seven(double dx) {
  std::vector<Box> out;
  const double xs[] = {0.1, 0.35, 0.6, 0.8, 0.2, 0.5, 0.75};
  const double ys[] = {0.2, 0.15, 0.3, 0.6, 0.7, 0.5, 0.85};
  for (int k = 0; k < 7; ++k) out.push_back(box(xs[k] + dx, ys[k], 0.04 + 0.005 * k, 0.05));
  return out;
}

// An entry is the answer for one pair of box sets: copied under another key's file name (another scene, or
// other options) it is not used there, sealed or not.
TEST(RegistrationCacheRules, AnEntryUnderAnotherKeysNameIsNotUsed) {
  test::TempDir d;
  const RegistrationCache cache(d / "cache");
  const auto a = seven(0), b = seven(0.02), c = seven(0.04);
  ASSERT_TRUE(cache.store(registration_cache_key(a, b, {}), register_rocks(a, b, {})));
  const std::string other = registration_cache_key(a, c, {});
  fs::create_directories(fs::path(cache.entry_path(other)).parent_path());
  fs::copy_file(cache.entry_path(registration_cache_key(a, b, {})), cache.entry_path(other));
  EXPECT_FALSE(cache.load(other, 7, 7).has_value());
  EXPECT_TRUE(cache.load(registration_cache_key(a, b, {}), 7, 7).has_value());
}

// The entry pairs all seven rocks (indices 0-6). A scene of six rocks on a side has no rock 6: unusable, on
// either side.
TEST(RegistrationCacheRules, StoredPairsMustNameRocksTheSceneHas) {
  test::TempDir d;
  const RegistrationCache cache(d / "cache");
  const auto a = seven(0), b = seven(0.02);
  const RegistrationReport r = register_rocks(a, b, {});
  ASSERT_EQ(r.pairs.size(), 7u);
  const std::string key = registration_cache_key(a, b, {});
  ASSERT_TRUE(cache.store(key, r));
  const RegistrationCache fresh(d / "cache");  // reads the file, not what store() remembered
  EXPECT_TRUE(fresh.load(key, 7, 7).has_value());
  EXPECT_FALSE(RegistrationCache(d / "cache").load(key, 6, 7).has_value());
  EXPECT_FALSE(RegistrationCache(d / "cache").load(key, 7, 6).has_value());
}

// Two sides with exactly the same boxes stop before any search (the identity): such an entry is read back like
// any other (labels-only twins are mostly like this).
TEST(RegistrationCacheRules, AnIdenticalLayoutsEntryIsReused) {
  test::TempDir d;
  const auto a = seven(0);
  const RegistrationReport r = register_rocks(a, a, {});
  ASSERT_EQ(r.stop, StopReason::kIdenticalLayouts);
  const std::string key = registration_cache_key(a, a, {});
  ASSERT_TRUE(RegistrationCache(d / "cache").store(key, r));
  const std::optional<RegistrationReport> back = RegistrationCache(d / "cache").load(key, 7, 7);
  ASSERT_TRUE(back.has_value());
  EXPECT_EQ(back->stop, StopReason::kIdenticalLayouts);
  EXPECT_EQ(back->pairs, r.pairs);
}

// The key's bytes for given settings change only with kFormat: entries written by an earlier build stay valid.
// Pinned for the defaults, for paper with its own trial count, a time budget and an aspect, and for consensus
// with a gate, a work budget and its own trial count.
TEST(RegistrationCacheRules, TheKeyOfGivenSettingsIsPinned) {
  const auto a = seven(0), b = seven(0.02);
  EXPECT_EQ(registration_cache_key(a, b, RegistrationOptions()), "07d3dfeeb9976ca7042e64c2dec5ccde");
  RegistrationOptions p;
  p.method = RegistrationMethod::kPaper;
  p.paper.samples = 5;
  p.time_budget_ms = 7;
  p.aspect = 1.6;
  EXPECT_EQ(registration_cache_key(a, b, p), "2150594c5cb61f7e7aec22db906c962b");
  RegistrationOptions c;
  c.consensus.inlier_gate = 0.01;
  c.work_budget = 1e5;
  c.consensus.max_hypotheses = 9;
  EXPECT_EQ(registration_cache_key(a, b, c), "b84c74a0423a3a9b2481f355512a337a");
}

// Every option that can change the answer is part of the key: changing one never reuses another's entry.
TEST(RegistrationCacheRules, TheKeyCoversEveryOptionThatChangesTheAnswer) {
  const auto a = seven(0), b = seven(0.02);
  const RegistrationOptions base;
  const std::string key = registration_cache_key(a, b, base);
  const std::vector<std::pair<const char*, void (*)(RegistrationOptions*)>> changes = {
      {"method", [](RegistrationOptions* o) { o->method = RegistrationMethod::kCpd; }},
      {"seed", [](RegistrationOptions* o) { o->seed = 1; }},
      {"consensus.max_hypotheses", [](RegistrationOptions* o) { o->consensus.max_hypotheses = 999; }},
      {"paper.samples", [](RegistrationOptions* o) { o->method = RegistrationMethod::kPaper, o->paper.samples = 9; }},
      {"time_budget_ms", [](RegistrationOptions* o) { o->time_budget_ms = 5; }},
      {"aspect", [](RegistrationOptions* o) { o->aspect = 1.6; }},
      {"pair_gate", [](RegistrationOptions* o) { o->paper.pair_gate = 0.3; }},
      {"min_scale", [](RegistrationOptions* o) { o->consensus.min_scale = 0.6; }},
      {"max_scale", [](RegistrationOptions* o) { o->consensus.max_scale = 1.9; }},
      {"max_rotation_deg", [](RegistrationOptions* o) { o->consensus.max_rotation_deg = 20; }},
      {"max_anisotropy", [](RegistrationOptions* o) { o->consensus.max_anisotropy = 1.5; }},
      {"inlier_gate", [](RegistrationOptions* o) { o->consensus.inlier_gate = 0.01; }},
      {"min_pair_iou", [](RegistrationOptions* o) { o->min_pair_iou = 0.2; }},
      {"pair_noise_floor", [](RegistrationOptions* o) { o->pair_noise_floor = 0.02; }},
      {"pair_max_size_ratio", [](RegistrationOptions* o) { o->pair_max_size_ratio = 1.5; }},
      {"cpd.iterations", [](RegistrationOptions* o) { o->cpd.iterations = 50; }},
      {"cpd.outlier_weight", [](RegistrationOptions* o) { o->cpd.outlier_weight = 0.3; }},
      {"work_budget", [](RegistrationOptions* o) { o->work_budget = 1e5; }},
  };
  for (const auto& [name, change] : changes) {
    RegistrationOptions o = base;
    change(&o);
    EXPECT_NE(registration_cache_key(a, b, o), key) << name;
  }
}

}  // namespace
}  // namespace ipd
