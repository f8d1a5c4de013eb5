#include "stats_panels.h"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <imgui.h>

namespace ipd::ui {

namespace {

std::string interval(double v, double lo, double hi) {
  if (std::isnan(v)) return "n/a";
  if (std::isnan(lo) || std::isnan(hi)) return fmt::format("{:.4f}", v);
  return fmt::format("{:.4f} [{:.3f}, {:.3f}]", v, lo, hi);
}

// 1, 2 or 5 times a power of ten, at least x.
double round_step(double x) {
  if (!(x > 0)) return 1;
  const double p = std::pow(10.0, std::floor(std::log10(x)));
  for (double m : {1.0, 2.0, 5.0, 10.0})
    if (m * p >= x * (1 - 1e-12)) return m * p;
  return 10 * p;
}

const ImU32 kBar = IM_COL32(110, 160, 230, 255), kBarHot = IM_COL32(150, 200, 255, 255);
const ImU32 kCurrent = IM_COL32(255, 215, 80, 255), kWhisker = IM_COL32(230, 230, 230, 255);

}  // namespace

SessionStatisticsRequest stats_request(const Session& s, const StatsPanelState& st) {
  SessionStatisticsRequest r;
  r.model = s.model();
  r.pair = s.pair_index();
  r.bootstrap.seed = s.study().config.registration.seed;  // as `ipd table` without --seed
  const auto& d = s.study().domains;
  const int n = static_cast<int>(d.size());
  if (n >= 3 && st.ref < n && st.a < n && st.b < n && st.ref != st.a && st.ref != st.b && st.a != st.b) {
    r.ref = d[st.ref].name;
    r.a = d[st.a].name;
    r.b = d[st.b].name;
  }
  return r;
}

HistogramBins histogram_bins(const std::vector<double>& values, int bins) {
  HistogramBins h;
  if (values.empty() || bins < 1) return h;
  const double lo = *std::min_element(values.begin(), values.end());
  const double hi = *std::max_element(values.begin(), values.end());
  h.width = round_step(std::max(hi, 1e-9) / bins);
  h.start = std::floor(lo / h.width) * h.width;
  const int n = std::max(1, static_cast<int>(std::floor((hi - h.start) / h.width)) + 1);
  h.counts.assign(n, 0);
  for (double v : values) h.counts[std::clamp(static_cast<int>(std::floor((v - h.start) / h.width)), 0, n - 1)]++;
  return h;
}

void cell_interval_tooltip(const SessionStatistics* stats, const std::string& model, int pair) {
  if (!stats || !ImGui::IsItemHovered() || pair < 0 || pair >= static_cast<int>(stats->table.columns.size())) return;
  const auto& [a, b] = stats->table.columns[pair];
  const TableCell* c = stats->table.cell(model, a, b);
  if (!c || std::isnan(c->ipd)) return;
  ImGui::BeginTooltip();
  ImGui::Text("IPD(%s, %s) for %s", a.c_str(), b.c_str(), model.c_str());
  ImGui::Text("%s", interval(c->ipd, c->ci_low, c->ci_high).c_str());
  ImGui::TextDisabled("%g%% scene-bootstrap interval, %d resamples; se %.4f", 100 * stats->request.bootstrap.level,
                      stats->request.bootstrap.resamples, c->se);
  ImGui::TextDisabled("%ld pairs in %d scenes", c->pairs, c->scenes);
  ImGui::EndTooltip();
}

namespace {

void draw_compare(const StudyView& v, const SessionStatistics* stats, StatsPanelState& st) {
  const auto& domains = v.session->study().domains;
  if (domains.size() < 3) return;
  ImGui::TextUnformatted("Which renderer is closer?");
  auto combo = [&](const char* label, int* index) {
    ImGui::SetNextItemWidth(110);
    if (ImGui::BeginCombo(label, domains[std::min<size_t>(*index, domains.size() - 1)].name.c_str())) {
      for (size_t k = 0; k < domains.size(); ++k)
        if (ImGui::Selectable(domains[k].name.c_str(), static_cast<int>(k) == *index)) *index = static_cast<int>(k);
      ImGui::EndCombo();
    }
  };
  combo("ref##cmp", &st.ref);
  ImGui::SameLine();
  combo("a##cmp", &st.a);
  combo("b##cmp", &st.b);
  if (st.ref == st.a || st.ref == st.b || st.a == st.b) {
    ImGui::TextDisabled("pick three different domains");
    return;
  }
  if (!stats || !stats->comparison) {
    if (stats && !stats->comparison_error.empty()) ImGui::TextWrapped("%s", stats->comparison_error.c_str());
    return;
  }
  const RendererComparison& c = *stats->comparison;
  const Comparison& r = c.result;
  ImGui::Text("IPD(%s,%s) %.4f  IPD(%s,%s) %.4f", c.ref.c_str(), c.a.c_str(), r.ipd_a, c.ref.c_str(), c.b.c_str(), r.ipd_b);
  ImGui::Text("delta %s   p = %.2g", interval(r.delta.estimate, r.delta.low, r.delta.high).c_str(), r.p_value);
  // The GUI font has no Δ or typographic minus: spell them in ASCII.
  std::string sentence = comparison_sentence(c);
  for (const auto& [from, to] : {std::pair<std::string, std::string>{"ΔIPD", "delta IPD"}, {"−", "-"}})
    for (size_t at; (at = sentence.find(from)) != std::string::npos;) sentence.replace(at, from.size(), to);
  ImGui::PushTextWrapPos(0);
  ImGui::TextUnformatted(sentence.c_str());
  ImGui::PopTextWrapPos();
}

void draw_histogram(const StudyView& v, const SessionStatistics* stats, StatsPanelState& st, UiState& ui) {
  ImGui::Text("Per-scene IPD, %s (click a bar: those scenes)", v.session->model().c_str());
  if (!stats || stats->scene_ipd.empty()) {
    ImGui::TextDisabled("no scene with pairs");
    return;
  }
  std::vector<double> values;
  for (const auto& [stem, val] : stats->scene_ipd) values.push_back(val);
  const HistogramBins h = histogram_bins(values, st.bins);
  const int top = *std::max_element(h.counts.begin(), h.counts.end());
  const float height = 70, full = ImGui::GetContentRegionAvail().x;
  const float bar_w = std::max(4.0f, full / static_cast<float>(h.counts.size()) - 2);
  // The current scene's bar is outlined.
  double current = std::nan("");
  if (!v.session->scenes().empty() && ui.scene < static_cast<int>(v.summaries->size())) current = (*v.summaries)[ui.scene].ipd;
  ImDrawList* dl = ImGui::GetWindowDrawList();
  for (size_t k = 0; k < h.counts.size(); ++k) {
    if (k) ImGui::SameLine(0, 2);
    const ImVec2 p0 = ImGui::GetCursorScreenPos();
    ImGui::PushID(static_cast<int>(k));
    const bool clicked = ImGui::InvisibleButton("bar", {bar_w, height});
    ImGui::PopID();
    const bool hot = ImGui::IsItemHovered();
    const float bh = top > 0 ? height * h.counts[k] / top : 0;
    dl->AddRectFilled({p0.x, p0.y + height - bh}, {p0.x + bar_w, p0.y + height}, hot ? kBarHot : kBar);
    const double lo = h.start + k * h.width, hi = lo + h.width;
    if (current >= lo && (current < hi || (k + 1 == h.counts.size() && current <= hi)))
      dl->AddRect(p0, {p0.x + bar_w, p0.y + height}, kCurrent, 0, 0, 2);
    const bool last = k + 1 == h.counts.size();
    const std::string filter = fmt::format("ipd>={:g} ipd{}{:g}", lo, last ? "<=" : "<", hi);
    if (hot) ImGui::SetTooltip("%d scene(s) with IPD in [%g, %g%s\nclick: show them in the scene list", h.counts[k],
                               lo, hi, last ? "]" : ")");
    if (clicked && filter.size() < sizeof ui.filter) std::snprintf(ui.filter, sizeof ui.filter, "%s", filter.c_str());
  }
  ImGui::TextDisabled("%g .. %g, %zu scenes", h.start, h.start + h.width * h.counts.size(), values.size());
}

void draw_size_breakdown(const SessionStatistics* stats) {
  if (!stats || !stats->size) return;
  const CellBreakdown& b = *stats->size;
  ImGui::Text("IPD by %s rock size (px²)", b.a.c_str());
  double top = 0;
  for (const auto& bin : b.bins)
    top = std::max({top, std::isnan(bin.ipd.high) ? 0.0 : bin.ipd.high, std::isnan(bin.ipd.estimate) ? 0.0 : bin.ipd.estimate});
  if (top <= 0) top = 1;
  ImDrawList* dl = ImGui::GetWindowDrawList();
  const float label_w = 120, width = std::max(40.0f, ImGui::GetContentRegionAvail().x - label_w - 8);
  const float row = ImGui::GetTextLineHeight();
  for (const auto& bin : b.bins) {
    ImGui::TextUnformatted(bin.label.c_str());
    ImGui::SameLine(label_w);
    const ImVec2 p0 = ImGui::GetCursorScreenPos();
    ImGui::Dummy({width, row});
    if (ImGui::IsItemHovered())
      ImGui::SetTooltip("%s: IPD %s\n%ld pairs in %d scenes", bin.label.c_str(),
                        interval(bin.ipd.estimate, bin.ipd.low, bin.ipd.high).c_str(), bin.pairs, bin.scenes);
    if (std::isnan(bin.ipd.estimate)) continue;
    auto x = [&](double val) { return p0.x + static_cast<float>(val / top) * width; };
    dl->AddRectFilled({p0.x, p0.y + 2}, {x(bin.ipd.estimate), p0.y + row - 2}, kBar);
    if (bin.ipd.has_interval()) {
      const float ym = p0.y + row * 0.5f;
      dl->AddLine({x(bin.ipd.low), ym}, {x(bin.ipd.high), ym}, kWhisker, 1.5f);
      dl->AddLine({x(bin.ipd.low), ym - 3}, {x(bin.ipd.low), ym + 3}, kWhisker, 1.5f);
      dl->AddLine({x(bin.ipd.high), ym - 3}, {x(bin.ipd.high), ym + 3}, kWhisker, 1.5f);
    }
  }
}

}  // namespace

void draw_stats_panels(const StudyView& v, const SessionStatistics* stats, bool computing, StatsPanelState& st,
                       UiState& ui, UiCommands& /*out*/) {
  if (!v.session) return;
  ImGui::Separator();
  if (stats) {
    const auto& [a, b] = v.session->domain_pairs()[v.session->pair_index()];
    const TableCell* c = stats->table.cell(v.session->model(), a, b);
    if (c) ImGui::Text("IPD %s", interval(c->ipd, c->ci_low, c->ci_high).c_str());
    ImGui::SameLine();
    ImGui::TextDisabled("%g%% CI%s", 100 * stats->request.bootstrap.level, computing ? ", updating..." : "");
  } else {
    ImGui::TextDisabled("computing intervals...");
  }
  ImGui::Separator();
  draw_histogram(v, stats, st, ui);
  ImGui::Separator();
  draw_size_breakdown(stats);
  ImGui::Separator();
  draw_compare(v, stats, st);
}

}  // namespace ipd::ui
