// Hand-made files the study holds but no domain pair or scene reads: a pairs folder or review file named after a
// domain that was renamed, a pairs file of a scene that is gone. Left unsaid, a renamed domain's hand pairs and
// review marks would vanish from every number without a word.
#pragma once

#include <vector>

#include "core/study/problem.h"
#include "core/study/study.h"

namespace ipd {

// A file named `pairs` or `review` (not a folder: nothing in it is read), one Problem per pairs/<A>__<B> folder or
// review/<A>__<B>.json file whose A or B is not a domain of the study, and per pairs/<A>__<B>/<stem>.json whose stem is
// not a scene of both. Links are not looked into (reading refuses them); a folder that can't be listed is said too.
std::vector<Problem> unused_hand_files(const Study& study);

}  // namespace ipd
