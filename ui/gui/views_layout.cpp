// The main window's columns (studio_columns() decides the widths): browser | the two pictures | IPD and
// statistics, the registration panel and the pair table as tabs, with draggable gaps; narrow windows tab the
// browser too, so the pictures keep a usable size. The focus view (Z) gives the pictures the whole window.
#include <algorithm>
#include <utility>

#include "ui/gui/studio_layout.h"
#include "ui/gui/views.h"

namespace ipd::ui {

namespace {

// A draggable vertical gap between two columns; returns the drag this frame (pixels, + = right).
float column_splitter(const char* id, float height, float width) {
  ImGui::InvisibleButton(id, {width, height});
  const bool hot = ImGui::IsItemHovered() || ImGui::IsItemActive();
  if (hot) ImGui::SetMouseCursor(ImGuiMouseCursor_ResizeEW);
  const ImVec2 a = ImGui::GetItemRectMin(), b = ImGui::GetItemRectMax();
  const float x = 0.5f * (a.x + b.x);
  ImGui::GetWindowDrawList()->AddLine({x, a.y}, {x, b.y},
                                      ImGui::GetColorU32(hot ? ImGuiCol_SeparatorActive : ImGuiCol_Separator));
  return ImGui::IsItemActive() ? ImGui::GetIO().MouseDelta.x : 0.0f;
}

// The registration panel and the pair table, each a tab beside the statistics: the centre column is the
// pictures' (they need the area: a 30 px rock of a 1936 px picture must stay visible).
void registration_tab(const StudyView& v, UiState& ui, UiCommands& out) {
  const bool bring_forward = std::exchange(ui.show_registration_tab, false);
  ui.registration_tab_shown =
      ImGui::BeginTabItem("registration", nullptr, bring_forward ? ImGuiTabItemFlags_SetSelected : 0);
  if (ui.registration_tab_shown) {
    ImGui::BeginChild("registration", {0, 0}, true);
    draw_registration(v, ui, out);
    ImGui::EndChild();
    ImGui::EndTabItem();
  }
}

void pair_table_tab(const StudyView& v, UiState& ui, UiCommands& out) {
  if (ImGui::BeginTabItem("pairs")) {
    ImGui::BeginChild("pairtable", {0, 0}, true);
    draw_pair_table(v, ui, out);
    ImGui::EndChild();
    ImGui::EndTabItem();
  }
}

// The focus view's thin strip: what is shown (scene, domain pair, model and the scene's IPD) and the way back.
void focus_strip(const StudyView& v, UiState& ui) {
  const Session& s = *v.session;
  std::string what = "focus view";
  if (!s.scenes().empty() && ui.scene < static_cast<int>(v.summaries->size())) {
    const SceneSummary& m = (*v.summaries)[ui.scene];
    what = m.stem + "  |  " + s.left_domain() + " vs " + s.right_domain() + "  |  model " +
           (s.model().empty() ? "none" : s.model()) + "  |  scene IPD " + fmt_ipd(m.ipd);
  }
  ImGui::TextUnformatted(what.c_str());
  const char* back = "panels (Z)";
  const float right = ImGui::GetWindowPos().x + ImGui::GetWindowContentRegionMax().x;
  if (ImGui::GetItemRectMax().x + ImGui::GetStyle().ItemSpacing.x + button_width(back) <= right) {
    ImGui::SameLine(ImGui::GetWindowContentRegionMax().x - button_width(back));
  }
  if (ImGui::SmallButton(back)) ui.focus = false;
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("show the scene list and the statistics again (Z)");
}

// The focus view: the two pictures take the whole window under a thin strip naming what they show.
void draw_focus_columns(const StudyView& v, UiState& ui, const Picture& left, const Picture& right, float h,
                        UiCommands& out) {
  focus_strip(v, ui);
  ImGui::BeginChild("pictures", {0, h - 8 - ImGui::GetFrameHeightWithSpacing()}, false,
                    ImGuiWindowFlags_NoScrollWithMouse);
  draw_side_by_side(v, ui, left, right, out);
  ImGui::EndChild();
}

}  // namespace

void draw_main_columns(const StudyView& v, UiState& ui, const Picture& left, const Picture& right, float h,
                       const std::function<void()>& draw_stats, UiCommands& out) {
  if (ui.focus) return draw_focus_columns(v, ui, left, right, h, out);
  const float gap = 8;
  const float width = ImGui::GetContentRegionAvail().x;
  const float browser_pref = ui.browser_width > 0 ? ui.browser_width : browser_width(v, 300, 500);
  const float stats_pref = ui.stats_width > 0 ? ui.stats_width : 400;
  const StudioColumns c = studio_columns(width, browser_pref, stats_pref, gap);
  const ImGuiWindowFlags side_flags = ImGuiWindowFlags_HorizontalScrollbar;
  auto stats_column = [&] {
    draw_ipd_panel(v, ui, out);
    draw_stats();
  };

  ImGui::BeginChild("left_column", {c.left, h - 8}, false, c.tabbed_side ? 0 : side_flags);
  if (c.tabbed_side) {
    if (ImGui::BeginTabBar("side_tabs")) {
      if (ImGui::BeginTabItem("scenes")) {
        ImGui::BeginChild("browser", {0, 0}, false, side_flags);
        draw_study_browser(v, ui, out);
        ImGui::EndChild();
        ImGui::EndTabItem();
      }
      if (ImGui::BeginTabItem("IPD & statistics")) {
        ImGui::BeginChild("ipd", {0, 0});
        stats_column();
        ImGui::EndChild();
        ImGui::EndTabItem();
      }
      registration_tab(v, ui, out);
      pair_table_tab(v, ui, out);
      ImGui::EndTabBar();
    }
  } else {
    draw_study_browser(v, ui, out);
  }
  ImGui::EndChild();
  ImGui::SameLine(0, 0);
  if (const float d = column_splitter("##split_left", h - 8, gap); d != 0) ui.browser_width = c.left + d;
  ImGui::SameLine(0, 0);
  ImGui::BeginChild("centre_column", {c.centre, h - 8}, false, ImGuiWindowFlags_NoScrollWithMouse);
  draw_side_by_side(v, ui, left, right, out);
  ImGui::EndChild();
  if (!c.tabbed_side) {
    ImGui::SameLine(0, 0);
    if (const float d = column_splitter("##split_right", h - 8, gap); d != 0) ui.stats_width = c.right - d;
    ImGui::SameLine(0, 0);
    ImGui::BeginChild("right_column", {c.right, h - 8});
    if (ImGui::BeginTabBar("right_tabs")) {
      if (ImGui::BeginTabItem("IPD & statistics")) {
        ImGui::BeginChild("ipd", {0, 0});
        stats_column();
        ImGui::EndChild();
        ImGui::EndTabItem();
      }
      registration_tab(v, ui, out);
      pair_table_tab(v, ui, out);
      ImGui::EndTabBar();
    }
    ImGui::EndChild();
  }
}

}  // namespace ipd::ui
