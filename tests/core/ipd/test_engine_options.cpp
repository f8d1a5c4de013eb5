// The table and pipeline options refuse a negative thread count (0 already means every core) by name.
#include <gtest/gtest.h>

#include <stdexcept>

#include "core/ipd/ipd.h"
#include "core/ipd/study_pipeline.h"

namespace ipd {
namespace {

TEST(EngineOptions, TableOptionsNameTheBadField) {
  TableOptions o;
  EXPECT_EQ(o.validate(), "");
  o.threads = -2;
  EXPECT_EQ(o.validate(), "threads must be >= 0 (0: hardware concurrency), got -2");
  try {
    compute_cross_table(StudyLabels{}, o);
    FAIL() << "compute_cross_table accepted -2 threads";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "table options: threads must be >= 0 (0: hardware concurrency), got -2");
  }
}

TEST(EngineOptions, PipelineOptionsNameTheBadField) {
  PipelineOptions o;
  EXPECT_EQ(o.validate(), "");
  o.threads = -1;
  EXPECT_EQ(o.validate(), "threads must be >= 0 (0: hardware concurrency), got -1");
  try {
    pair_study(StudyLabels{}, {}, o);
    FAIL() << "pair_study accepted -1 threads";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "pipeline options: threads must be >= 0 (0: hardware concurrency), got -1");
  }
}

}  // namespace
}  // namespace ipd
