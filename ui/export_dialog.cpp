#include "export_dialog.h"

#include <imgui.h>

#include <algorithm>
#include <filesystem>

namespace ipd::ui {

Crop crop_of_view(const CanvasView& view) {
  // place() centres the picture's point (0.5 + pan) in the pane and scales it by zoom.
  const double half = 0.5 / std::max(1.0f, view.zoom);
  const double cx = 0.5 + view.pan.x, cy = 0.5 + view.pan.y;
  Crop c{std::clamp(cx - half, 0.0, 1.0), std::clamp(cy - half, 0.0, 1.0), std::clamp(cx + half, 0.0, 1.0),
         std::clamp(cy + half, 0.0, 1.0)};
  if (!(c.x1 - c.x0 > 1e-3 && c.y1 - c.y0 > 1e-3)) return Crop{};
  // Snap to the whole picture when the zoom shows all of it.
  if (c.x0 < 1e-3 && c.y0 < 1e-3 && c.x1 > 1 - 1e-3 && c.y1 > 1 - 1e-3) return Crop{};
  return c;
}

ExportViewContext export_view_context(const Session& s, const UiState& ui) {
  ExportViewContext c;
  c.default_dir = s.read_only() ? std::filesystem::current_path().string()
                                : (std::filesystem::path(s.study().root) / "figures").string();
  if (ui.scene >= 0 && ui.scene < int(s.scenes().size())) {
    c.scene = ui.scene;
    c.base_name = s.scenes()[ui.scene].stem + "_" + s.left_domain() + "_" + s.right_domain();
  }
  c.layers = ui.layers;
  c.view = ui.left_view;
  return c;
}

void open_export_dialog(ExportDialogState& st, const ExportViewContext& ctx) {
  st.open = true;
  st.layers[0] = ctx.layers.gt;
  st.layers[1] = ctx.layers.predictions;
  st.layers[2] = ctx.layers.confidences && st.column == 1;  // confidences don't fit a single column
  st.layers[3] = ctx.layers.indices;
  std::snprintf(st.dir, sizeof st.dir, "%s", ctx.default_dir.c_str());
  std::snprintf(st.name, sizeof st.name, "%s", ctx.base_name.c_str());
}

std::optional<ExportRequest> draw_export_dialog(ExportDialogState& st, const ExportViewContext& ctx) {
  std::optional<ExportRequest> out;
  if (st.open && !ImGui::IsPopupOpen("Export figure")) ImGui::OpenPopup("Export figure");
  if (!ImGui::BeginPopupModal("Export figure", &st.open, ImGuiWindowFlags_AlwaysAutoResize)) return out;
  static const char* kinds[] = {"pairs (Fig. 1)", "registration (Fig. 2)"};
  static const char* formats[] = {"PDF", "SVG", "PNG (300 dpi)"};
  static const char* exts[] = {".pdf", ".svg", ".png"};
  ImGui::Combo("figure", &st.kind, kinds, 2);
  ImGui::Combo("format", &st.format, formats, 3);
  ImGui::RadioButton("single column (3.5 in)", &st.column, 0);
  ImGui::SameLine();
  ImGui::RadioButton("double (7.16 in)", &st.column, 1);
  ImGui::SliderFloat("font (pt)", &st.font_pt, 6.0f, 12.0f, "%.1f");
  static const char* names[] = {"GT", "predictions", "confidences", "numbers", "pairs", "legend"};
  ImGui::TextUnformatted("layers:");
  for (int k = 0; k < 6; ++k) {
    ImGui::SameLine();
    ImGui::Checkbox(names[k], &st.layers[k]);
  }
  const Crop crop = crop_of_view(ctx.view);
  if (crop.whole()) {
    ImGui::TextDisabled("crop: the whole picture (zoom in to export a region)");
  } else {
    ImGui::Checkbox("crop to the current zoom", &st.crop_to_view);
    ImGui::SameLine();
    ImGui::TextDisabled("(%.2f, %.2f) - (%.2f, %.2f)", crop.x0, crop.y0, crop.x1, crop.y1);
  }
  ImGui::InputText("folder", st.dir, sizeof st.dir);
  ImGui::InputText("file name", st.name, sizeof st.name);
  const std::string path =
      (std::filesystem::path(st.dir) / (std::string(st.name) + (st.kind == 0 ? "_pairs" : "_registration") + exts[st.format]))
          .string();
  ImGui::TextDisabled("writes %s", path.c_str());
  ImGui::TextDisabled("same figure as: ipd figure %s ... --conf <slider> (edits included)", st.kind == 0 ? "pairs" : "registration");
  if (ImGui::Button("Export") && st.name[0]) {
    ExportRequest r;
    r.kind = st.kind == 0 ? "pairs" : "registration";
    r.options.width_in = st.column == 0 ? kSingleColumnIn : kDoubleColumnIn;
    r.options.font_pt = st.font_pt;
    r.options.layers = {st.layers[0], st.layers[1], st.layers[2], st.layers[3], st.layers[4], st.layers[5]};
    if (st.crop_to_view) r.options.crop = crop;
    r.options.font_file = default_font_file();
    r.path = path;
    r.scene = ctx.scene;
    out = r;
    st.open = false;
    ImGui::CloseCurrentPopup();
  }
  ImGui::SameLine();
  if (ImGui::Button("Cancel")) {
    st.open = false;
    ImGui::CloseCurrentPopup();
  }
  ImGui::EndPopup();
  return out;
}

}  // namespace ipd::ui
