// The parsed-study cache (study_cache.h): reopening reuses unchanged label files and registrations, and a
// truncated, corrupt or stale cache is never trusted: the study reads exactly as without a cache.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <fmt/format.h>
#include <filesystem>

#include "core/ipd/label_fingerprint.h"
#include "core/ipd/study_cache.h"
#include "core/session/session.h"
#include "core/util/atomic_file.h"
#include "core/util/cache_signer.h"
#include "tests/core/ipd/table_through_cache.h"
#include "tests/support/test_support.h"

namespace fs = std::filesystem;

namespace ipd {
namespace {

// Two domains x 3 scenes of 6 rocks, one model; scene s2 of `synth` has a malformed line.
void write_cache_study(const test::TempDir& d) {
  for (int k = 0; k < 3; ++k) {
    std::string real, synth;
    for (int r = 0; r < 6; ++r) {
      real += fmt::format("0 {:.3f} {:.3f} 0.050 0.040\n", 0.1 + 0.13 * r, 0.2 + 0.1 * ((r * 7 + k) % 5));
      synth += fmt::format("0 {:.3f} {:.3f} 0.050 0.040\n", 0.12 + 0.13 * r, 0.2 + 0.1 * ((r * 7 + k) % 5));
    }
    if (k == 2) synth += "0 0.5 0.5 oops 0.1\n";
    test::write_text(d / fmt::format("real/labels/s{}.txt", k), real);
    test::write_text(d / fmt::format("synth/labels/s{}.txt", k), synth);
    test::write_text(d / fmt::format("real/predictions/det/s{}.txt", k), "0 0.100 0.200 0.050 0.040 0.9\n");
    test::write_text(d / fmt::format("synth/predictions/det/s{}.txt", k), "0 0.120 0.200 0.050 0.040 0.8\n");
  }
}

// Every file's boxes, lines and errors, as one comparable text.
std::string dump(const StudyLabels& l) {
  std::string out;
  auto file = [&](const LabelFile& f) {
    out += fmt::format("{} exists={}\n", f.path, f.exists);
    for (size_t k = 0; k < f.boxes.size(); ++k) {
      const Box& b = f.boxes[k];
      out += fmt::format("  {} {} {} {} {} {} line {}\n", b.cls, b.cx, b.cy, b.w, b.h, b.conf, f.line_of_box[k]);
    }
    for (const auto& e : f.errors) out += "  error " + e.to_string() + "\n";
  };
  for (const auto& [d, stems] : l.gt)
    for (const auto& [s, f] : stems) file(f);
  for (const auto& [d, models] : l.predictions)
    for (const auto& [m, stems] : models)
      for (const auto& [s, f] : stems) file(f);
  return out;
}

struct Opened {
  std::string labels;
  StudyCacheStats stats;
  std::string fingerprint;  // StudyLabels::label_fingerprint as the load left it
};

// One open through the cache, as Session::open does it (labels, then save).
Opened open_cached(const std::string& root) {
  const Study study = open_study(root);
  StudyCache cache(parsed_study_cache_path(root), study.root);
  StudyLabels labels = cache.load_labels(study);
  RegistrationCache registration("");
  registration.preload(cache.take_registrations());
  cache.save(labels, registration);
  return {dump(labels), cache.stats(), labels.label_fingerprint};
}

TEST(StudyCache, ReopenReusesEveryFileAndReadsTheSame) {
  test::TempDir d;
  write_cache_study(d);
  const std::string fresh = dump(load_labels(open_study(d.path())));
  EXPECT_NE(fresh.find("s2.txt:7: "), std::string::npos) << fresh;  // the malformed line is reported

  const Opened first = open_cached(d.path());
  EXPECT_EQ(first.stats.state, "missing");
  EXPECT_EQ(first.stats.files_parsed, 12);
  EXPECT_TRUE(first.stats.written);
  EXPECT_EQ(parsed_study_cache_path(d.path()), (fs::path(d.path()) / ".ipd-cache" / "parsed-study.bin").string());
  EXPECT_EQ(first.labels, fresh);

  const Opened again = open_cached(d.path());
  EXPECT_EQ(again.stats.state, "loaded");
  EXPECT_EQ(again.stats.files_reused, 12);
  EXPECT_EQ(again.stats.files_parsed, 0);
  EXPECT_FALSE(again.stats.written);  // nothing changed: not rewritten
  EXPECT_EQ(again.labels, fresh);
}

// Shortened in place while it is being read (anyone who can write the study can): read into memory, the
// file reads short and is ignored; a mapped file would have crashed the program (SIGBUS) at the next access.
TEST(StudyCache, ACacheShortenedWhileItIsReadIsIgnoredWithoutACrash) {
  test::TempDir d;
  write_cache_study(d);
  const std::string fresh = dump(load_labels(open_study(d.path())));
  open_cached(d.path());
  const std::string path = parsed_study_cache_path(d.path());
  const size_t size = read_file(path).size();
  const Study study = open_study(d.path());
  StudyCache cache(path, study.root, [&](const char* step) {
    if (std::string(step) == "opened") {
      ASSERT_EQ(::truncate(path.c_str(), static_cast<off_t>(size / 2)), 0);
    }
  });
  EXPECT_EQ(cache.stats().state, "ignored: truncated");
  EXPECT_EQ(dump(cache.load_labels(study)), fresh);
}

TEST(StudyCache, TruncatedOrFlippedCacheIsIgnoredAndRebuilt) {
  test::TempDir d;
  write_cache_study(d);
  const std::string fresh = dump(load_labels(open_study(d.path())));
  open_cached(d.path());
  const std::string path = parsed_study_cache_path(d.path());
  const std::string good = read_file(path);

  write_file_atomically(path, good.substr(0, good.size() - 9));
  Opened o = open_cached(d.path());
  EXPECT_EQ(o.stats.state, "ignored: truncated");
  EXPECT_EQ(o.stats.files_parsed, 12);
  EXPECT_EQ(o.labels, fresh);
  EXPECT_EQ(read_file(path), good);  // rebuilt

  // One byte inside a stored box: the signature refuses the file.
  std::string flipped = good;
  const size_t at = flipped.size() / 2;
  flipped[at] = static_cast<char>(flipped[at] ^ 0x10);
  write_file_atomically(path, flipped);
  o = open_cached(d.path());
  EXPECT_EQ(o.stats.state, "ignored: not signed by this installation");
  EXPECT_EQ(o.labels, fresh);

  write_file_atomically(path, "IPDSTUDY");
  EXPECT_EQ(open_cached(d.path()).stats.state, "ignored: not a parsed-study cache");
  std::string other_version = good;
  other_version[8] = static_cast<char>(other_version[8] + 1);
  write_file_atomically(path, other_version);
  EXPECT_EQ(open_cached(d.path()).stats.state, "ignored: another format version");
}

// A parsed-study file is served only when this installation signed it: one that came with the study
// (signed by another key) is rebuilt, and what is served equals a fresh parse.
TEST(StudyCache, AFileSignedElsewhereIsIgnoredAndRebuilt) {
  test::TempDir d;
  write_cache_study(d);
  const std::string fresh = dump(load_labels(open_study(d.path())));
  open_cached(d.path());
  const std::string path = parsed_study_cache_path(d.path());
  const std::string good = read_file(path);
  // Move real/s0's first box from x 0.100 to 0.900, re-signing the payload with `key_path`.
  const double from = 0.1, to = 0.9;
  const size_t at = good.find(std::string(reinterpret_cast<const char*>(&from), 8));
  ASSERT_NE(at, std::string::npos);
  auto forged_with = [&](const CacheSigner& signer) {
    std::string f = good;
    f.replace(at, 8, std::string(reinterpret_cast<const char*>(&to), 8));
    const std::string mac = signer.mac(kParsedStudySignature, std::string_view(f).substr(kParsedStudyHeaderBytes));
    f.replace(kParsedStudyHeaderBytes - mac.size(), mac.size(), mac);
    return f;
  };
  write_file_atomically(path, forged_with(CacheSigner::instance()));
  Opened o = open_cached(d.path());
  EXPECT_EQ(o.stats.state, "loaded");  // signed by this installation: served as stored
  EXPECT_NE(o.labels.find("0 0.9 0.2 0.05 0.04 1 line 1"), std::string::npos) << o.labels;

  write_file_atomically(path, forged_with(CacheSigner(d / "other/key")));
  o = open_cached(d.path());
  EXPECT_EQ(o.stats.state, "ignored: not signed by this installation");
  EXPECT_EQ(o.stats.files_parsed, 12);
  EXPECT_EQ(o.labels, fresh);
  o = open_cached(d.path());
  EXPECT_EQ(o.stats.state, "loaded");
  EXPECT_EQ(o.labels, fresh);  // the rebuilt file serves exactly the fresh parse
}

// With the parsed-study file in use, registrations are written once, in it, not one file each (creating
// 30,000 entry files cost more than registering again); another method's results are kept beside them.
TEST(StudyCache, RegistrationsGoInTheOneFileAndAnotherMethodsAreKept) {
  test::TempDir d;
  write_cache_study(d);
  auto cached_with = [&](RegistrationMethod m) {
    const CrossTable table =
        test::table_through_cache(d.path(), [m](TableOptions& t) { t.registration.method = m; }).table;
    EXPECT_EQ(table.registrations, 3);
    return table.cached_registrations;
  };
  EXPECT_EQ(cached_with(RegistrationMethod::kConsensus), 0);
  EXPECT_FALSE(fs::exists(registration_cache_dir(d.path())));  // no entry files
  EXPECT_EQ(cached_with(RegistrationMethod::kConsensus), 3);
  EXPECT_EQ(cached_with(RegistrationMethod::kPaper), 0);
  EXPECT_EQ(cached_with(RegistrationMethod::kConsensus), 3);  // kept while the paper method's were added
  EXPECT_EQ(cached_with(RegistrationMethod::kPaper), 3);
  EXPECT_FALSE(fs::exists(registration_cache_dir(d.path())));
}

// A registration read back from the one file keeps what its search counted and its fit's measure: a cpd answer
// stays a mixture width, a paper answer a mean distance.
TEST(StudyCache, ARegistrationReadBackKeepsItsCountsAndItsFitsMeasure) {
  test::TempDir d;
  write_cache_study(d);
  auto first_registration = [&](RegistrationMethod m, int* cached) {
    const CrossTable table =
        test::table_through_cache(d.path(), [m](TableOptions& t) { t.registration.method = m; }).table;
    *cached = table.cached_registrations;
    return table.pairings.at(0).at(0).registration;
  };
  for (auto m : {RegistrationMethod::kPaper, RegistrationMethod::kConsensus, RegistrationMethod::kCpd}) {
    SCOPED_TRACE(to_string(m));
    int cached = -1;
    const RegistrationReport cold = first_registration(m, &cached);
    EXPECT_EQ(cached, 0);
    const RegistrationReport warm = first_registration(m, &cached);
    EXPECT_EQ(cached, 3);
    ASSERT_GT(cold.hypotheses, 0);
    EXPECT_EQ(cold.fit.measure, fit_measure_of(m));
    EXPECT_EQ(warm.samples, cold.samples);
    EXPECT_EQ(warm.em_iterations, cold.em_iterations);
    EXPECT_EQ(warm.hypotheses, cold.hypotheses);
    EXPECT_EQ(warm.fit.measure, cold.fit.measure);
    EXPECT_EQ(warm.fit.value, cold.fit.value);
  }
}

TEST(StudyCache, IdenticalLayoutsReadBackAndTheWarmRunRewritesNothing) {
  // Scene s0's layouts are the same boxes on both sides: registered without a search (its own stop reason).
  // That report must read back like any other, or the whole file would be ignored on every run.
  test::TempDir d;
  write_cache_study(d);
  test::write_text(d / "synth/labels/s0.txt", read_file(d / "real/labels/s0.txt"));
  auto run = [&](bool* written) {
    const test::TableThroughCache r = test::table_through_cache(d.path());
    const CrossTable& table = r.table;
    *written = r.stats.written;
    EXPECT_EQ(table.pairings.at(0).at(0).registration.stop, StopReason::kIdenticalLayouts);
    EXPECT_FALSE(table.pairings.at(0).at(0).registration.fit.scored());  // no search, no fit: warm too
    return std::make_pair(r.stats.state, table.cached_registrations);
  };
  bool written = false;
  EXPECT_EQ(run(&written), std::make_pair(std::string("missing"), 0));
  EXPECT_TRUE(written);
  EXPECT_EQ(run(&written), std::make_pair(std::string("loaded"), 3));
  EXPECT_FALSE(written);
}

TEST(StudyCache, AChangedLabelFileIsParsedAgain) {
  test::TempDir d;
  write_cache_study(d);
  open_cached(d.path());
  // Same size, and the old modification time put back: the inode/ctime still tell.
  const std::string file = d / "real/labels/s1.txt";
  struct stat before {};
  ASSERT_EQ(::stat(file.c_str(), &before), 0);
  std::string text = read_file(file);
  text[2] = text[2] == '1' ? '2' : '1';  // "0 0.1.." -> "0 0.2.." : first rock's cx moves by 0.1
  test::write_text(file, text);
  const struct timespec times[2] = {before.st_atim, before.st_mtim};
  ASSERT_EQ(::utimensat(AT_FDCWD, file.c_str(), times, 0), 0);

  const Opened o = open_cached(d.path());
  EXPECT_EQ(o.stats.state, "loaded");
  EXPECT_EQ(o.stats.files_parsed, 1);
  EXPECT_EQ(o.stats.files_reused, 11);
  EXPECT_TRUE(o.stats.written);
  EXPECT_EQ(o.labels, dump(load_labels(open_study(d.path()))));
  EXPECT_NE(o.labels.find(fmt::format("s1.txt exists=true\n  0 {} ", text[2] == '2' ? 0.2 : 0.1)), std::string::npos);

  // A new scene and a removed one are seen too.
  test::write_text(d / "real/labels/s3.txt", "0 0.5 0.5 0.1 0.1\n");
  fs::remove(d / "synth/predictions/det/s0.txt");
  const Opened o2 = open_cached(d.path());
  EXPECT_EQ(o2.stats.files_parsed, 3);  // real/labels/s3, the removed prediction, synth/predictions of s3
  EXPECT_EQ(o2.labels, dump(load_labels(open_study(d.path()))));
}

// The label set's fingerprint is kept in the file and given back only while every GT file reads back unchanged and
// no GT file came or went; otherwise it is the files' own again.
TEST(StudyCache, TheLabelFingerprintIsReadBackOnlyWhileTheGroundTruthIsUnchanged) {
  test::TempDir d;
  write_cache_study(d);
  const std::string fresh = label_set_fingerprint(open_study(d.path()));
  EXPECT_EQ(fresh.size(), 12u);
  const Opened first = open_cached(d.path());
  EXPECT_EQ(first.fingerprint, fresh);
  const Opened again = open_cached(d.path());
  EXPECT_EQ(again.stats.files_parsed, 0);
  EXPECT_FALSE(again.stats.written);
  EXPECT_EQ(again.fingerprint, fresh);

  // A GT file's bytes change (same size, its old modification time put back).
  const std::string file = d / "real/labels/s1.txt";
  struct stat before {};
  ASSERT_EQ(::stat(file.c_str(), &before), 0);
  std::string text = read_file(file);
  text[2] = text[2] == '1' ? '2' : '1';
  test::write_text(file, text);
  const struct timespec times[2] = {before.st_atim, before.st_mtim};
  ASSERT_EQ(::utimensat(AT_FDCWD, file.c_str(), times, 0), 0);
  const Opened changed = open_cached(d.path());
  const std::string now = label_set_fingerprint(open_study(d.path()));
  EXPECT_NE(now, fresh);
  EXPECT_EQ(changed.fingerprint, now);
  EXPECT_EQ(open_cached(d.path()).fingerprint, now);  // and kept for the next run

  // A GT file goes: every other one reads back unchanged, but the set is not the one hashed.
  fs::remove(d / "synth/labels/s2.txt");
  const Opened fewer = open_cached(d.path());
  EXPECT_EQ(fewer.stats.files_parsed, 0);
  const std::string without = label_set_fingerprint(open_study(d.path()));
  EXPECT_NE(without, now);
  EXPECT_EQ(fewer.fingerprint, without);
}

TEST(StudyCache, SessionReopensFromItWithTheSameFigures) {
  test::TempDir d;
  write_cache_study(d);
  SessionOptions o;
  o.cache_dir = registration_cache_dir(d.path());
  o.study_cache_path = parsed_study_cache_path(d.path());
  const Session cold = Session::open(d.path(), o);
  EXPECT_EQ(cold.cached_registrations(), 0);
  // Registration entry files gone: the three registrations come from the one file.
  fs::remove_all(o.cache_dir);
  const Session warm = Session::open(d.path(), o);
  EXPECT_EQ(warm.study_cache_stats().state, "loaded");
  EXPECT_EQ(warm.study_cache_stats().registrations_stored, 3);
  EXPECT_EQ(warm.cached_registrations(), 3);
  EXPECT_FALSE(warm.study_cache_stats().written);
  ASSERT_EQ(warm.scenes().size(), 3u);
  for (int k = 0; k < 3; ++k) {
    EXPECT_EQ(warm.view_pairs(k), cold.view_pairs(k));
    EXPECT_EQ(warm.summary(k).ipd, cold.summary(k).ipd) << k;
  }
  EXPECT_EQ(warm.cell().pairs, cold.cell().pairs);
  EXPECT_EQ(warm.cell().ipd, cold.cell().ipd);
}

// A twin rendered from the same labels registers as 'identical layouts' (the last stop reason): the cache
// holding such registrations is loaded again, not ignored and rebuilt at every open.
TEST(StudyCache, IdenticalTwinsAreReadBackFromIt) {
  test::TempDir d;
  write_cache_study(d);
  for (int k = 0; k < 3; ++k)
    fs::copy_file(d / fmt::format("real/labels/s{}.txt", k), d / fmt::format("synth/labels/s{}.txt", k),
                  fs::copy_options::overwrite_existing);
  SessionOptions o;
  o.cache_dir = registration_cache_dir(d.path());
  o.study_cache_path = parsed_study_cache_path(d.path());
  const Session cold = Session::open(d.path(), o);
  ASSERT_EQ(cold.scenes()[0].automatic.registration.stop, StopReason::kIdenticalLayouts);
  fs::remove_all(o.cache_dir);
  const Session warm = Session::open(d.path(), o);
  EXPECT_EQ(warm.study_cache_stats().state, "loaded");
  EXPECT_EQ(warm.cached_registrations(), 3);
}

TEST(StudyCache, FirstScenesAreAPrefixOfTheStudy) {
  test::TempDir d;
  write_cache_study(d);
  test::write_text(d / "real/labels/s3.txt", "0 0.5 0.5 0.1 0.1\n");  // only in real: not a common scene
  SessionOptions o;
  o.first_scenes = 2;
  const Session first = Session::open(d.path(), o);
  const Session all = Session::open(d.path(), SessionOptions{});
  ASSERT_EQ(first.scenes().size(), 2u);
  ASSERT_EQ(all.scenes().size(), 3u);
  for (int k = 0; k < 2; ++k) {
    EXPECT_EQ(first.scenes()[k].stem, all.scenes()[k].stem);
    EXPECT_EQ(first.view_pairs(k), all.view_pairs(k));
  }
}

}  // namespace
}  // namespace ipd
