// The pieces behind small overlaps: the least-squares similarity (flat triples and rock pairs propose it), the
// judgement of a candidate alignment on the pairing it produces, and the second look's edge search.
#include <gtest/gtest.h>

#include <cmath>

#include "core/geometry/affine_estimator.h"
#include "core/registration/consensus/consensus_second_look.h"  // core/src: internal
#include "core/registration/registration_frame.h"
#include "tests/support/test_support.h"

namespace ipd {
namespace {

using test::box;

TEST(SimilarityLeastSquares, RecoversRotationScaleAndShiftFromTwoOrMorePoints) {
  // 1.2 x rotation by 30 degrees, then (0.5, -0.25): [c -s; s c] with c = 1.2 cos 30, s = 1.2 sin 30.
  const double c = 1.2 * std::cos(M_PI / 6), s = 1.2 * std::sin(M_PI / 6);
  auto map = [&](const Eigen::Vector2d& p) {
    return Eigen::Vector2d(c * p.x() - s * p.y() + 0.5, s * p.x() + c * p.y() - 0.25);
  };
  const Eigen::Vector2d src[4] = {{0, 0}, {1, 0}, {0.5, 0.5}, {2, 1}};
  Eigen::Vector2d dst[4];
  for (int k = 0; k < 4; ++k) dst[k] = map(src[k]);
  for (size_t n : {2, 4}) {
    Affine2 m;
    ASSERT_TRUE(similarity_least_squares(src, dst, n, &m));
    EXPECT_NEAR(m(0, 0), c, 1e-12);
    EXPECT_NEAR(m(0, 1), -s, 1e-12);
    EXPECT_NEAR(m(1, 0), s, 1e-12);
    EXPECT_NEAR(m(1, 1), c, 1e-12);
    EXPECT_NEAR(m(0, 2), 0.5, 1e-12);
    EXPECT_NEAR(m(1, 2), -0.25, 1e-12);
  }
  // Collinear points still determine it (an affine would not be); one point, or two equal ones, do not.
  const Eigen::Vector2d line[3] = {{0, 0}, {1, 1}, {3, 3}};
  const Eigen::Vector2d line_dst[3] = {map(line[0]), map(line[1]), map(line[2])};
  Affine2 m;
  ASSERT_TRUE(similarity_least_squares(line, line_dst, 3, &m));
  EXPECT_NEAR(m(1, 0), s, 1e-12);
  EXPECT_FALSE(similarity_least_squares(src, dst, 1, &m));
  const Eigen::Vector2d same[2] = {{0.3, 0.3}, {0.3, 0.3}};
  EXPECT_FALSE(similarity_least_squares(same, dst, 2, &m));
  // Two points always fit exactly: (-1,0), (1,0) onto (0,-1), (0,1) is a quarter turn.
  const Eigen::Vector2d turn_src[2] = {{-1, 0}, {1, 0}}, turn_dst[2] = {{0, -1}, {0, 1}};
  ASSERT_TRUE(similarity_least_squares(turn_src, turn_dst, 2, &m));
  EXPECT_NEAR(m(1, 0), 1.0, 1e-12);
  EXPECT_NEAR(m(0, 0), 0.0, 1e-12);
}

// Hand-computed judgement. A: three 0.1 x 0.1 boxes; B: two. Under the identity A0 meets B0 exactly (IoU 1),
// A1 overlaps B1 shifted by half a width (IoU 0.05 / 0.15 = 1/3), A2 lies wholly inside B's picture with no
// partner (one unpaired A rock). Shifted 0.6 to the right, nothing pairs: only A0 (now at x = 0.8) lands wholly
// inside B's picture, unpaired; B's boxes map back to x = -0.4 and -0.05, outside A's picture.
TEST(SecondLook, JudgesACandidateOnThePairingItProduces) {
  const std::vector<Box> a = {box(0.2, 0.2, 0.1, 0.1), box(0.5, 0.2, 0.1, 0.1), box(0.5, 0.7, 0.1, 0.1)};
  const std::vector<Box> b = {box(0.2, 0.2, 0.1, 0.1), box(0.55, 0.2, 0.1, 0.1)};
  const detail::RegistrationFrame f(a, b, 1.0);
  const auto j = detail::judge_candidate(f, a, b, f.from_image(identity_affine()), 2.0, PairingRule());
  EXPECT_NEAR(j.iou_sum, 1.0 + 1.0 / 3.0, 1e-9);
  EXPECT_EQ(j.unpaired_a, 1);
  EXPECT_EQ(j.unpaired_b, 0);
  EXPECT_NEAR(j.total, 2.0 + 0.2 * (4.0 / 3.0) - 0.1 * 1, 1e-9);

  Affine2 shift = identity_affine();
  shift(0, 2) = 0.6;
  const auto k = detail::judge_candidate(f, a, b, f.from_image(shift), 0.0, PairingRule());
  EXPECT_EQ(k.iou_sum, 0.0);
  EXPECT_EQ(k.unpaired_a, 1);
  EXPECT_EQ(k.unpaired_b, 0);
  EXPECT_NEAR(k.total, -0.1, 1e-12);
}

// The prior on the camera, by hand: 2.5 per unit of |log scale| and 1 per radian. Twice the size turned by 0.5 rad
// costs 2.5 ln 2 + 0.5; half the size turned the other way costs the same; the unmoved camera and a pure shift
// cost nothing.
TEST(SecondLook, MisalignmentCostIsTheCamerasScaleAndRotation) {
  auto similarity = [](double scale, double turn, double dx) {
    Affine2 m;
    m << scale * std::cos(turn), -scale * std::sin(turn), dx, scale * std::sin(turn), scale * std::cos(turn), 0;
    return m;
  };
  EXPECT_EQ(detail::misalignment_cost(identity_affine()), 0.0);
  EXPECT_EQ(detail::misalignment_cost(similarity(1, 0, 0.3)), 0.0);
  EXPECT_NEAR(detail::misalignment_cost(similarity(2, 0.5, 0)), 2.5 * std::log(2.0) + 0.5, 1e-12);
  EXPECT_NEAR(detail::misalignment_cost(similarity(0.5, -0.5, 0)), 2.5 * std::log(2.0) + 0.5, 1e-12);
  // An anisotropic scale counts by its area: 2 x 0.5 keeps the area, so only its rotation costs.
  Affine2 stretch;
  stretch << 2, 0, 0, 0, 0.5, 0;
  EXPECT_NEAR(detail::misalignment_cost(stretch), 0.0, 1e-12);
  // The judgement subtracts it. A's rock, twice the size, lands at (0.4, 0.4) and B's maps back to (0.45, 0.45):
  // each wholly inside the other picture, unpaired (0.1 and 0.05).
  const std::vector<Box> a = {box(0.2, 0.2, 0.1, 0.1)}, b = {box(0.9, 0.9, 0.1, 0.1)};
  const detail::RegistrationFrame f(a, b, 1.0);
  Affine2 grown = identity_affine();
  grown(0, 0) = grown(1, 1) = 2;
  const auto j = detail::judge_candidate(f, a, b, f.from_image(grown), 1.0, PairingRule());
  EXPECT_EQ(j.unpaired_a, 1);
  EXPECT_EQ(j.unpaired_b, 1);
  EXPECT_NEAR(j.total, 1.0 - 0.1 - 0.05 - 2.5 * std::log(2.0), 1e-9);
}

// Three rocks on B; A holds the same triangle twice about the picture's centre: once at 1/1.05 of the size (boxes too)
// and once at 1/1.65. The camera 1.05 times closer and the one 1.65 times closer each fit three rocks exactly, with the
// same IoU, sizes and unpaired rocks: nothing in the rocks decides. The prior on the camera does: whichever triangle A
// lists first, the smaller misalignment (1.05) pairs. Without it the search keeps the 1.65 camera when A lists the 1.05
// triangle first.
TEST(SecondLook, AnExactTieGoesToTheSmallerMisalignment) {
  const std::vector<Box> b = {box(0.30, 0.30, 0.06, 0.05), box(0.70, 0.35, 0.05, 0.07), box(0.45, 0.75, 0.07, 0.06)};
  auto triangle = [&](double scale, double cx, double cy) {  // B's triangle shrunk by `scale` about (cx, cy)
    std::vector<Box> out;
    for (const Box& x : b) {
      Box y = x;
      y.cx = cx + (x.cx - cx) / scale, y.cy = cy + (x.cy - cy) / scale, y.w = x.w / scale, y.h = x.h / scale;
      out.push_back(y);
    }
    return out;
  };
  const auto near = triangle(1.05, 0.5, 0.5), far = triangle(1.65, 0.5, 0.5);
  for (bool near_first : {true, false}) {
    std::vector<Box> a = near_first ? near : far;
    const auto& second = near_first ? far : near;
    a.insert(a.end(), second.begin(), second.end());
    const int first = near_first ? 0 : 3;
    const RegistrationReport r = register_rocks(a, b, RegistrationOptions());
    EXPECT_EQ(r.pairs, (RockPairs{{first, 0}, {first + 1, 1}, {first + 2, 2}})) << near_first;
    EXPECT_NEAR(r.affine(0, 0), 1.05, 1e-6) << near_first;
  }
}

}  // namespace
}  // namespace ipd
