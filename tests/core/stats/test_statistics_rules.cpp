// The statistics' rules about missing data: no pairs is no measurement (NaN), never an IPD of 0.
#include <gtest/gtest.h>

#include <cmath>

#include "core/stats/statistics.h"

namespace ipd {
namespace {

TEST(StatisticsRules, NoPairsIsNoMeasurement) {
  EXPECT_TRUE(std::isnan(pooled_mean({})));
  EXPECT_TRUE(std::isnan(pooled_mean({{0, 0}, {0, 0}})));
  EXPECT_DOUBLE_EQ(pooled_mean({{0.5, 1}, {0.2, 3}}), 0.7 / 4);  // pooled over pairs, not a mean of scene means
  BootstrapOptions o;
  o.resamples = 10;
  const Interval ci = bootstrap_pooled_mean({{0, 0}, {0, 0}}, o, "det|real|synth");
  EXPECT_TRUE(std::isnan(ci.estimate));
  EXPECT_TRUE(std::isnan(ci.low));
  EXPECT_EQ(ci.resamples, 0);
}

}  // namespace
}  // namespace ipd
