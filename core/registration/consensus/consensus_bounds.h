// Internal: what a camera misalignment can do to the linear part of an affine, the plausibility test every
// hypothesis of the consensus registration passes before it is scored.
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <cmath>

namespace ipd::detail {

// Checked for every hypothesis, so in closed form without trigonometry: with e = (a+d)/2, f = (a-d)/2,
// g = (c+b)/2, h = (c-b)/2, the singular values are |(e,h)| +- |(f,g)| and the rotation of the closest
// similarity is the angle of (e, h).
struct Bounds {
  double min_scale, max_scale, max_rotation, max_anisotropy;
  double cos_rotation = std::cos(std::min(max_rotation, M_PI));
  // Edge directions may turn by the rotation plus what shear and anisotropic scale add (~0.5 rad).
  double cos_edge_turn = std::cos(std::min(max_rotation + 0.5, M_PI));

  bool plausible(const Eigen::Matrix2d& l) const {
    const double a = l(0, 0), b = l(0, 1), c = l(1, 0), d = l(1, 1);
    const double e = 0.5 * (a + d), f = 0.5 * (a - d), g = 0.5 * (c + b), h = 0.5 * (c - b);
    const double q = std::sqrt(e * e + h * h), r = std::sqrt(f * f + g * g);
    return q > r && q - r >= min_scale && q + r <= max_scale && e >= q * cos_rotation &&
           q + r <= max_anisotropy * (q - r);
  }
};

}  // namespace ipd::detail
