// Confidence in a non-answer: whatever the method, an alignment that pairs no rock, fewer than three, rocks on
// a line, or that a rival the method scored beats, is flagged ambiguous with its reason, and a rival that fits
// better is the answer.
#include <gtest/gtest.h>

#include <fmt/format.h>
#include <cmath>
#include <nlohmann/json.hpp>
#include <random>

#include "core/registration/registration.h"
#include "core/registration/registration_cache.h"
#include "core/registration/registration_recorder.h"
#include "core/util/atomic_file.h"
#include "tests/support/test_support.h"

namespace ipd {
namespace {

using test::box;

constexpr RegistrationMethod kAll[] = {RegistrationMethod::kConsensus, RegistrationMethod::kPaper,
                                       RegistrationMethod::kCpd};

RegistrationReport registered(const std::vector<Box>& a, const std::vector<Box>& b, RegistrationMethod m,
                              std::uint64_t seed = 0) {
  RegistrationOptions o;
  o.method = m;
  o.seed = seed;
  return register_rocks(a, b, o);
}

// 28 rocks scattered at least 0.08 apart, sizes 0.02-0.05.
std::vector<Box> scattered(unsigned seed, size_t n) {
  std::mt19937 g(seed);
  auto u = [&](double lo, double hi) { return lo + (hi - lo) * (g() / 4294967296.0); };
  std::vector<Box> out;
  while (out.size() < n) {
    const Box b = box(u(0.05, 0.95), u(0.05, 0.95), u(0.02, 0.05), u(0.02, 0.05));
    bool apart = true;
    for (const auto& o : out) apart = apart && std::hypot(o.cx - b.cx, o.cy - b.cy) > 0.08;
    if (apart) out.push_back(b);
  }
  return out;
}

// One real rock against 28: a single pair fixes no alignment, any of the 28 fits as well (it read confidence
// 1.000, not ambiguous, for every method).
TEST(RegistrationAmbiguity, OneRockAgainstManyIsTooFewPairs) {
  const auto many = scattered(3, 28);
  for (auto m : kAll) {
    const auto r = registered({many[5]}, many, m);
    EXPECT_EQ(r.pairs, (RockPairs{{0, 5}})) << to_string(m);
    EXPECT_TRUE(r.ambiguous) << to_string(m);
    EXPECT_EQ(r.ambiguity, Ambiguity::kFewPairs) << to_string(m);
    EXPECT_EQ(r.confidence, 0.0) << to_string(m);
  }
  // Two rocks against the 28: two pairs fix no affine either. Many placements fit two rocks as well; consensus
  // takes the unmoved camera among them (its judgement's prior on the camera), as the others do.
  for (auto m : kAll) {
    const auto r = registered({many[5], many[9]}, many, m);
    EXPECT_EQ(r.pairs, (RockPairs{{0, 5}, {1, 9}})) << to_string(m);
    EXPECT_EQ(r.ambiguity, Ambiguity::kFewPairs) << to_string(m);
    EXPECT_EQ(r.confidence, 0.0) << to_string(m);
  }
  EXPECT_STREQ(ambiguity_reason(Ambiguity::kFewPairs),
               "fewer than 3 rocks are paired: too few to fix an alignment, another fits as well");
}

// Confidence from the answer's score and the best distinct rival's, higher is better: an answer that scores
// nothing is no better than any rival (two exact fits of the paper's, distances counted from 1e-9, read 0).
TEST(RegistrationAmbiguity, ConfidenceFromScores) {
  EXPECT_EQ(detail::confidence_from_scores(2, 1), 0.5);
  EXPECT_EQ(detail::confidence_from_scores(2, -INFINITY), 1.0);  // no rival
  EXPECT_EQ(detail::confidence_from_scores(1, 2), 0.0);          // beaten: clamped
  EXPECT_EQ(detail::confidence_from_scores(0, 0), 0.0);
  EXPECT_EQ(detail::confidence_from_scores(0, -INFINITY), 0.0);
}

// 20 rocks of zero size whose centres align exactly: every centre is an inlier, but no box overlaps another,
// so no rock is paired (consensus read confidence 0.863, cpd 0.613, not ambiguous).
TEST(RegistrationAmbiguity, AlignedCentresThatPairNothingHaveNoSupport) {
  auto rocks = scattered(3, 20);
  for (Box& b : rocks) b.w = b.h = 0;
  for (auto m : {RegistrationMethod::kConsensus, RegistrationMethod::kCpd}) {
    const auto r = registered(rocks, rocks, m);
    EXPECT_TRUE(r.pairs.empty()) << to_string(m);
    EXPECT_EQ(r.ambiguity, Ambiguity::kNoSupport) << to_string(m);
    EXPECT_TRUE(r.ambiguous) << to_string(m);
    EXPECT_EQ(r.confidence, 0.0) << to_string(m);
  }
  EXPECT_EQ(registered(rocks, rocks, RegistrationMethod::kConsensus).inliers, 20);
  EXPECT_STREQ(ambiguity_reason(Ambiguity::kNoSupport), "the alignment pairs no rock, so nothing supports it");
  EXPECT_STREQ(ambiguity_reason(Ambiguity::kNone), "");
}

// 8 rocks mirror-symmetric about x = 0.5, B the same layout shifted: the shift and the mirror both fit exactly.
// The paper's method may return either (it allows reflections); it stopped at its first exact fit and read
// confidence 1.000. Now an exact fit stops the search only once a distinct exact rival is seen: confidence 0.
TEST(RegistrationAmbiguity, PaperOnAMirrorSymmetricLayoutIsAmbiguous) {
  std::vector<Box> rocks;
  const double spots[4][2] = {{0.2, 0.2}, {0.35, 0.5}, {0.15, 0.75}, {0.4, 0.9}};
  for (int k = 0; k < 4; ++k)
    for (double x : {spots[k][0], 1 - spots[k][0]}) rocks.push_back(box(x, spots[k][1], 0.03 + 0.01 * k, 0.04));
  // B a little shifted (an identical B gets the identity without a search): the shifted identity and the
  // shifted mirror both fit exactly.
  std::vector<Box> moved = rocks;
  for (Box& b : moved) b.cx += 0.01, b.cy += 0.005;
  for (std::uint64_t seed = 0; seed < 4; ++seed) {
    const auto r = registered(rocks, moved, RegistrationMethod::kPaper, seed);
    EXPECT_EQ(r.pairs.size(), 8u) << "seed " << seed;
    EXPECT_LT(r.confidence, 1e-6) << "seed " << seed;  // 1 - 1e-9 / (1e-9 + the rival's ~1e-16)
    EXPECT_EQ(r.ambiguity, Ambiguity::kRival) << "seed " << seed;
    EXPECT_EQ(r.stop, StopReason::kCannotBeBeaten) << "seed " << seed;  // once the rival is seen
  }
  // The consensus method allows no reflection: the identity, unrivalled.
  const auto c = registered(rocks, rocks, RegistrationMethod::kConsensus);
  EXPECT_FALSE(c.ambiguous) << c.confidence;
  EXPECT_TRUE(c.affine.isApprox(identity_affine(), 1e-9)) << c.affine;
}

// 12 rocks on a line at slope 0.56, B shifted by (0.02, 0.01). cpd inverted a near-singular scatter matrix
// (its test was absolute) and returned a singular affine that paired nothing; now EM takes rigid CPD's
// similarity step on a line and finds the shift, and every method flags the line: the affine across it is a
// guess (the paper's read confidence 1.000).
TEST(RegistrationAmbiguity, CollinearRocksAreDegenerate) {
  std::vector<Box> a, b;
  for (int k = 0; k < 12; ++k) {
    const double x = 0.05 + 0.075 * k;
    a.push_back(box(x, 0.1 + 0.56 * x, 0.03, 0.03));
    b.push_back(box(x + 0.02, 0.11 + 0.56 * x, 0.03, 0.03));
  }
  for (auto m : kAll) {
    const auto r = registered(a, b, m);
    EXPECT_EQ(r.pairs.size(), 12u) << to_string(m);
    EXPECT_EQ(r.ambiguity, Ambiguity::kDegenerate) << to_string(m);
    EXPECT_EQ(r.confidence, 0.0) << to_string(m);
  }
  const auto cpd = registered(a, b, RegistrationMethod::kCpd);
  Affine2 shift = identity_affine();
  shift(0, 2) = 0.02, shift(1, 2) = 0.01;
  for (const Box& r : a) {  // along the line the similarity is exact
    const Eigen::Vector2d d = apply(cpd.affine, r.centre()) - apply(shift, r.centre());
    EXPECT_LT(d.norm(), 1e-6) << cpd.affine;
  }
  EXPECT_LT(cpd.affine.cwiseAbs().maxCoeff(), 2.0) << cpd.affine;
}

// A 7 x 7 grid and the same grid one spacing to the right. The identity already pairs 42 of 49 rocks, beyond
// chance: the consensus search stopped after that one hypothesis, and its own shifted rival (all 49) beat it,
// confidence 0. The rival is now the answer, flagged: the search's own best was beaten.
TEST(RegistrationAmbiguity, ConsensusNeverReturnsAnAlignmentItsRivalBeats) {
  std::vector<Box> a, b;
  for (int y = 0; y < 7; ++y)
    for (int x = 0; x < 7; ++x) {
      a.push_back(box(0.05 + 0.11 * x, 0.05 + 0.11 * y, 0.04, 0.04));
      b.push_back(box(0.16 + 0.11 * x, 0.05 + 0.11 * y, 0.04, 0.04));
    }
  const auto r = registered(a, b, RegistrationMethod::kConsensus);
  EXPECT_EQ(r.hypotheses, 1);
  EXPECT_EQ(r.pairs.size(), 49u);
  for (const auto& [i, j] : r.pairs) EXPECT_EQ(i, j);
  Affine2 shift = identity_affine();
  shift(0, 2) = 0.11;
  EXPECT_TRUE(r.affine.isApprox(shift, 1e-9)) << r.affine;
  EXPECT_EQ(r.ambiguity, Ambiguity::kBeaten);
  EXPECT_NEAR(r.confidence, 1.0 - 42.0 / 49.0, 1e-9);  // the identity's 42 exact rocks against 49
  EXPECT_EQ(r.note, "a shifted placement scored after the search fitted better than its best: used");
}

// The reason survives the registration cache.
TEST(RegistrationAmbiguity, TheReasonIsCached) {
  test::TempDir d;
  const RegistrationCache cache(d / "cache");
  const auto many = scattered(3, 28);
  const std::vector<Box> one{many[5]};
  bool hit = false;
  register_rocks_cached(&cache, one, many, {}, &hit);
  const auto again = register_rocks_cached(&cache, one, many, {}, &hit);
  EXPECT_TRUE(hit);
  EXPECT_EQ(again.ambiguity, Ambiguity::kFewPairs);
  EXPECT_TRUE(again.ambiguous);
  EXPECT_NE(read_file(cache.entry_path(registration_cache_key(one, many, {}))).find("\"ambiguity\":3"),
            std::string::npos);
}

// `ipd register` names the reason after the confidence, in text and JSON.
TEST(Cli, RegisterNamesWhyARegistrationIsAmbiguous) {
  test::TempDir d;
  const auto many = scattered(3, 28);
  std::string all;
  for (const Box& b : many) all += fmt::format("0 {:.4f} {:.4f} {:.4f} {:.4f}\n", b.cx, b.cy, b.w, b.h);
  test::write_text(d / "one.txt",
                   fmt::format("0 {:.4f} {:.4f} {:.4f} {:.4f}\n", many[5].cx, many[5].cy, many[5].w, many[5].h));
  test::write_text(d / "many.txt", all);
  const auto r = test::run_ipd("register " + d / "one.txt " + d / "many.txt");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("confidence 0.000; AMBIGUOUS: fewer than 3 rocks are paired: too few to fix an alignment, "
                       "another fits as well\n"),
            std::string::npos)
      << r.out;
  const auto j = nlohmann::json::parse(test::run_ipd("register " + d / "one.txt " + d / "many.txt --json").out);
  EXPECT_EQ(j["ambiguous"], true);
  EXPECT_EQ(j["ambiguity"], "fewer than 3 rocks are paired: too few to fix an alignment, another fits as well");
}

}  // namespace
}  // namespace ipd
