// A cross table computed as the commands compute it: labels through the parsed-study cache, registrations through
// the registration cache handed the file's entries, then the parsed-study file saved. The cache tests run it again
// and again on one study to see what a second run reuses.
#pragma once

#include <functional>
#include <string>

#include "core/ipd/ipd.h"
#include "core/ipd/study_cache.h"
#include "core/registration/registration_cache.h"
#include "core/study/study.h"

namespace ipd::test {

struct TableThroughCache {
  CrossTable table;
  StudyCacheStats stats;    // the parsed-study cache's, after the save
  std::string fingerprint;  // the label set's, as the load left it
};

// `adjust` changes the table's options (a method, only the pairs with one domain) before it is computed.
inline TableThroughCache table_through_cache(const std::string& root,
                                             const std::function<void(TableOptions&)>& adjust = {}) {
  const Study study = open_study(root);
  StudyCache cache(parsed_study_cache_path(study.root), study.root);
  const StudyLabels labels = cache.load_labels(study);
  RegistrationCache registration(registration_cache_dir(study.root));
  cache.hand_registrations_to(registration);
  TableOptions t;
  t.registration = study.config.registration;
  t.cache_dir = registration.dir();
  t.registration_cache = &registration;
  if (adjust) adjust(t);
  TableThroughCache out{compute_cross_table(labels, t), {}, labels.label_fingerprint};
  cache.save(labels, registration);
  out.stats = cache.stats();
  return out;
}

}  // namespace ipd::test
