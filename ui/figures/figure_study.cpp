#include "ui/figures/figure_study.h"

#include <fmt/format.h>
#include <algorithm>
#include <array>

#include "ui/figures/figure_charts.h"
#include "ui/figures/figure_gallery.h"
#include "ui/figures/figure_provenance.h"
#include "ui/figures/figure_stats.h"
#include "ui/figures/figure_table.h"

namespace ipd::ui {

bool is_study_figure_kind(const std::string& kind) {
  return kind == "table" || kind == "compare" || kind == "distribution" || kind == "breakdown" || kind == "gallery";
}

namespace {

// The model a one-model figure shows: the request's, else one trained on `domain`, else the first.
// A figure of a cell that is not a number (no predictions left on either side) would draw two empty
// prediction sets as a perfect match: refuse it, saying why, as ipd compare and ipd breakdown do.
void require_number(const TableCell* c) {
  if (c && !c->no_value_reason.empty())
    throw StudyError(
        fmt::format("model '{}': IPD({}, {}) is not a number: {}", c->model, c->a, c->b, c->no_value_reason));
}

// "Predictions with conf ≥ 0.5." after a figure's note when the predictions were cut at a threshold.
void add_threshold_note(std::string* note, const StudyFigureRequest& r) {
  if (r.conf_threshold <= 0) return;
  *note += fmt::format("{}Predictions with conf \u2265 {:g}.", note->empty() ? "" : " ", r.conf_threshold);
}

std::string pick_model(const CrossTable& t, const std::string& asked, const std::string& domain) {
  if (!asked.empty()) return asked;
  for (const auto& m : t.models)
    if (m.trained_on == domain) return m.name;
  if (t.models.empty()) throw StudyError("the study has no model predictions to draw");
  return t.models.front().name;
}

// The reference and the two renderers of a compare figure (defaults: the first three domains).
std::array<std::string, 3> compare_domains(const Study& st, const StudyFigureRequest& r) {
  if (st.domains.size() < 3 && (r.ref.empty() || r.a.empty() || r.b.empty()))
    throw StudyError(st.root + ": compare needs three domains (a reference and two renderers)");
  const std::string ref = r.ref.empty() ? st.domains[0].name : r.ref;
  std::vector<std::string> others;
  for (const auto& d : st.domains)
    if (d.name != ref) others.push_back(d.name);
  return {ref, r.a.empty() ? others.at(0) : r.a, r.b.empty() ? others.at(1) : r.b};
}

// The domain pair of a breakdown or gallery (defaults: the first domain and the next other one).
std::pair<std::string, std::string> cell_domains(const Study& st, const StudyFigureRequest& r) {
  if (st.domains.size() < 2)
    throw StudyError(fmt::format("{}: a {} needs two domains, this study has one", st.root, r.kind));
  const std::string a = r.a.empty() ? st.domains[0].name : r.a;
  const std::string b = !r.b.empty() ? r.b : st.domains[0].name == a ? st.domains[1].name : st.domains[0].name;
  return {a, b};
}

std::string draw_study_figure_body(DisplayList& fig, const CrossTable& t, const StudyLabels& labels,
                                   const StudyFigureRequest& r, const FigureOptions& o) {
  const Study& st = labels.study;
  if (st.domains.empty()) throw StudyError(st.root + ": the study has no domains");
  if (r.kind == "table") {
    TableFigure table = table_figure_of(t, o.ci, r.bootstrap.level);
    add_threshold_note(&table.note, r);
    draw_table_figure(fig, table, o);
    return "IPD cross table";
  }
  if (r.kind == "compare") {
    const auto [ref, a, b] = compare_domains(st, r);
    CompareOptions co;
    co.bootstrap = r.bootstrap;
    co.permutations = r.permutations;
    if (const std::string bad = co.validate(); !bad.empty()) throw StudyError(bad);
    for (const ModelInfo& m : t.models)
      if (r.models.empty() || std::find(r.models.begin(), r.models.end(), m.name) != r.models.end()) {
        require_number(t.cell(m.name, ref, a));
        require_number(t.cell(m.name, ref, b));
      }
    DotWhiskerChart chart = compare_chart(t, r.models, ref, a, b, co);
    add_threshold_note(&chart.footnote, r);
    draw_dot_whisker_chart(fig, chart, o);
    return fmt::format("IPD({0}, {1}) - IPD({0}, {2})", ref, a, b);
  }
  if (r.kind == "distribution") {
    const std::string model = pick_model(t, r.model, st.domains.front().name);
    for (const auto& [a, b] : t.columns) require_number(t.cell(model, a, b));
    DistributionChart chart = distribution_chart(t, model, r.worst);
    add_threshold_note(&chart.footnote, r);
    draw_distribution_chart(fig, chart, o);
    return "Per-scene IPD of " + model;
  }
  if (r.kind != "breakdown" && r.kind != "gallery") throw std::invalid_argument("not a study figure: '" + r.kind + "'");
  const auto [a, b] = cell_domains(st, r);
  // The default model is the one trained on the pair's first domain in the table's order (the left picture), so
  // `--domains hapke,real` draws and scores what `--domains real,hapke` does.
  std::string first = a;
  for (const auto& [x, y] : t.columns)
    if (includes_pair({{a, b}}, x, y)) first = x;
  const std::string model = pick_model(t, r.model, first);
  const TableCell* cell = t.cell(model, a, b);
  if (!cell) throw StudyError(fmt::format("{}: no IPD({}, {}) for model {} in this study", st.root, a, b, model));
  if (r.kind == "gallery") {
    require_number(cell);
    GalleryInput in = gallery_input(labels, *cell, r.count, r.gallery_sort, r.scene, r.rock);
    load_gallery_pictures(in, st);
    draw_gallery_figure(fig, in, o);
    return fmt::format("Rock pairs of IPD({}, {}) for {}", cell->a, cell->b, model);
  }
  BreakdownOptions bo;
  if (!parse_breakdown_by(o.by, &bo.by))
    throw std::invalid_argument("--by: expected size, region or confidence, found '" + o.by + "'");
  bo.bins = r.bins;
  bo.bootstrap = r.bootstrap;
  if (const std::string bad = bo.validate(); !bad.empty()) throw StudyError(bad);
  DotWhiskerChart chart = breakdown_chart(breakdown_cell(labels, *cell, bo), bo.bootstrap.level);
  add_threshold_note(&chart.footnote, r);
  draw_dot_whisker_chart(fig, chart, o);
  return fmt::format("IPD({}, {}) by {}", a, b, o.by);
}

}  // namespace

DomainPairFilter study_figure_domain_pairs(const Study& st, const StudyFigureRequest& r) {
  if (st.domains.empty()) return {};
  if (r.kind == "compare") {
    const auto [ref, a, b] = compare_domains(st, r);
    return {{ref, a}, {ref, b}};
  }
  if (r.kind == "breakdown" || r.kind == "gallery") return {cell_domains(st, r)};
  return {};
}

std::string draw_study_figure(DisplayList& fig, const CrossTable& t, const StudyLabels& labels,
                              const StudyFigureRequest& r, const FigureOptions& o, const Provenance* provenance) {
  const std::string title = draw_study_figure_body(fig, t, labels, r, o);
  add_provenance(fig,
                 provenance ? *provenance : table_provenance(t, labels, study_figure_domain_pairs(labels.study, r)), o);
  return title;
}

}  // namespace ipd::ui
