#include "ui/gui/stats_panels.h"
#include "ui/gui/studio_layout.h"

#include <fmt/format.h>
#include <imgui.h>
#include <algorithm>
#include <cmath>

#include "core/report/table_format.h"
#include "core/util/number_text.h"
#include "ui/figures/stats_charts.h"
#include "ui/gui/canvas_imgui.h"

namespace ipd::ui {

namespace {

std::string interval(double v, double lo, double hi) {
  if (std::isnan(v)) return "n/a";
  if (std::isnan(lo) || std::isnan(hi)) return fixed(v, 4);
  return fixed(v, 4) + " [" + fixed(lo, 3) + ", " + fixed(hi, 3) + "]";  // never "-0.000"
}
// A cell's IPD with its interval, or with why it has none ("0.0200, 1 scene: no interval").
std::string cell_interval(const TableCell& c) {
  const std::string why = std::isnan(c.ci_low) ? no_interval_reason(c) : std::string();
  return interval(c.ipd, c.ci_low, c.ci_high) + (why.empty() ? "" : ", " + why);
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
constexpr double kLineToEm = 1.164;  // DejaVu Sans' line height over its em size (as ImGuiCanvas assumes)

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

std::string empty_histogram_text(const std::vector<SceneSummary>& summaries) {
  const SceneSummary* paired = nullptr;
  for (const SceneSummary& m : summaries)
    if (m.pairs > 0 && (!paired || (paired->no_value_reason.empty() && !m.no_value_reason.empty()))) paired = &m;
  if (!paired) return "no scene with pairs";
  // Pairs but no value: "no scene with pairs" would send the user looking at the registration.
  if (!paired->no_value_reason.empty()) return "no per-scene IPD: " + paired->no_value_reason;
  return "no scene with an IPD";
}

std::string cell_totals_line(double ipd, long pairs, const std::vector<SceneSummary>& summaries) {
  const long with_pairs =
      std::count_if(summaries.begin(), summaries.end(), [](const SceneSummary& m) { return m.pairs > 0; });
  const long without = static_cast<long>(summaries.size()) - with_pairs;
  std::string line = fmt_ipd(ipd) + " over " + counted(pairs, "pair") + " in " + histogram_scenes_text(with_pairs);
  if (without > 0) line += " (" + counted(without, "scene") + " without pairs)";
  return line;
}

std::string histogram_scenes_text(size_t scenes) { return counted(scenes, "scene") + " with pairs"; }

HistogramBins histogram_bins(const std::vector<double>& values, int bins) {
  HistogramBins h;
  if (values.empty() || bins < 1) return h;
  const double lo = *std::min_element(values.begin(), values.end());
  const double hi = *std::max_element(values.begin(), values.end());
  h.width = round_step(std::max(hi, 1e-9) / bins);
  if (lo == hi) {                        // one value: three bins around it, its bar drawn at the value
    if (h.width < 1e-6) h.width = 0.01;  // every IPD 0: a readable axis, not bins of 1e-9
    h.start = std::max(0.0, std::floor(lo / h.width) * h.width - h.width);  // an IPD is never negative
    h.counts.assign(3, 0);
    h.counts[std::clamp(static_cast<int>(std::floor((lo - h.start) / h.width + 1e-9)), 0, 2)] =
        static_cast<int>(values.size());
    h.lone_value = lo;
    return h;
  }
  h.start = std::floor(lo / h.width) * h.width;
  const int n = std::max(1, static_cast<int>(std::floor((hi - h.start) / h.width)) + 1);
  h.counts.assign(n, 0);
  for (double v : values) h.counts[std::clamp(static_cast<int>(std::floor((v - h.start) / h.width)), 0, n - 1)]++;
  return h;
}

std::string compare_delta_line(const Comparison& r) {
  std::string line = "\u0394IPD = " + minus_number(r.delta.estimate, 4);
  if (r.scenes < 2) return line + fmt::format(", {} scene: no interval, no test", r.scenes);
  if (!std::isnan(r.delta.estimate) && r.delta.has_interval())
    line += " [" + minus_number(r.delta.low, 3) + ", " + minus_number(r.delta.high, 3) + "]";
  if (std::isnan(r.p_value)) return line;
  return line + (r.p_value < 1e-4 ? std::string("   p < 0.0001") : fmt::format("   p = {:.2g}", r.p_value));
}

void cell_interval_tooltip(const SessionStatistics* stats, const std::string& model, int pair) {
  if (!stats || !ImGui::IsItemHovered() || pair < 0 || pair >= static_cast<int>(stats->table.columns.size())) return;
  const auto& [a, b] = stats->table.columns[pair];
  const TableCell* c = stats->table.cell(model, a, b);
  if (!c || std::isnan(c->ipd)) return;
  ImGui::BeginTooltip();
  ImGui::Text("IPD(%s, %s) for %s", a.c_str(), b.c_str(), model.c_str());
  ImGui::Text("%s", cell_interval(*c).c_str());
  ImGui::TextDisabled("%g%% scene-bootstrap interval, %s resamples; se %.4f", 100 * stats->request.bootstrap.level,
                      grouped_thousands(stats->request.bootstrap.resamples).c_str(), c->se);
  ImGui::TextDisabled("%s in %s", counted(c->pairs, "pair").c_str(), counted(c->scenes, "scene").c_str());
  ImGui::EndTooltip();
}

namespace {

void draw_compare(const StudyView& v, const SessionStatistics* stats, bool computing, StatsPanelState& st) {
  const auto& domains = v.session->study().domains;
  if (domains.size() < 3) return;
  ImGui::TextUnformatted(computing ? "Which renderer is closer? (updating...)" : "Which renderer is closer?");
  auto combo = [&](const char* label, int* index) {
    ImGui::SetNextItemWidth(110);
    if (ImGui::BeginCombo(label, domains[std::min<size_t>(*index, domains.size() - 1)].name.c_str())) {
      for (size_t k = 0; k < domains.size(); ++k)
        if (ImGui::Selectable(domains[k].name.c_str(), static_cast<int>(k) == *index)) *index = static_cast<int>(k);
      ImGui::EndCombo();
    }
  };
  combo("ref##cmp", &st.ref);
  same_line_if_fits(110 + ImGui::GetStyle().ItemInnerSpacing.x + ImGui::CalcTextSize("a").x);
  combo("a##cmp", &st.a);
  combo("b##cmp", &st.b);
  if (st.ref == st.a || st.ref == st.b || st.a == st.b) {
    ImGui::TextDisabled("pick three different domains");
    return;
  }
  if (!stats || !stats->comparison) {
    if (stats && !stats->comparison_error.empty()) text_wrapped_at_spaces(stats->comparison_error);
    return;
  }
  const RendererComparison& c = *stats->comparison;
  const Comparison& r = c.result;
  text_wrapped_at_spaces("IPD(" + c.ref + "," + c.a + ") " + fixed(r.ipd_a, 4) + ", IPD(" + c.ref + "," + c.b + ") " +
                         fixed(r.ipd_b, 4));
  // The numbers line writes ΔIPD and the typographic minus as the sentence under it (comparison_sentence) does,
  // when the font draws them (ipd-studio loads DejaVu Sans with both); in ASCII when it does not (ImGui's built-in
  // font would draw '?').
  const ImFont* font = ImGui::GetFont();
  auto has_glyph = [font](char32_t g) { return font->FindGlyphNoFallback(static_cast<ImWchar>(g)) != nullptr; };
  text_wrapped_at_spaces(spell_missing_glyphs(compare_delta_line(r), has_glyph));
  text_wrapped_at_spaces(
      spell_missing_glyphs(comparison_sentence(c), has_glyph));  // never "-0.|0799", never "delta" | "IPD"
}

}  // namespace

// The charts draw on the figure canvas in window pixels, text at the GUI font's size.
TextStyle gui_text() { return {ImGui::GetFontSize() / kLineToEm, {}, false}; }

static Colour colour_of(ImU32 c) {
  return rgb(int(c & 0xff), int((c >> 8) & 0xff), int((c >> 16) & 0xff), int((c >> 24) & 0xff));
}

ChartColours gui_colours() {
  return {colour_of(kBar),
          colour_of(kBarHot),
          colour_of(kCurrent),
          rgb(150, 150, 150),
          colour_of(kWhisker),
          colour_of(ImGui::GetColorU32(ImGuiCol_TextDisabled)),
          colour_of(ImGui::GetColorU32(ImGuiCol_Text))};
}

namespace {

// `computing`: these statistics are of an earlier state (the study still loading, or before an edit); the
// caption says so, as the interval line does, so a partial count ("40 scenes" of 10,000) isn't read as final.
void draw_histogram(const StudyView& v, const SessionStatistics* stats, bool computing, StatsPanelState& st,
                    UiState& ui) {
  text_wrapped_at_spaces("Per-scene IPD, " + v.session->model() + " (click a bar: those scenes)");
  if (!stats || stats->scene_ipd.empty()) {
    text_wrapped_at_spaces(stats && v.summaries ? empty_histogram_text(*v.summaries) : "no scene with pairs");
    return;
  }
  std::vector<double> values;
  for (const auto& [stem, val] : stats->scene_ipd) values.push_back(val);
  const HistogramBins h = histogram_bins(values, st.bins);
  HistogramInput in{h.start, h.width, h.counts, std::nan(""), h.lone_value};
  std::string current_stem;
  if (!v.session->scenes().empty() && ui.scene < static_cast<int>(v.summaries->size())) {
    in.current = (*v.summaries)[ui.scene].ipd;
    current_stem = (*v.summaries)[ui.scene].stem;
  }
  const float line = ImGui::GetTextLineHeight();
  // Never zero-sized (ImGui asserts on an empty button), however narrow the panel.
  const ImVec2 p0 = ImGui::GetCursorScreenPos(),
               size{std::max(8 * line, ImGui::GetContentRegionAvail().x), 70 + 2 * line};
  const bool clicked = ImGui::InvisibleButton("histogram", size);
  ImGuiCanvas canvas(ImGui::GetWindowDrawList(), p0, 1, {});
  const TextStyle text = gui_text();
  const HistogramChart chart = layout_histogram(canvas, text, in, {0, 0, size.x, size.y});
  int hot = -1;
  if (ImGui::IsItemHovered()) {
    const ImVec2 m = ImGui::GetMousePos();
    for (size_t k = 0; k < chart.bars.size(); ++k) {
      const PtRect& s = chart.bars[k].slot;
      if (m.x - p0.x >= s.x0 && m.x - p0.x < s.x1 && m.y - p0.y >= s.y0 && m.y - p0.y <= s.y1)
        hot = static_cast<int>(k);
    }
  }
  draw_histogram(canvas, text, chart, gui_colours(), hot);
  if (hot >= 0) {
    const HistogramBar& b = chart.bars[hot];
    const bool last = hot + 1 == static_cast<int>(chart.bars.size());
    ImGui::SetTooltip("%s with IPD in [%g, %g%s\nclick: show them in the scene list", counted(b.count, "scene").c_str(),
                      b.lo, b.hi, last ? "]" : ")");
    const std::string filter = fmt::format("ipd>={:g} ipd{}{:g}", b.lo, last ? "<=" : "<", b.hi);
    if (clicked && filter.size() < sizeof ui.filter) std::snprintf(ui.filter, sizeof ui.filter, "%s", filter.c_str());
  }
  const std::string scenes = histogram_scenes_text(values.size()) + (computing ? " (updating...)" : "");
  if (current_stem.empty() || std::isnan(in.current))
    text_disabled_wrapped_at_spaces(scenes);
  else
    text_disabled_wrapped_at_spaces(scenes + "; outlined: the bin of " + current_stem);
}

void draw_size_breakdown(const SessionStatistics* stats, bool computing) {
  if (!stats || !stats->size) return;
  const CellBreakdown& b = *stats->size;
  ImGui::Text("IPD by %s rock size (px²)%s", b.a.c_str(), computing ? " (updating...)" : "");
  std::vector<ValueBarRow> rows;
  for (const auto& bin : b.bins) rows.push_back({bin.label, bin.ipd.estimate, bin.ipd.low, bin.ipd.high});
  const TextStyle text = gui_text();
  const ImVec2 p0 = ImGui::GetCursorScreenPos();
  ImGuiCanvas canvas(ImGui::GetWindowDrawList(), p0, 1, {});
  const ImVec2 size{std::max(8 * ImGui::GetTextLineHeight(), ImGui::GetContentRegionAvail().x),
                    static_cast<float>(value_bars_height(canvas, text, std::max<size_t>(1, rows.size())))};
  ImGui::InvisibleButton("size bars", size);
  const ValueBarsChart chart = layout_value_bars(canvas, text, rows, {0, 0, size.x - 2, size.y});
  int hot = -1;
  if (ImGui::IsItemHovered()) {
    const ImVec2 m = ImGui::GetMousePos();
    for (size_t i = 0; i < chart.rows.size(); ++i)
      if (m.y - p0.y >= chart.rows[i].band.y0 && m.y - p0.y < chart.rows[i].band.y1) hot = static_cast<int>(i);
  }
  draw_value_bars(canvas, text, chart, rows, gui_colours(), hot);
  if (hot >= 0) {
    const BreakdownBin& bin = b.bins[hot];
    ImGui::SetTooltip("%s: IPD %s\n%s in %s", bin.label.c_str(),
                      interval(bin.ipd.estimate, bin.ipd.low, bin.ipd.high).c_str(), counted(bin.pairs, "pair").c_str(),
                      counted(bin.scenes, "scene").c_str());
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
    if (c) ImGui::Text("IPD %s", cell_interval(*c).c_str());
    const bool has_ci = c && !std::isnan(c->ci_low);
    const std::string ci =
        fmt::format("{}{}", has_ci || !c ? fmt::format("{:g}% CI", 100 * stats->request.bootstrap.level) : "",
                    computing ? ", updating..." : "");
    same_line_if_fits(ImGui::CalcTextSize(ci.c_str()).x);
    ImGui::TextDisabled("%s", ci.c_str());
  } else {
    ImGui::TextDisabled("computing intervals...");
  }
  ImGui::Separator();
  draw_histogram(v, stats, computing, st, ui);
  ImGui::Separator();
  draw_size_breakdown(stats, computing);
  ImGui::Separator();
  draw_compare(v, stats, computing, st);
}

}  // namespace ipd::ui
