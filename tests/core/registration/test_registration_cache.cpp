// The on-disk registration cache: same answer as registering, recomputed when an entry is corrupt, keyed by
// boxes and options, and shared by `ipd table` (compute_cross_table) and the session.
#include <gtest/gtest.h>

#include <filesystem>
#include <fmt/format.h>
#include <fstream>

#include "core/util/atomic_file.h"
#include "core/ipd/ipd.h"
#include "core/registration/registration_cache.h"
#include "core/session/session.h"
#include "tests/support/test_support.h"

namespace fs = std::filesystem;

namespace ipd {
namespace {

std::vector<Box> rocks(double dx) {
  std::vector<Box> out;
  const double xs[] = {0.1, 0.35, 0.6, 0.8, 0.2, 0.5, 0.75};
  const double ys[] = {0.2, 0.15, 0.3, 0.6, 0.7, 0.5, 0.85};
  for (int k = 0; k < 7; ++k) out.push_back(Box{0, xs[k] + dx, ys[k], 0.04 + 0.005 * k, 0.05, 1.0});
  return out;
}

TEST(RegistrationCache, StoresLoadsAndRecomputesCorruptEntries) {
  test::TempDir d;
  const RegistrationCache cache(d / "cache");
  const auto a = rocks(0), b = rocks(0.02);
  RegistrationOptions o;
  bool hit = true;
  const RegistrationReport first = register_rocks_cached(&cache, a, b, o, &hit);
  EXPECT_FALSE(hit);
  EXPECT_EQ(first.pairs.size(), 7u);
  const RegistrationReport again = register_rocks_cached(&cache, a, b, o, &hit);
  EXPECT_TRUE(hit);
  EXPECT_EQ(again.pairs, first.pairs);
  EXPECT_TRUE(again.affine.isApprox(first.affine, 1e-15));
  EXPECT_EQ(again.inliers, first.inliers);
  EXPECT_EQ(again.stop, first.stop);

  // Another seed, another box: other keys.
  RegistrationOptions o2 = o;
  o2.seed = 5;
  const std::string key = registration_cache_key(a, b, o);
  EXPECT_NE(registration_cache_key(a, b, o2), key);
  EXPECT_NE(registration_cache_key(a, rocks(0.021), o), key);
  EXPECT_EQ(key.size(), 32u);

  // A flipped digit fails the checksum; a truncated entry fails to parse; both are recomputed.
  const std::string path = cache.entry_path(key);
  std::string text = read_file(path);
  const size_t at = text.find("\"pairs\":[[") + 10;
  text[at] = text[at] == '1' ? '2' : '1';
  write_file_atomically(path, text);
  EXPECT_FALSE(cache.load(key, 7, 7).has_value());
  EXPECT_EQ(register_rocks_cached(&cache, a, b, o, &hit).pairs, first.pairs);
  EXPECT_FALSE(hit);
  write_file_atomically(path, read_file(path).substr(0, 40));
  EXPECT_FALSE(cache.load(key, 7, 7).has_value());
  EXPECT_EQ(register_rocks_cached(&cache, a, b, o, &hit).pairs, first.pairs);
  EXPECT_FALSE(hit);
  // Counts that don't fit the stored pairs: unusable.
  EXPECT_TRUE(cache.load(key, 7, 7).has_value());
  EXPECT_FALSE(cache.load(key, 3, 7).has_value());
}

TEST(RegistrationCache, TableAndSessionShareItAndAgree) {
  test::TempDir d;
  for (int k = 0; k < 3; ++k) {
    std::string real, synth, det_real, det_synth;
    for (const Box& x : rocks(0.01 * k)) real += fmt::format("0 {} {} {} {}\n", x.cx, x.cy, x.w, x.h);
    for (const Box& x : rocks(0.01 * k + 0.03)) synth += fmt::format("0 {} {} {} {}\n", x.cx, x.cy, x.w, x.h);
    test::write_text(d / fmt::format("real/labels/s{}.txt", k), real);
    test::write_text(d / fmt::format("synth/labels/s{}.txt", k), synth);
    test::write_text(d / fmt::format("real/predictions/det/s{}.txt", k), "0 0.1 0.2 0.04 0.05 0.9\n");
    test::write_text(d / fmt::format("synth/predictions/det/s{}.txt", k), "0 0.13 0.2 0.04 0.05 0.9\n");
  }
  const StudyLabels labels = load_labels(open_study(d.path()));
  TableOptions t;
  t.cache_dir = registration_cache_dir(d.path());
  EXPECT_EQ(t.cache_dir, (fs::path(d.path()) / ".ipd-cache" / "registration").string());
  const CrossTable cold = compute_cross_table(labels, t);
  EXPECT_EQ(cold.registrations, 3);
  EXPECT_EQ(cold.cached_registrations, 0);
  const CrossTable warm = compute_cross_table(labels, t);
  EXPECT_EQ(warm.cached_registrations, 3);
  EXPECT_DOUBLE_EQ(warm.cells[0].ipd, cold.cells[0].ipd);
  EXPECT_EQ(warm.cells[0].pairs, cold.cells[0].pairs);

  SessionOptions so;
  so.cache_dir = t.cache_dir;
  const Session s = Session::open(d.path(), so);
  EXPECT_EQ(s.cached_registrations(), 3);
  EXPECT_DOUBLE_EQ(s.totals().ipd(), cold.cells[0].ipd);
}

}  // namespace
}  // namespace ipd
