#include "core/registration/consensus/shifted_placements.h"

#include "core/registration/consensus/consensus_search.h"
#include "core/registration/consensus/local_optimisers.h"

namespace ipd::detail {

ShiftedPlacements shifted_placements(SupportMeasurer* support, const SearchRecorder& recorder,
                                     const RegistrationFrame& f, const Affine2& best, const Eigen::Matrix2d& linear,
                                     double gate, bool refine) {
  ShiftedPlacements out;
  for (const auto& t : top_translations(linear, f.a, f.b, 2 * gate, 4)) {
    Affine2 m;
    m.leftCols<2>() = linear;
    m.col(2) = t;
    double s = support->score(m);
    if (refine) improve(support, &m, &s);
    const bool same = recorder.agree(m, best);
    double& kept = same ? out.same : out.rival;
    if (s > kept) kept = s, (same ? out.same_model : out.rival_model) = m;
  }
  return out;
}

}  // namespace ipd::detail
