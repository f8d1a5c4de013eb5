#include "core/session/session_ranking.h"

#include <algorithm>

#include "core/session/session_statistics.h"

namespace ipd {

bool SessionRankRequest::operator==(const SessionRankRequest& o) const {
  return model == o.model && ref == o.ref && bootstrap.resamples == o.bootstrap.resamples &&
         bootstrap.level == o.bootstrap.level && bootstrap.seed == o.bootstrap.seed && permutations == o.permutations &&
         level == o.level;
}

CrossTable session_rank_table(const Session& session, const std::string& model, const std::string& ref,
                              const BootstrapOptions& bootstrap) {
  CrossTable t = session_table(session);
  // Only the cells a ranking reads: a candidate-vs-candidate cell's interval would be work for nothing.
  t.cells.erase(std::remove_if(t.cells.begin(), t.cells.end(),
                               [&](const TableCell& c) { return c.model != model || (c.a != ref && c.b != ref); }),
                t.cells.end());
  add_confidence_intervals(&t, bootstrap, 1);
  return t;
}

SessionRanking compute_session_ranking(const Session& session, const SessionRankRequest& request) {
  SessionRanking out;
  out.request = request;
  if (request.model.empty()) {
    out.error = "no model: a ranking needs predictions";
    return out;
  }
  try {
    RankOptions ro;
    ro.model = request.model;
    ro.domains = resolve_rank_domains(session.study(), request.ref, {});
    ro.compare.bootstrap = request.bootstrap;
    ro.compare.permutations = request.permutations;
    ro.level = request.level;
    out.ranking = rank_candidates(session.labels(),
                                  session_rank_table(session, request.model, request.ref, request.bootstrap), ro);
  } catch (const std::exception& e) {
    out.error = e.what();
  }
  return out;
}

}  // namespace ipd
