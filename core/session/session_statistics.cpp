#include "core/session/session_statistics.h"

namespace ipd {

bool SessionStatisticsRequest::operator==(const SessionStatisticsRequest& o) const {
  return model == o.model && pair == o.pair && ref == o.ref && a == o.a && b == o.b &&
         bootstrap.resamples == o.bootstrap.resamples && bootstrap.level == o.bootstrap.level &&
         bootstrap.seed == o.bootstrap.seed && permutations == o.permutations;
}

CrossTable session_table(const Session& s) {
  CrossTable t;
  t.models = s.study().models;
  t.columns = s.domain_pairs();
  for (const auto& m : t.models) {
    for (size_t p = 0; p < t.columns.size(); ++p) {
      TableCell c = s.cell_for(m.name, static_cast<int>(p));  // the window's cell, with its scenes for the intervals
      if (!c.missing_predictions) c.per_scene = s.contributions_for(m.name, static_cast<int>(p)).to_vector();
      t.cells.push_back(std::move(c));
    }
  }
  return t;
}

SessionStatistics compute_session_statistics(const Session& s, const SessionStatisticsRequest& r) {
  SessionStatistics out;
  out.request = r;
  out.table = session_table(s);
  add_confidence_intervals(&out.table, r.bootstrap, r.threads);
  if (r.pair >= 0 && r.pair < static_cast<int>(out.table.columns.size())) {
    const auto& [a, b] = out.table.columns[r.pair];
    if (const TableCell* cell = out.table.cell(r.model, a, b);
        cell && !cell->missing_predictions && cell->no_value_reason.empty()) {
      for (const auto& sc : cell->per_scene)
        if (sc.pairs > 0) out.scene_ipd.emplace_back(sc.stem, sc.ipd());
      BreakdownOptions bo;
      bo.bootstrap = r.bootstrap;
      out.size = breakdown_cell(s.labels(), *cell, bo);
    }
  }
  if (!r.ref.empty()) {
    try {
      CompareOptions co;
      co.bootstrap = r.bootstrap;
      co.permutations = r.permutations;
      out.comparison = compare_renderers(out.table, r.model, r.ref, r.a, r.b, co);
    } catch (const std::exception& e) {
      out.comparison_error = e.what();
    }
  }
  return out;
}

}  // namespace ipd
