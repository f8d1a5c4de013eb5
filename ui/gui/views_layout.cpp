// The main window's columns (studio_columns() decides the widths): browser | pictures over registration
// and pair table | IPD and statistics, with draggable gaps; narrow windows tab what no longer fits side
// by side, so the pictures keep a usable width.
#include <algorithm>

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

void draw_centre(const StudyView& v, UiState& ui, const Picture& left, const Picture& right, float h, bool tabbed,
                 UiCommands& out) {
  const Session& s = *v.session;
  // The pictures' pane takes the height their aspect needs (no letterbox), unless the user dragged it.
  const float w = ImGui::GetContentRegionAvail().x;
  const int iw = left.width > 0 ? left.width : s.study().config.image_width;
  const int ih = left.height > 0 ? left.height : s.study().config.image_height;
  const float aspect = iw > 0 && ih > 0 ? float(iw) / ih : 1.6f;
  // Toolbar (one line, or two when narrow), the captions' strip, then the pictures.
  const float toolbar = (w >= scene_toolbar_width() ? 1 : 2) * ImGui::GetFrameHeightWithSpacing();
  const float fit = (w - 6) * 0.5f / aspect + toolbar + ImGui::GetTextLineHeightWithSpacing() + 4;
  const float pic_h = std::clamp(ui.pictures_height > 0 ? ui.pictures_height : fit, 0.25f * h, 0.8f * h);
  ImGui::BeginChild("pictures", {0, pic_h}, false, ImGuiWindowFlags_NoScrollWithMouse);
  draw_side_by_side(v, ui, left, right, out);
  ImGui::EndChild();
  ImGui::InvisibleButton("##split", {-1, 6});
  if (ImGui::IsItemActive()) ui.pictures_height = pic_h + ImGui::GetIO().MouseDelta.y;
  if (ImGui::IsItemHovered() || ImGui::IsItemActive()) ImGui::SetMouseCursor(ImGuiMouseCursor_ResizeNS);
  if (tabbed) {
    if (ImGui::BeginTabBar("centre_tabs")) {
      const float rest = ImGui::GetContentRegionAvail().y - ImGui::GetFrameHeightWithSpacing() - 8;
      if (ImGui::BeginTabItem("registration")) {
        ImGui::BeginChild("registration", {0, rest}, true);
        draw_registration(v, ui, out);
        ImGui::EndChild();
        ImGui::EndTabItem();
      }
      if (ImGui::BeginTabItem("pairs")) {
        ImGui::BeginChild("pairtable", {0, rest}, true);
        draw_pair_table(v, ui, out);
        ImGui::EndChild();
        ImGui::EndTabItem();
      }
      ImGui::EndTabBar();
    }
    return;
  }
  const float rest = ImGui::GetContentRegionAvail().y - 8;
  // The pair table's columns are sized from their text; the registration plot takes the rest.
  const ImGuiStyle& st = ImGui::GetStyle();
  const float table_w = 7 * 2 * st.CellPadding.x + ImGui::CalcTextSize("99 x 99 0.000 0.000 excl. 999.9 0.00").x +
                        3 * st.WindowPadding.x + st.ScrollbarSize + 110;
  const float avail_w = ImGui::GetContentRegionAvail().x;
  ImGui::BeginChild("registration", {std::max(avail_w * 0.55f, avail_w - table_w), rest}, true);
  draw_registration(v, ui, out);
  ImGui::EndChild();
  ImGui::SameLine();
  ImGui::BeginChild("pairtable", {0, rest}, true);
  draw_pair_table(v, ui, out);
  ImGui::EndChild();
}

// A collapsed side column of the focus view: one button that brings the panels back.
void focus_strip(const char* id, float height, UiState& ui) {
  ImGui::BeginChild(id, {kFocusStrip, height}, false, ImGuiWindowFlags_NoScrollbar);
  if (ImGui::Button(id[0] == 'l' ? ">##strip" : "<##strip", {-1, 0})) ui.focus = false;
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("show the scene list and the statistics again (Z)");
  ImGui::EndChild();
}

// The focus view: the two pictures take the whole centre column, the panels are strips at its sides.
void draw_focus_columns(const StudyView& v, UiState& ui, const Picture& left, const Picture& right, float h,
                        UiCommands& out) {
  const float gap = 8;
  const StudioColumns c = focus_columns(ImGui::GetContentRegionAvail().x, gap);
  focus_strip("left_strip", h - 8, ui);
  ImGui::SameLine(0, gap);
  ImGui::BeginChild("pictures", {c.centre, h - 8}, false, ImGuiWindowFlags_NoScrollWithMouse);
  draw_side_by_side(v, ui, left, right, out);
  ImGui::EndChild();
  ImGui::SameLine(0, gap);
  focus_strip("right_strip", h - 8, ui);
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
      ImGui::EndTabBar();
    }
  } else {
    draw_study_browser(v, ui, out);
  }
  ImGui::EndChild();
  ImGui::SameLine(0, 0);
  if (const float d = column_splitter("##split_left", h - 8, gap); d != 0) ui.browser_width = c.left + d;
  ImGui::SameLine(0, 0);
  ImGui::BeginChild("centre_column", {c.centre, h - 8});
  draw_centre(v, ui, left, right, h - 8, c.tabbed_centre, out);
  ImGui::EndChild();
  if (!c.tabbed_side) {
    ImGui::SameLine(0, 0);
    if (const float d = column_splitter("##split_right", h - 8, gap); d != 0) ui.stats_width = c.right - d;
    ImGui::SameLine(0, 0);
    ImGui::BeginChild("ipd", {c.right, h - 8});
    stats_column();
    ImGui::EndChild();
  }
}

}  // namespace ipd::ui
