#include "ui/gui/rank_view.h"

#include <fmt/format.h>
#include <algorithm>
#include <cmath>

#include "core/stats/study_statistics.h"
#include "ui/figures/figure_charts.h"
#include "ui/figures/figure_sweep.h"
#include "ui/gui/studio_layout.h"

namespace ipd::ui {

namespace {

// With the typographic minus, as ipd rank and the compare panel write it.
std::string interval_text(double low, double high) {
  if (std::isnan(low) || std::isnan(high)) return "";
  return fmt::format(" [{}, {}]", minus_number(low, 3), minus_number(high, 3));
}

std::string params_text(const std::vector<std::pair<std::string, double>>& params) {
  std::string out;
  for (const auto& [name, value] : params) out += fmt::format("{}{}={:g}", out.empty() ? "" : " ", name, value);
  return out;
}

// The plot of the IPD along the one varying parameter: interval bars, the points (the best a larger ring, the
// group filled), a click selects a setting.
void draw_sweep(const Session& s, const SweepChart& chart, const std::string& ref, UiCommands& out) {
  const float h = std::max(120.0f, 9 * ImGui::GetTextLineHeight());
  const ImVec2 p0 = ImGui::GetCursorScreenPos();
  const float w = std::max(200.0f, ImGui::GetContentRegionAvail().x);
  ImGui::InvisibleButton("##sweep", {w, h});
  const bool hovered = ImGui::IsItemHovered();
  ImDrawList* dl = ImGui::GetWindowDrawList();
  const float line = ImGui::GetTextLineHeight();
  const float left = p0.x + ImGui::CalcTextSize("0.000").x + 10, right = p0.x + w - 12;
  const float top = p0.y + 6, bottom = p0.y + h - 2 * line - 4;
  double x0 = chart.points.front().x, x1 = chart.points.back().x, y0 = 0, y1 = 0;
  for (const SweepPoint& p : chart.points) y1 = std::max({y1, p.ipd, std::isnan(p.high) ? p.ipd : p.high});
  if (x1 <= x0) x1 = x0 + 1;
  if (y1 <= 0) y1 = 1;
  // Round ticks, as the sweep figure has them: the IPD axis ends on its last tick, the points between the ends
  // of the parameter axis are read against its own.
  const std::vector<double> y_ticks = nice_ticks(0, y1, 4), x_ticks = nice_ticks(x0, x1, 5);
  if (!y_ticks.empty()) y1 = std::max(y1, y_ticks.back());
  auto sx = [&](double x) { return left + float((x - x0) / (x1 - x0)) * (right - left); };
  auto sy = [&](double y) { return bottom - float((y - y0) / (y1 - y0)) * (bottom - top); };
  const ImU32 axis = IM_COL32(160, 160, 170, 255), text = IM_COL32(220, 220, 220, 255);
  dl->AddLine({left, top}, {left, bottom}, axis);
  dl->AddLine({left, bottom}, {right, bottom}, axis);
  const double y_step = y_ticks.size() > 1 ? y_ticks[1] - y_ticks[0] : y1;
  for (double y : y_ticks) {
    const std::string t = tick_text(y, y_step);
    dl->AddLine({left - 3, sy(y)}, {left, sy(y)}, axis);
    dl->AddText({p0.x, sy(y) - 0.5f * line}, text, t.c_str());
  }
  const double x_step = x_ticks.size() > 1 ? x_ticks[1] - x_ticks[0] : x1 - x0;
  for (double x : x_ticks) {
    if (x < x0 - 1e-9 * (x1 - x0) || x > x1 + 1e-9 * (x1 - x0)) continue;  // the axis spans the settings only
    const std::string t = tick_text(x, x_step);
    dl->AddLine({sx(x), bottom}, {sx(x), bottom + 3}, axis);
    dl->AddText({std::clamp(sx(x) - 0.5f * ImGui::CalcTextSize(t.c_str()).x, p0.x, right - 20), bottom + 2}, text,
                t.c_str());
  }
  const std::string label = chart.parameters.front() + "  (IPD, lower is closer to " + ref + ")";
  dl->AddText({left + 0.5f * (right - left - ImGui::CalcTextSize(label.c_str()).x), bottom + 2 + line}, text,
              label.c_str());
  const ImVec2 mouse = ImGui::GetIO().MousePos;
  int nearest = -1;
  float nearest_d = 10;
  for (size_t k = 0; k < chart.points.size(); ++k) {
    const SweepPoint& p = chart.points[k];
    const ImVec2 c{sx(p.x), sy(p.ipd)};
    if (!std::isnan(p.low) && !std::isnan(p.high)) dl->AddLine({c.x, sy(p.low)}, {c.x, sy(p.high)}, axis, 1.5f);
    if (k > 0) {
      const SweepPoint& q = chart.points[k - 1];
      dl->AddLine({sx(q.x), sy(q.ipd)}, c, IM_COL32(120, 170, 255, 200), 1.5f);
    }
    const bool current = p.domain == s.right_domain();
    const ImU32 colour = current ? kSelected : IM_COL32(120, 170, 255, 255);
    if (p.in_group)
      dl->AddCircleFilled(c, 4.5f, colour);
    else
      dl->AddCircle(c, 4.5f, colour, 0, 1.5f);
    if (p.best) dl->AddCircle(c, 8.0f, kHighlight, 0, 2.0f);
    const float d = std::hypot(mouse.x - c.x, mouse.y - c.y);
    if (d < nearest_d) nearest_d = d, nearest = static_cast<int>(k);
  }
  if (hovered && nearest >= 0) {
    const SweepPoint& p = chart.points[nearest];
    ImGui::SetTooltip("%s: %s = %g, IPD %s%s%s (click: show it on the right)", p.domain.c_str(),
                      chart.parameters.front().c_str(), p.x, fmt_ipd(p.ipd).c_str(),
                      interval_text(p.low, p.high).c_str(),
                      p.best       ? ", the best"
                      : p.in_group ? ", not distinguishable from the best"
                                   : "");
    if (ImGui::IsMouseClicked(ImGuiMouseButton_Left)) choose_ranked_domain(s, p.domain, out);
  }
}

}  // namespace

SessionRankRequest rank_request(const Session& s) {
  SessionRankRequest r;
  r.model = s.model();
  r.ref = s.left_domain();
  return r;
}

void choose_ranked_domain(const Session& s, const std::string& domain, UiCommands& out) {
  if (domain == s.left_domain()) return;
  out.left_domain = s.left_domain();
  out.right_domain = domain;
}

std::vector<std::string> rank_row_cells(const RankedCandidate& r) {
  std::string vs_best, p;
  if (r.vs_best) {
    const Comparison& c = r.vs_best->result;
    const double delta = c.ipd_a - c.ipd_b;
    vs_best = (delta > 0 ? "+" : "") + minus_number(delta, 4) + interval_text(c.delta.low, c.delta.high);
    p = std::isnan(r.p_holm) ? "n/a" : fmt::format("{:.4f}", r.p_holm);
  }
  return {std::to_string(r.rank),
          r.domain,
          params_text(r.params),
          fmt_ipd(r.ipd) + interval_text(r.ci_low, r.ci_high),
          thousands(r.pairs),
          vs_best,
          p,
          r.rank == 1       ? "best"
          : r.in_best_group ? "\u2248 best"
                            : ""};
}

void draw_rank_window(const StudyView& v, const SessionRanking* result, bool current, UiState& ui, UiCommands& out) {
  if (!ui.show_rank || !v.session) return;
  const ImVec2 display = ImGui::GetIO().DisplaySize;
  ImGui::SetNextWindowSize({std::min(display.x * 0.9f, 760.0f), std::min(display.y * 0.8f, 560.0f)},
                           ImGuiCond_FirstUseEver);
  ImGui::SetNextWindowPos({display.x * 0.5f, display.y * 0.5f}, ImGuiCond_FirstUseEver, {0.5f, 0.5f});
  if (!ImGui::Begin("Rank renderer settings###Rank", &ui.show_rank)) {
    ImGui::End();
    return;
  }
  const Session& s = *v.session;
  text_wrapped_at_spaces("Every other domain ranked by its IPD against " + s.left_domain() + " (the left domain) for " +
                         (s.model().empty() ? std::string("no model") : s.model()) +
                         ", conf >= " + fmt::format("{:g}", s.conf_threshold()) +
                         "; lower is closer. A click shows that setting on the right.");
  if (!result) {
    ImGui::TextDisabled("computing the ranking...");
    ImGui::End();
    return;
  }
  if (!current) ImGui::TextDisabled("updating...");
  if (!result->ranking) {
    text_coloured_wrapped_at_spaces({1, 0.55f, 0, 1}, "no ranking: " + result->error);
    ImGui::End();
    return;
  }
  const Ranking& k = *result->ranking;
  const float table_h = std::min(ImGui::GetContentRegionAvail().y * 0.5f,
                                 (k.ranked.size() + 1.5f) * ImGui::GetTextLineHeightWithSpacing() + 8);
  if (ImGui::BeginTable(
          "rank", 8,
          ImGuiTableFlags_RowBg | ImGuiTableFlags_ScrollY | ImGuiTableFlags_ScrollX | ImGuiTableFlags_BordersInnerV,
          {0, std::max(80.0f, table_h)})) {
    ImGui::TableSetupScrollFreeze(2, 1);
    const std::string ipd_tip = "IPD(" + k.ref + ", setting) with its 95% scene-bootstrap interval, as ipd table";
    const std::string holm = fmt::format("its p-value Holm-corrected over the {} comparisons with the best", k.tests);
    setup_text_columns({{"#", "99", "rank, 1 = closest to the reference"},
                        {"setting", nullptr, "the domain (a renderer setting)"},
                        {"params", "w=0.30 b=0.20", "study.yaml's params of the setting"},
                        {"IPD", "0.0000 [0.000, 0.000]", ipd_tip.c_str()},
                        {"pairs", "99,999", "rock pairs counted"},
                        {"vs best", "+0.0000 [\u22120.000, \u22120.000]", "IPD minus the best's, paired interval"},
                        {"p Holm", "0.0000", holm.c_str()},
                        {"group", "\u2248 best", "\u2248 best: not distinguishable from the best at the 0.05 level"}},
                       /*sortable=*/false);
    for (const RankedCandidate& r : k.ranked) {
      const std::vector<std::string> cells = rank_row_cells(r);
      const ImFont* font = ImGui::GetFont();
      auto has_glyph = [font](char32_t g) { return font->FindGlyphNoFallback(static_cast<ImWchar>(g)) != nullptr; };
      ImGui::TableNextRow();
      ImGui::TableNextColumn();
      const bool shown = r.domain == s.right_domain();
      if (ImGui::Selectable((cells[0] + "##" + r.domain).c_str(), shown, ImGuiSelectableFlags_SpanAllColumns))
        choose_ranked_domain(s, r.domain, out);
      if (ImGui::IsItemHovered()) ImGui::SetTooltip("show %s on the right", r.domain.c_str());
      for (size_t c = 1; c < cells.size(); ++c) {
        ImGui::TableNextColumn();
        const std::string cell = spell_missing_glyphs(cells[c], has_glyph);  // "−" and "≈" when the font draws them
        if (c == 7 && r.in_best_group)
          ImGui::TextColored({0.5f, 0.9f, 0.5f, 1}, "%s", cell.c_str());
        else
          ImGui::TextUnformatted(cell.c_str());
      }
    }
    ImGui::EndTable();
  }
  for (const UnrankedCandidate& u : k.unranked)
    text_disabled_wrapped_at_spaces("not ranked: " + u.domain + ": " + u.reason);
  // The sweep, by the figure's rule: one varying parameter draws a line; otherwise say why there is none.
  try {
    const SweepChart chart = sweep_chart(k, "");  // the window ranks every other domain: no choice to offer
    if (chart.parameters.size() == 1) {
      ImGui::TextUnformatted(("IPD along " + chart.parameters.front() +
                              " (ring: the best; filled: not distinguishable from it; bars: 95% intervals)")
                                 .c_str());
      draw_sweep(s, chart, k.ref, out);
    } else {
      text_disabled_wrapped_at_spaces("two parameters vary (" + chart.parameters[0] + ", " + chart.parameters[1] +
                                      "): ipd figure sweep draws them as a heat map");
    }
  } catch (const std::exception& e) {
    text_disabled_wrapped_at_spaces(std::string("no sweep plot: ") + e.what());
  }
  ImGui::End();
}

}  // namespace ipd::ui
