// Audit of a scene's pairs (residual, aligned IoU, size ratio, suspect rule) and stable pair numbers.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "core/session/audit.h"
#include "tests/support/test_support.h"

namespace ipd {
namespace {

using test::box;

// B is A moved by +0.1 in x, except: pair 1 is 1 px off in y, pair 2 is 20 px off in x, pair 3's B box is
// three times as large, pair 4 is paired with a rock far away. Image 1000 x 500: every box is 50 x 50 px.
struct Fixture {
  std::vector<Box> a{box(0.1, 0.1, 0.05, 0.1), box(0.5, 0.5, 0.05, 0.1), box(0.3, 0.7, 0.05, 0.1),
                     box(0.6, 0.2, 0.05, 0.1), box(0.8, 0.8, 0.05, 0.1)};
  std::vector<Box> b{box(0.2, 0.1, 0.05, 0.1), box(0.6, 0.502, 0.05, 0.1), box(0.42, 0.7, 0.05, 0.1),
                     box(0.7, 0.2, 0.15, 0.3), box(0.2, 0.9, 0.05, 0.1)};
  Affine2 shift;
  Fixture() { shift << 1, 0, 0.1, 0, 1, 0; }
};

TEST(Audit, ResidualIouSizeRatioAndSuspectsByHand) {
  const Fixture f;
  const SceneAudit s = audit_pairs(f.a, f.b, {{0, 0}, {1, 1}, {2, 2}, {3, 3}, {4, 4}}, f.shift, 1000, 500);
  ASSERT_EQ(s.pairs.size(), 5u);
  EXPECT_NEAR(s.pairs[0].residual_px, 0.0, 1e-9);
  EXPECT_NEAR(s.pairs[1].residual_px, 1.0, 1e-9);
  EXPECT_NEAR(s.pairs[2].residual_px, 20.0, 1e-9);
  EXPECT_NEAR(s.pairs[4].residual_px, std::hypot(700.0, 50.0), 1e-9);
  // Residuals 0, 1, 20, 0, 701.8: median 1; rock sizes 50, 50, 50, 150, 50 px: median 50.
  EXPECT_NEAR(s.typical_residual_px, 1.0, 1e-9);
  EXPECT_NEAR(s.suspect_residual_px, 12.5, 1e-9);  // max(3 x 1, 0.25 x 50)
  EXPECT_NEAR(s.pairs[1].aligned_iou, 2450.0 / 2550.0, 1e-9);
  EXPECT_NEAR(s.pairs[2].aligned_iou, 1500.0 / 3500.0, 1e-9);
  EXPECT_NEAR(s.pairs[3].aligned_iou, 2500.0 / 22500.0, 1e-9);
  EXPECT_NEAR(s.pairs[3].size_ratio, 1.0 / 3.0, 1e-9);
  EXPECT_NEAR(s.pairs[0].size_ratio, 1.0, 1e-9);
  EXPECT_FALSE(s.pairs[0].suspect);
  EXPECT_FALSE(s.pairs[1].suspect);
  EXPECT_EQ(s.pairs[2].why, "residual");
  EXPECT_EQ(s.pairs[3].why, "size");
  EXPECT_EQ(s.pairs[4].why, "residual, no overlap");
  EXPECT_EQ(s.suspects, 3);
}

// Two 10 x 10 px rocks (image 1000 x 500) 11 px apart do not overlap, but their centres are inside a noise
// floor of 0.0125 x 1000 = 12.5 px: a pairing rule with that floor pairs such a near miss, so the audit with
// the same floor does not call it "no overlap". 13 px apart they are beyond the floor and are. (The residual
// rule is held off by a large factor; the default floor is 0, as the pairing rule's.)
TEST(Audit, APairsAuditIsFoundByItsTwoRocks) {
  SceneAudit audit;
  for (const auto& [a, b] : RockPairs{{0, 2}, {3, 1}, {1, 0}}) {
    PairAudit p;
    p.a = a, p.b = b;
    audit.pairs.push_back(p);
  }
  const PairAuditIndex index(audit);
  EXPECT_EQ(index.find(1, 0), &audit.pairs[2]);
  EXPECT_EQ(index.find(3, 1), &audit.pairs[1]);
  EXPECT_EQ(index.find(0, 2), &audit.pairs[0]);
  EXPECT_EQ(index.find(1, 2), nullptr);  // rock 1's pair is (1, 0)
  EXPECT_EQ(index.find(2, 0), nullptr);  // rock 2 is unpaired
  EXPECT_EQ(index.find(7, 0), nullptr);
  EXPECT_EQ(index.find(-1, 0), nullptr);
}

TEST(Audit, ANearMissWithinTheNoiseFloorIsNotNoOverlap) {
  const std::vector<Box> a{box(0.5, 0.5, 0.01, 0.02)};
  AuditOptions o;
  o.min_residual_rock_fraction = 10;
  o.noise_floor = 0.0125;
  EXPECT_FALSE(
      audit_pairs(a, {box(0.511, 0.5, 0.01, 0.02)}, {{0, 0}}, identity_affine(), 1000, 500, o).pairs[0].suspect);
  const SceneAudit far = audit_pairs(a, {box(0.513, 0.5, 0.01, 0.02)}, {{0, 0}}, identity_affine(), 1000, 500, o);
  EXPECT_NEAR(far.pairs[0].residual_px, 13.0, 1e-9);
  EXPECT_EQ(far.pairs[0].why, "no overlap");
}

TEST(Audit, TheResidualFactorDecidesAboveTheRockFloor) {
  const Fixture f;
  AuditOptions o;
  o.min_residual_rock_fraction = 0;  // threshold = 3 x median(0, 1, 20) = 3 px
  const SceneAudit s = audit_pairs(f.a, f.b, {{0, 0}, {1, 1}, {2, 2}}, f.shift, 1000, 500, o);
  EXPECT_NEAR(s.suspect_residual_px, 3.0, 1e-9);
  EXPECT_FALSE(s.pairs[1].suspect);
  EXPECT_TRUE(s.pairs[2].suspect);
  o.residual_factor = 25;  // 25 px: nothing is far off
  EXPECT_EQ(audit_pairs(f.a, f.b, {{0, 0}, {1, 1}, {2, 2}}, f.shift, 1000, 500, o).suspects, 0);
}

TEST(Audit, BadInputIsRefused) {
  const Fixture f;
  EXPECT_THROW(audit_pairs(f.a, f.b, {{0, 5}}, f.shift, 1000, 500), std::invalid_argument);
  AuditOptions o;
  o.min_size_ratio = 1.5;
  EXPECT_EQ(o.validate(), "size ratios must satisfy 0 < min <= 1 <= max, got 1.5 and 2");
  EXPECT_THROW(audit_pairs(f.a, f.b, {}, f.shift, 1000, 500, o), std::invalid_argument);
  EXPECT_EQ(audit_pairs(f.a, f.b, {}, f.shift, 1000, 500).suspects, 0);
}

TEST(PairNumbers, AreTheLeftRockNumberAndSurviveUnpairing) {
  const RockPairs pairs{{0, 2}, {2, 0}, {4, 1}};
  EXPECT_EQ(pair_numbers(pairs, 5, true), (std::vector<int>{1, 0, 3, 0, 5}));
  EXPECT_EQ(pair_numbers(pairs, 3, false), (std::vector<int>{3, 5, 1}));
  // Unpairing pair 3 leaves 1 and 5 as they were.
  EXPECT_EQ(pair_numbers({{0, 2}, {4, 1}}, 5, true), (std::vector<int>{1, 0, 0, 0, 5}));
  EXPECT_EQ(pair_numbers({{0, 2}, {4, 1}}, 3, false), (std::vector<int>{0, 5, 1}));
}

}  // namespace
}  // namespace ipd

#include "core/session/scene_filter.h"

namespace ipd {
namespace {

SceneSummary audit_scene(const std::string& stem, double ipd, int suspects, bool edited) {
  SceneSummary s;
  s.stem = stem;
  s.ipd = ipd;
  s.suspects = suspects;
  s.edited = edited;
  return s;
}

TEST(SceneFilter, ComparisonsFlagsAndText) {
  const SceneSummary a = audit_scene("scene_01", 0.2, 1, false), b = audit_scene("scene_02", 0.05, 0, true),
                     none = audit_scene("scene_03", std::nan(""), 0, false);
  EXPECT_TRUE(SceneFilter::parse("ipd>0.1").matches(a));
  EXPECT_FALSE(SceneFilter::parse("ipd>0.1").matches(b));
  EXPECT_FALSE(SceneFilter::parse("ipd>0.1").matches(none));
  EXPECT_TRUE(SceneFilter::parse("ipd<=0.05").matches(b));
  EXPECT_FALSE(SceneFilter::parse("ipd<0.05").matches(b));
  EXPECT_TRUE(SceneFilter::parse("suspect").matches(a));
  EXPECT_FALSE(SceneFilter::parse("suspect").matches(b));
  EXPECT_TRUE(SceneFilter::parse("edited 02").matches(b));
  EXPECT_FALSE(SceneFilter::parse("edited 01").matches(b));
  EXPECT_TRUE(SceneFilter::parse("").matches(none));
  const SceneFilter bad = SceneFilter::parse("ipd>abc suspect");
  EXPECT_EQ(bad.error, "'ipd>abc': expected a number after >");
  EXPECT_EQ(bad.terms.size(), 1u);
}

}  // namespace
}  // namespace ipd
