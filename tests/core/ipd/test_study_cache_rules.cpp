// The parsed-study cache keeps files as filtered by the study's rock class and confidence threshold: under
// another threshold the predictions are parsed again, never served as filtered before.
#include <gtest/gtest.h>

#include "core/ipd/study_cache.h"
#include "core/registration/registration_cache.h"
#include "tests/support/test_support.h"

namespace ipd {
namespace {

StudyLabels open_cached_for_rules(const std::string& root, StudyCacheStats* stats) {
  const Study study = open_study(root);
  StudyCache cache(parsed_study_cache_path(root), study.root);
  StudyLabels labels = cache.load_labels(study);
  RegistrationCache registration("");
  registration.preload(cache.take_registrations());
  cache.save(labels, registration);
  *stats = cache.stats();
  return labels;
}

// Two predictions, confidence 0.9 and 0.4: a threshold of 0.5 keeps one. Raising it in study.yaml after a
// first open must not serve the two the cache holds.
TEST(StudyCacheRules, AnotherConfidenceThresholdParsesPredictionsAgain) {
  test::TempDir d;
  test::write_text(d / "real/labels/s1.txt", "0 0.2 0.2 0.1 0.1\n0 0.6 0.6 0.1 0.1\n");
  test::write_text(d / "synth/labels/s1.txt", "0 0.6 0.6 0.1 0.1\n0 0.2 0.2 0.1 0.1\n");
  test::write_text(d / "real/predictions/det/s1.txt", "0 0.2 0.2 0.1 0.1 0.9\n0 0.65 0.6 0.1 0.1 0.4\n");
  test::write_text(d / "synth/predictions/det/s1.txt", "0 0.25 0.2 0.1 0.1 0.8\n");
  StudyCacheStats stats;
  EXPECT_EQ(open_cached_for_rules(d.path(), &stats).predictions_of("real", "det", "s1").boxes.size(), 2u);
  EXPECT_EQ(open_cached_for_rules(d.path(), &stats).predictions_of("real", "det", "s1").boxes.size(), 2u);
  EXPECT_EQ(stats.files_parsed, 0);  // all reused
  test::write_text(d / "study.yaml", "conf_threshold: 0.5\n");
  EXPECT_EQ(open_cached_for_rules(d.path(), &stats).predictions_of("real", "det", "s1").boxes.size(), 1u);
  EXPECT_EQ(stats.files_parsed, 4);
}

}  // namespace
}  // namespace ipd
