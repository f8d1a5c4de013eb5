// Internal: the placements most rock pairs agree on under a given linear part, scored with the consensus
// method's support measurer. They are the rivals a small overlap allows (a patch of rocks that fits in several
// places), which a search that stopped early may never have scored; consensus and cpd judge their answers
// against them.
#pragma once

#include <Eigen/Core>

#include "core/geometry/geometry.h"
#include "core/registration/consensus/support_measurer.h"
#include "core/registration/registration_frame.h"
#include "core/registration/registration_recorder.h"

namespace ipd::detail {

// The best placement that differs from `best` (a rival) and the best that agrees with it (the same alignment,
// sometimes fitted better than the search left it: least squares cannot refine rocks on a line). Scores 0 and
// models untouched when there is none.
struct ShiftedPlacements {
  double rival = 0, same = 0;
  Affine2 rival_model = identity_affine(), same_model = identity_affine();
};

// The translations top_translations() finds under `linear`, scored. `refine`: each is first fitted to its own
// rocks, for cpd, which scores no rival of its own (the consensus search has refined its rivals already and
// scores these as they come).
ShiftedPlacements shifted_placements(SupportMeasurer* support, const SearchRecorder& recorder,
                                     const RegistrationFrame& f, const Affine2& best, const Eigen::Matrix2d& linear,
                                     double gate, bool refine);

}  // namespace ipd::detail
