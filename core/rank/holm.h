// Holm's step-down correction of p-values for testing several hypotheses at once (Holm 1979): a ranking tests
// every candidate against the best, and with a dozen candidates one of them would look "different" by chance
// at the uncorrected level about half the time. Holm keeps the family-wise error at the level chosen and is
// never less powerful than Bonferroni.
#pragma once

#include <vector>

namespace ipd {

// The Holm-adjusted p-values, in the order given: with the m p-values that are numbers sorted ascending,
// p_(i) adjusted = max over j <= i of min(1, (m - j + 1) p_(j)). NaN (a test that was not run) stays NaN and
// does not count in m. Equal p-values keep their input order (the adjustment is the same either way).
std::vector<double> holm_adjusted(const std::vector<double>& p);

}  // namespace ipd
