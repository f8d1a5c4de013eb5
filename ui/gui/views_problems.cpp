// The Problems window: every problem the engine found in the study's data (bad label lines that were
// skipped, scenes without a counterpart, ignored pairs files, pictures that can't be read), each naming its
// file and line; a click goes to its scene. The status bar shows their count and opens it.
#include <imgui.h>

#include <string>

#include "ui/gui/studio_layout.h"
#include "ui/gui/views.h"

namespace ipd::ui {

std::string problems_label(size_t count) { return counted(static_cast<long>(count), "problem"); }

void draw_problems_window(const StudyView& v, UiState& ui, UiCommands& out) {
  if (!ui.show_problems || !v.problems) return;
  ImGui::SetNextWindowSize({760, 320}, ImGuiCond_FirstUseEver);
  const std::string title = problems_label(v.problems->size()) + " in the study's data###Problems";
  if (!ImGui::Begin(title.c_str(), &ui.show_problems)) {
    ImGui::End();
    return;
  }
  if (v.problems->empty()) ImGui::TextDisabled("None found.");
  // Wrapped: at the window's first-use width the line ran past its right edge.
  text_disabled_wrapped_at_spaces(
      "Malformed label lines are skipped (their rocks are in no IPD); cells without a number say why. Click a row to "
      "see its scene.");
  if (ImGui::BeginTable("problems", 2,
                        ImGuiTableFlags_RowBg | ImGuiTableFlags_BordersInnerV | ImGuiTableFlags_ScrollY |
                            ImGuiTableFlags_Resizable)) {
    ImGui::TableSetupScrollFreeze(0, 1);
    ImGui::TableSetupColumn("scene", ImGuiTableColumnFlags_WidthFixed, ImGui::CalcTextSize("scene_00000").x);
    ImGui::TableSetupColumn("problem (file:line: what is wrong)");
    ImGui::TableHeadersRow();
    for (size_t k = 0; k < v.problems->size(); ++k) {
      const Problem& p = (*v.problems)[k];
      ImGui::TableNextRow();
      ImGui::TableNextColumn();
      ImGui::PushID(static_cast<int>(k));
      const bool can_go = !p.scene.empty();
      if (ImGui::Selectable(can_go ? p.scene.c_str() : "-", false,
                            ImGuiSelectableFlags_SpanAllColumns | (can_go ? 0 : ImGuiSelectableFlags_Disabled)))
        out.goto_problem = static_cast<int>(k);
      ImGui::PopID();
      ImGui::TableNextColumn();
      text_wrapped_at_spaces(p.to_string());  // never inside a number, as every panel wraps
    }
    ImGui::EndTable();
  }
  ImGui::End();
}

}  // namespace ipd::ui
