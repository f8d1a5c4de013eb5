// The IPD check of `ipd bench registration --ipd-check`: its simulated detector and its IPD sum.
#include <gtest/gtest.h>

#include "app/bench/ipd_check.h"
#include "tests/support/test_support.h"

namespace ipd {
namespace {

using test::box;

// Perfect localisation (no error) gives every rock IoU 1; the same seed gives the same values; a 3 px error
// costs 20 px rocks more IoU than 200 px rocks on average (the detector the check simulates).
TEST(IpdCheck, TheSimulatedDetectorIsHarderOnSmallRocks) {
  const std::vector<Box> gt = {box(0.3, 0.3, 0.1, 0.1), box(0.7, 0.7, 0.2, 0.2)};
  for (double v : simulated_performance(gt, 1000, 1000, 5, 0.0, 0.0)) EXPECT_NEAR(v, 1.0, 1e-12);
  EXPECT_EQ(simulated_performance(gt, 1000, 1000, 5), simulated_performance(gt, 1000, 1000, 5));
  // 200 rocks 450 px apart in a 10,000 px picture: 20 px or 200 px wide, none overlapping another's prediction.
  std::vector<Box> small, large;
  for (int k = 0; k < 200; ++k) {
    small.push_back(box(0.05 + 0.045 * (k % 20), 0.05 + 0.045 * (k / 20), 0.002, 0.002));
    large.push_back(box(0.05 + 0.045 * (k % 20), 0.05 + 0.045 * (k / 20), 0.02, 0.02));
  }
  double small_mean = 0, large_mean = 0;
  for (double v : simulated_performance(small, 10000, 10000, 9)) small_mean += v / 200;
  for (double v : simulated_performance(large, 10000, 10000, 9)) large_mean += v / 200;
  EXPECT_LT(small_mean, large_mean - 0.1);
}

// Two cases: |0.9 - 0.5| + |0.8 - 0.8| over two pairs, then |0.2 - 0.6| over one: IPD 0.8 / 3.
TEST(IpdCheck, SumsAbsoluteDifferencesOverEveryCasesPairs) {
  IpdCheck total;
  add_to_ipd({{0, 1}, {1, 0}}, {0.9, 0.8}, {0.8, 0.5}, &total);
  add_to_ipd({{0, 0}}, {0.2}, {0.6}, &total);
  EXPECT_EQ(total.pairs, 3);
  EXPECT_NEAR(total.ipd(), 0.8 / 3, 1e-12);
}

}  // namespace
}  // namespace ipd
