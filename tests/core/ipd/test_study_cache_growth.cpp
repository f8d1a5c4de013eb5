// A study that gains a renderer setting between two rankings (a calibration loop): the second run takes every
// other domain's parsed labels and registrations from the parsed-study cache, parses and registers only the new
// domain's, and hashes for the label set's fingerprint only the domains from the new one on in path order.
#include <gtest/gtest.h>

#include <fmt/format.h>
#include <algorithm>
#include <filesystem>
#include <vector>

#include "core/ipd/label_fingerprint.h"
#include "core/ipd/study_cache.h"
#include "core/rank/ranking.h"
#include "core/util/atomic_file.h"
#include "core/util/sha256.h"
#include "tests/core/ipd/table_through_cache.h"
#include "tests/support/test_support.h"

namespace fs = std::filesystem;

namespace ipd {
namespace {

// Domain `name`: 3 scenes of 4 rocks (`shift` moves them right) and model det's predictions, one per scene.
void write_growth_domain(const test::TempDir& d, const std::string& name, double shift) {
  for (int k = 0; k < 3; ++k) {
    std::string gt;
    for (int r = 0; r < 4; ++r)
      gt += fmt::format("0 {:.3f} {:.3f} 0.050 0.040\n", 0.1 + 0.2 * r + shift, 0.2 + 0.15 * ((r * 3 + k) % 4));
    test::write_text(d / fmt::format("{}/labels/s{}.txt", name, k), gt);
    test::write_text(d / fmt::format("{}/predictions/det/s{}.txt", name, k),
                     fmt::format("0 {:.3f} 0.200 0.050 0.040 0.9\n", 0.1 + shift));
  }
}

struct Ranked {
  StudyCacheStats stats;
  int registrations = 0, cached = 0;  // scene pairs registered in all, and of them taken from the cache
  std::string fingerprint;
};

// One ranking's worth of work against `real`, as `ipd rank` does it: labels through the parsed-study cache, the
// (real, candidate) pairs only, registrations through the cache, then the cache saved.
Ranked rank_through_cache(const std::string& root) {
  const test::TableThroughCache r = test::table_through_cache(root, [&root](TableOptions& t) {
    t.only_pairs = ranked_pairs(resolve_rank_domains(open_study(root), "real", {}));
  });
  return {r.stats, r.table.registrations, r.table.cached_registrations, r.fingerprint};
}

TEST(StudyCacheGrowth, ANewDomainIsTheOnlyOneParsedRegisteredAndHashed) {
  test::TempDir d;
  write_growth_domain(d, "real", 0.0);
  write_growth_domain(d, "synth", 0.01);
  const Ranked first = rank_through_cache(d.path());
  EXPECT_EQ(first.stats.files_parsed, 12);  // 2 domains x 3 scenes x (GT + det)
  EXPECT_EQ(first.registrations, 3);        // (real, synth) x 3 scenes
  EXPECT_EQ(first.cached, 0);
  EXPECT_EQ(first.stats.fingerprint_domains_read, 2);

  // "zeta" sorts after both: real's and synth's files, registrations and hashing are reused.
  write_growth_domain(d, "zeta", 0.02);
  const Ranked grown = rank_through_cache(d.path());
  EXPECT_EQ(grown.stats.state, "loaded");
  EXPECT_EQ(grown.stats.files_reused, 12);
  EXPECT_EQ(grown.stats.files_parsed, 6);
  EXPECT_EQ(grown.registrations, 6);  // (real, synth) and (real, zeta): never (synth, zeta)
  EXPECT_EQ(grown.cached, 3);         // so the 3 of (real, zeta) are the only ones registered
  EXPECT_EQ(grown.stats.fingerprint_domains_read, 1);
  EXPECT_EQ(grown.fingerprint, label_set_fingerprint(open_study(d.path())));
  EXPECT_NE(grown.fingerprint, first.fingerprint);

  // "alpha" sorts first: the hash is resumed from nothing, every domain read again, and the result the same as
  // without a cache.
  write_growth_domain(d, "alpha", 0.03);
  const Ranked before_all = rank_through_cache(d.path());
  EXPECT_EQ(before_all.stats.files_reused, 18);
  EXPECT_EQ(before_all.stats.files_parsed, 6);
  EXPECT_EQ(before_all.cached, 6);
  EXPECT_EQ(before_all.registrations, 9);
  EXPECT_EQ(before_all.stats.fingerprint_domains_read, 4);
  EXPECT_EQ(before_all.fingerprint, label_set_fingerprint(open_study(d.path())));

  // A GT file of synth changes (one rock moves, same size): synth and zeta after it are hashed again, and only
  // (real, synth)'s scene s1 is registered again.
  const std::string file = d / "synth/labels/s1.txt";
  std::string text = read_file(file);
  ASSERT_EQ(text.substr(0, 6), "0 0.11");
  text[5] = '2';
  test::write_text(file, text);
  const Ranked changed = rank_through_cache(d.path());
  EXPECT_EQ(changed.stats.files_parsed, 1);
  EXPECT_EQ(changed.registrations - changed.cached, 1);
  EXPECT_EQ(changed.stats.fingerprint_domains_read, 2);
  EXPECT_EQ(changed.fingerprint, label_set_fingerprint(open_study(d.path())));
  EXPECT_NE(changed.fingerprint, before_all.fingerprint);

  // Nothing changed since: the stored fingerprint is given back, nothing hashed or registered.
  const Ranked warm = rank_through_cache(d.path());
  EXPECT_EQ(warm.stats.files_parsed, 0);
  EXPECT_EQ(warm.stats.fingerprint_domains_read, 0);
  EXPECT_EQ(warm.cached, 9);
  EXPECT_EQ(warm.fingerprint, changed.fingerprint);
  EXPECT_FALSE(warm.stats.written);
}

// Hashed a domain at a time, the files still go in the order of their full paths: "a-b/..." before "a/..." and
// "s-1.txt" before "s.txt" ('-' sorts before '/' and '.'), as a hash over the sorted paths has them.
TEST(StudyCacheGrowth, TheFingerprintHashesTheFilesInTheOrderOfTheirPaths) {
  test::TempDir d;
  std::vector<std::string> paths;
  for (const char* domain : {"a", "a-b"})
    for (const char* stem : {"s", "s-1"}) {
      const std::string rel = fmt::format("{}/labels/{}.txt", domain, stem);
      test::write_text(d / rel, fmt::format("0 0.{} 0.5 0.1 0.1\n", 1 + paths.size()));
      paths.push_back(rel);
    }
  std::sort(paths.begin(), paths.end());
  ASSERT_EQ(paths.front(), "a-b/labels/s-1.txt");
  Sha256 sha;
  for (const std::string& rel : paths) {
    const std::string text = read_file(d / rel);
    sha.add(rel + std::string(1, '\0') + std::to_string(text.size()) + std::string(1, '\0'));
    sha.add(text);
  }
  EXPECT_EQ(label_set_fingerprint(open_study(d.path())), sha.hex().substr(0, 12));
}

// SHA-256("abc") is FIPS 180-2's first example: resumed after "ab", the stream still ends in it.
TEST(StudyCacheGrowth, AHashResumedFromItsStateEndsInTheSameDigest) {
  Sha256 a;
  a.add("ab");
  std::optional<Sha256> resumed = Sha256::resume(a.state());
  ASSERT_TRUE(resumed);
  resumed->add("c");
  EXPECT_EQ(resumed->hex(), "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
  EXPECT_FALSE(Sha256::resume("not a state"));
}

}  // namespace
}  // namespace ipd

namespace ipd {
namespace {
// The parsed-study file belongs to the study's folder, not to how a command line spelled it: opened as DIR and
// then as DIR/./ (or a relative path), every file and registration is reused, and each file is named as the second
// run names the study.
TEST(StudyCacheGrowth, AStudyNamedAnotherWayReusesEverythingAndIsNamedAsGiven) {
  test::TempDir d;
  write_growth_domain(d, "real", 0.0);
  write_growth_domain(d, "synth", 0.01);
  test::write_text(d / "synth/labels/s2.txt", "0 0.5 0.5 0.1 0.1\n0 0.5\n");  // one bad line, kept as an error
  const test::TableThroughCache first = test::table_through_cache(d.path());
  EXPECT_EQ(first.stats.files_parsed, 12);
  const std::string other = d.path() + "/.";
  const test::TableThroughCache second = test::table_through_cache(other);
  EXPECT_EQ(second.stats.state, "loaded");
  EXPECT_EQ(second.stats.files_reused, 12);
  EXPECT_EQ(second.stats.files_parsed, 0);
  EXPECT_EQ(second.table.cached_registrations, 3);
  const Study study = open_study(other);
  StudyCache cache(parsed_study_cache_path(study.root), study.root);
  const StudyLabels labels = cache.load_labels(study);
  EXPECT_EQ(cache.stats().files_reused, 12);
  const LabelFile& bad = labels.gt_of("synth", "s2");
  EXPECT_EQ(bad.path, other + "/synth/labels/s2.txt");
  ASSERT_EQ(bad.errors.size(), 1u);
  EXPECT_EQ(bad.errors[0].file, other + "/synth/labels/s2.txt");
}
}  // namespace
}  // namespace ipd
