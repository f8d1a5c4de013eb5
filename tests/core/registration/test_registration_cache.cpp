// The on-disk registration cache: same answer as registering, recomputed when an entry is corrupt, keyed by
// boxes and options, and shared by `ipd table` (compute_cross_table) and the session.
#include <gtest/gtest.h>

#include <fmt/format.h>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "core/ipd/ipd.h"
#include "core/registration/registration_cache.h"
#include "core/session/session.h"
#include "core/util/atomic_file.h"
#include "core/util/cache_signer.h"
#include "tests/support/test_support.h"

namespace fs = std::filesystem;

namespace ipd {
namespace {

std::vector<Box> rocks(double dx) { return test::seven_rocks(dx); }

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
  // What the search counted and its fit, under the same measure (a bare number could not say which way is better).
  EXPECT_EQ(again.samples, first.samples);
  EXPECT_EQ(again.em_iterations, first.em_iterations);
  EXPECT_EQ(again.hypotheses, first.hypotheses);
  EXPECT_EQ(again.fit.measure, FitMeasure::kSoftInliers);
  EXPECT_EQ(again.fit.value, first.fit.value);

  // Another seed, another box: other keys.
  RegistrationOptions o2 = o;
  o2.seed = 5;
  const std::string key = registration_cache_key(a, b, o);
  EXPECT_NE(registration_cache_key(a, b, o2), key);
  EXPECT_NE(registration_cache_key(a, rocks(0.021), o), key);
  EXPECT_EQ(key.size(), 32u);

  // A flipped digit fails the signature; a truncated entry fails to parse; both are recomputed.
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

// A twin rendered from the same labels is registered without a search (stop reason 'identical layouts',
// the enum's last): its entry is read back like any other, not registered again at every open.
TEST(RegistrationCache, IdenticalLayoutsAreReadBack) {
  test::TempDir d;
  const RegistrationCache cache(d / "cache");
  const auto a = rocks(0);
  RegistrationOptions o;
  bool hit = true;
  const RegistrationReport first = register_rocks_cached(&cache, a, a, o, &hit);
  ASSERT_EQ(first.stop, StopReason::kIdenticalLayouts);
  EXPECT_FALSE(hit);
  const RegistrationReport again = register_rocks_cached(&cache, a, a, o, &hit);
  EXPECT_TRUE(hit);
  EXPECT_EQ(again.stop, StopReason::kIdenticalLayouts);
  EXPECT_EQ(again.pairs, first.pairs);
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
  EXPECT_DOUBLE_EQ(s.cell().ipd, cold.cells[0].ipd);
}

TEST(RegistrationCache, ForgedOrForeignEntriesAreIgnoredRecomputedAndOverwritten) {
  test::TempDir d;
  const RegistrationCache cache(d / "cache");
  const auto a = rocks(0), b = rocks(0.02);
  const RegistrationOptions o;
  const RegistrationReport first = register_rocks_cached(&cache, a, b, o);
  const std::string key = registration_cache_key(a, b, o);
  const std::string path = cache.entry_path(key);
  nlohmann::json j = nlohmann::json::parse(read_file(path).substr(0, read_file(path).find('\n')));
  j["pairs"] = {{0, 6}};  // a well-formed entry that would change every IPD using it
  const std::string forged = j.dump();
  // Signed by this installation it would be served: the signature is the only thing that stops it.
  write_file_atomically(path,
                        forged + "\n" + CacheSigner::instance().mac_hex(kRegistrationEntrySignature, forged) + "\n");
  ASSERT_TRUE(cache.load(key, 7, 7).has_value());
  EXPECT_EQ(cache.load(key, 7, 7)->pairs, (RockPairs{{0, 6}}));
  // Signed by another installation (a study copied with its cache), or carrying the old unkeyed checksum:
  // ignored, recomputed and overwritten with an entry this installation trusts.
  for (const std::string& sig :
       {CacheSigner(d / "other/key").mac_hex(kRegistrationEntrySignature, forged), std::string("0123456789abcdef")}) {
    write_file_atomically(path, forged + "\n" + sig + "\n");
    EXPECT_FALSE(cache.load(key, 7, 7).has_value());
    bool hit = true;
    EXPECT_EQ(register_rocks_cached(&cache, a, b, o, &hit).pairs, first.pairs);
    EXPECT_FALSE(hit);
    ASSERT_TRUE(cache.load(key, 7, 7).has_value());
    EXPECT_EQ(cache.load(key, 7, 7)->pairs, first.pairs);
  }
}

// A study shipped with caches signed elsewhere: `ipd table` prints exactly what --no-cache prints, and the
// forged entries, which change the table under the key that signed them (so the test can tell), are replaced.
TEST(RegistrationCache, ForeignCachesChangeNothingInTheTable) {
  test::TempDir d;
  ASSERT_EQ(test::run_ipd(fmt::format("demo {} --labels-only --scenes 3 --rocks 12", d / "study")).exit_code, 0);
  auto table_as = [&](const std::string& home, const std::string& extra = "") {
    const test::CommandResult r = test::run_command(fmt::format(
        "XDG_CACHE_HOME={} {} table {} --format csv --bootstrap 0 {}", d / home, IPD_BINARY, d / "study", extra));
    EXPECT_EQ(r.exit_code, 0) << r.err;
    return r.out;
  };
  const std::string fresh = table_as("mine", "--no-cache");
  // One entry file per registration, as `ipd table` keys them (compute_cross_table with the study's options).
  {
    const StudyLabels labels = load_labels(open_study(d / "study"));
    TableOptions t;
    t.registration = labels.study.config.registration;
    t.cache_dir = registration_cache_dir(d / "study");
    EXPECT_EQ(compute_cross_table(labels, t).registrations, 9);  // 3 domain pairs x 3 scenes
  }
  // Each forged to pair nothing and signed with the collaborator's key.
  auto entries = [&] {
    std::vector<fs::path> out;
    for (const auto& e : fs::recursive_directory_iterator(d / "study/.ipd-cache/registration"))
      if (e.path().extension() == ".json") out.push_back(e.path());
    return out;
  };
  ASSERT_EQ(entries().size(), 9u);
  for (const fs::path& p : entries()) {
    const std::string text = read_file(p.string());
    nlohmann::json j = nlohmann::json::parse(text.substr(0, text.find('\n')));
    j["pairs"] = nlohmann::json::array();
    const std::string payload = j.dump();
    write_file_atomically(
        p.string(),
        payload + "\n" + CacheSigner(d / "theirs/ipd-studio/key").mac_hex(kRegistrationEntrySignature, payload) + "\n");
  }
  EXPECT_NE(table_as("theirs"), fresh);  // under the key that signed them, the forgeries count
  // Their run also left a parsed-study file holding the forged registrations, signed with their key.
  ASSERT_TRUE(fs::exists(d / "study/.ipd-cache/parsed-study.bin"));
  EXPECT_EQ(table_as("mine"), fresh);  // under mine: both ignored and recomputed, byte for byte
  EXPECT_EQ(table_as("mine"), fresh);  // and what replaced them is served as the same
  // The forged entry files were overwritten with ones this installation signed.
  const CacheSigner mine(d / "mine/ipd-studio/key");
  for (const fs::path& p : entries()) {
    const std::string text = read_file(p.string());
    const size_t nl = text.find('\n');
    EXPECT_EQ(text.substr(nl + 1, 64), mine.mac_hex(kRegistrationEntrySignature, text.substr(0, nl))) << p;
  }
}

}  // namespace
}  // namespace ipd
