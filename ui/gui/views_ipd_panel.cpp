// The IPD panel: the scene in view (its IPD, suspect pairs, review marks), the domain pair's IPD, the cross
// table of every model and domain pair, and undo, redo, export and "save as".
#include <algorithm>
#include <string>
#include <utility>
#include <vector>

#include "core/report/table_format.h"
#include "ui/gui/stats_panels.h"
#include "ui/gui/studio_layout.h"
#include "ui/gui/table_layout.h"
#include "ui/gui/views.h"

namespace ipd::ui {

void draw_ipd_panel(const StudyView& v, UiState& ui, UiCommands& out) {
  const Session& s = *v.session;
  const TableCell t = s.cell();  // the domain pair's cell: its number below, and why a scene has none
  if (!s.scenes().empty()) {
    const SceneSummary& m = (*v.summaries)[ui.scene];
    ImGui::Text("scene %s", m.stem.c_str());
    if (t.missing_predictions)  // no scene has a number, whatever its pairs: say why, not "0 pairs"
      text_coloured_wrapped_at_spaces({1, 0.55f, 0, 1}, "IPD – (not a number): " + t.no_value_reason);
    else
      text_wrapped_at_spaces("IPD " + fmt_ipd(m.ipd) + "  (" + counted(m.pairs, "pair") + ", unpaired " +
                             thousands(m.unpaired_a) + " / " + thousands(m.unpaired_b) + ")");
    if (!m.no_value_reason.empty())
      text_coloured_wrapped_at_spaces({1, 0.55f, 0, 1}, "no IPD for this scene: " + m.no_value_reason);
    if (m.suspects)
      text_coloured_wrapped_at_spaces({1, 0.55f, 0, 1}, counted(m.suspects, "suspect pair") +
                                                            ": N jumps to the next one, C marks it checked, correct");
    // Review marks: what was looked at, so an audit can be split over days or people.
    bool reviewed = s.reviewed(ui.scene);
    if (ImGui::Checkbox("reviewed (R)", &reviewed)) out.toggle_reviewed = true;
    if (const auto [l, r] = selected_pair(s, ui); l >= 0) {
      const std::string label = "pair " + std::to_string(l + 1) + " checked, correct (C)";
      bool checked = s.checked(ui.scene, l, r);
      same_line_if_fits(ImGui::GetFrameHeight() + ImGui::CalcTextSize(label.c_str()).x +
                        ImGui::GetStyle().ItemInnerSpacing.x);
      if (ImGui::Checkbox(label.c_str(), &checked)) out.check_left = l, out.check_right = r;
    }
  }
  ImGui::Separator();
  // A first look while the study loads: the numbers below are of the scenes read so far, not yet the study's.
  const std::string partial = v.loading.empty() ? std::string() : " (scenes read so far; updating...)";
  text_wrapped_at_spaces("IPD(" + s.left_domain() + ", " + s.right_domain() + ") for " + s.model() + partial);
  if (!t.no_value_reason.empty())  // two empty prediction sets are not a perfect match: say why there is no number
    text_coloured_wrapped_at_spaces({1, 0.55f, 0, 1}, "– (not a number): " + t.no_value_reason);
  else
    text_wrapped_at_spaces(cell_totals_line(t.ipd, t.pairs, *v.summaries));
  ImGui::Separator();
  text_wrapped_at_spaces("Cross table (lower is better)" + partial);
  const auto& pairs = s.domain_pairs();
  // Sized to its rows (two header rows, one per model): a fixed height left blank rows below them.
  auto model_label = [](const ModelInfo& m) {
    // "det-real (real)" says the training domain twice; the name alone when it already holds it.
    const bool named = m.trained_on.empty() || m.name.find(m.trained_on) != std::string::npos;
    return named ? m.name : m.name + " (" + m.trained_on + ")";
  };
  std::vector<float> widths(pairs.size() + 1, ImGui::CalcTextSize("train \\ eval").x);
  for (const auto& m : s.study().models) widths[0] = std::max(widths[0], ImGui::CalcTextSize(model_label(m).c_str()).x);
  std::vector<std::pair<std::string, std::string>> headers;
  for (const auto& [a, b] : pairs) headers.push_back(cross_table_header(a, b));
  for (size_t p = 0; p < pairs.size(); ++p)
    widths[p + 1] = std::max({ImGui::CalcTextSize(headers[p].first.c_str()).x,
                              ImGui::CalcTextSize(headers[p].second.c_str()).x, ImGui::CalcTextSize("0.0000").x});
  const ImGuiStyle& style = ImGui::GetStyle();
  const TableSize size =
      cross_table_size(widths, static_cast<int>(s.study().models.size()) + 2, ImGui::GetContentRegionAvail().x,
                       {ImGui::GetTextLineHeight(), style.CellPadding.x, style.CellPadding.y, 1, style.ScrollbarSize});
  if (ImGui::BeginTable("cross", static_cast<int>(pairs.size()) + 1,
                        ImGuiTableFlags_Borders | ImGuiTableFlags_SizingFixedFit |
                            (size.scroll_x ? ImGuiTableFlags_ScrollX : ImGuiTableFlags_None),
                        ImVec2(0, size.scroll_x ? size.height : 0))) {
    // Headers on two rows ("|real -" over "principled|"): a column is as wide as its longer domain name, not both
    // names, so three domain pairs fit the side panel at 1600 px.
    ImGui::TableSetupColumn("train \\ eval");
    for (size_t p = 0; p < pairs.size(); ++p) ImGui::TableSetupColumn(nullptr);
    for (int row = 0; row < 2; ++row) {
      ImGui::TableNextRow(ImGuiTableRowFlags_Headers);
      ImGui::TableSetColumnIndex(0);
      ImGui::PushID(row);
      ImGui::TableHeader(row == 0 ? "train \\ eval" : "");
      for (size_t p = 0; p < pairs.size(); ++p) {
        ImGui::TableSetColumnIndex(static_cast<int>(p) + 1);
        ImGui::TableHeader(row == 0 ? headers[p].first.c_str() : headers[p].second.c_str());
      }
      ImGui::PopID();
    }
    std::vector<std::string> reasons;  // of the cells that are not a number: footnote k is reasons[k - 1]
    for (const auto& m : s.study().models) {
      ImGui::TableNextRow();
      ImGui::TableNextColumn();
      ImGui::TextUnformatted(model_label(m).c_str());
      if (!m.trained_on.empty() && ImGui::IsItemHovered()) ImGui::SetTooltip("trained on %s", m.trained_on.c_str());
      for (size_t p = 0; p < pairs.size(); ++p) {
        ImGui::TableNextColumn();
        const TableCell cell = s.cell_for(m.name, static_cast<int>(p));  // the engine's cell (ipd.h)
        const bool involves = cell.involves_training_domain;
        const double val = cell.ipd;
        const bool current = m.name == s.model() && static_cast<int>(p) == s.pair_index();
        if (!involves)  // the en dash of the tables and figures (the paper's mark)
          ImGui::TextDisabled("–");
        else if (!cell.no_value_reason.empty())  // the tables' and figures' mark, its reason below the table
          ImGui::TextColored({1, 0.55f, 0, 1}, "%s",
                             no_value_mark(footnote_number(&reasons, cell.no_value_reason)).c_str());
        else if (current)
          ImGui::TextColored({1, 0.85f, 0.3f, 1}, "%s", fmt_ipd(val).c_str());
        else
          ImGui::TextUnformatted(fmt_ipd(val).c_str());
        if (involves && !cell.no_value_reason.empty() && ImGui::IsItemHovered())
          ImGui::SetTooltip("not a number: %s", cell.no_value_reason.c_str());
        else if (involves)
          cell_interval_tooltip(v.stats, m.name, static_cast<int>(p));
      }
    }
    ImGui::EndTable();
    for (size_t k = 0; k < reasons.size(); ++k)
      text_disabled_wrapped_at_spaces(no_value_mark(static_cast<int>(k) + 1) + ": not a number, " + reasons[k]);
  }
  ImGui::Separator();
  ImGui::BeginDisabled(!s.can_undo());
  if (ImGui::Button("undo (Ctrl+Z)")) out.undo = true;
  ImGui::EndDisabled();
  same_line_if_fits(button_width("redo (Ctrl+Y)"));
  ImGui::BeginDisabled(!s.can_redo());
  if (ImGui::Button("redo (Ctrl+Y)")) out.redo = true;
  ImGui::EndDisabled();
  same_line_if_fits(button_width("export figures"));
  if (ImGui::Button("export figures")) out.export_figures = true;
  if (s.read_only()) {
    take_keyboard_if_asked(ui, UiState::Field::kSaveAs);
    const bool entered =
        ImGui::InputTextWithHint("##saveas", "directory for the edited pairs; Enter saves", ui.save_as_dir,
                                 sizeof ui.save_as_dir, ImGuiInputTextFlags_EnterReturnsTrue);
    if (entered) out.save_as = true;
    keep_keyboard_after_enter(entered);
    ImGui::SameLine();
    if (ImGui::Button("save as")) out.save_as = true;
  }
}

}  // namespace ipd::ui
