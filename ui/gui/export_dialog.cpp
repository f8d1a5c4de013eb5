#include "ui/gui/export_dialog.h"

#include <imgui.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>

#include "ui/gui/views.h"

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

namespace {
const char* const kByNames[3] = {"size", "region", "confidence"};
bool is_scene_kind(int kind) { return kind < 2; }
}  // namespace

ExportViewContext export_view_context(const Session& s, const UiState& ui, const StatsPanelState& stats) {
  ExportViewContext c;
  c.default_dir = s.read_only() ? std::filesystem::current_path().string()
                                : (std::filesystem::path(s.study().root) / "figures").string();
  if (ui.scene >= 0 && ui.scene < int(s.scenes().size())) {
    c.scene = ui.scene;
    c.scene_stale = !s.stale_pairs(ui.scene).first.empty();
    c.base_name = s.scenes()[ui.scene].stem + "_" + s.left_domain() + "_" + s.right_domain();
  }
  c.model = s.model();
  c.conf_threshold = s.conf_threshold();
  c.left = s.left_domain();
  c.right = s.right_domain();
  const SessionStatisticsRequest r = stats_request(s, stats);
  c.ref = r.ref, c.a = r.a, c.b = r.b;
  c.layers = ui.layers;
  c.view = ui.left_view;
  return c;
}

std::string default_figure_name(const ExportDialogState& st, const ExportViewContext& ctx) {
  const std::string kind = kFigureKinds[std::clamp(st.kind, 0, 6)];
  char conf[32] = "";
  if (ctx.conf_threshold > 0) std::snprintf(conf, sizeof conf, "_conf%g", ctx.conf_threshold);
  const std::string model = ctx.model.empty() ? "" : "_" + ctx.model;
  // The registration figure shows GT only: neither model nor threshold changes it.
  if (kind == "registration") return ctx.base_name + "_" + kind;
  if (is_scene_kind(st.kind)) return ctx.base_name + model + conf + "_" + kind;
  if (kind == "table") return kind + conf;
  if (kind == "compare") return (ctx.ref.empty() ? kind : kind + "_" + ctx.ref + "_" + ctx.a + "_" + ctx.b) + conf;
  if (kind == "distribution") return kind + model + conf;
  if (kind == "gallery") return kind + model + "_" + ctx.left + "_" + ctx.right + conf;
  return kind + "_" + kByNames[std::clamp(st.by, 0, 2)] + model + "_" + ctx.left + "_" + ctx.right + conf;
}

void open_export_dialog(ExportDialogState& st, const ExportViewContext& ctx) {
  st.open = true;
  st.layers[0] = ctx.layers.gt;
  st.layers[1] = ctx.layers.predictions;
  st.layers[2] = ctx.layers.confidences && st.column == 1;  // confidences don't fit a single column
  st.layers[3] = ctx.layers.indices;
  st.gallery_sort = static_cast<int>(ctx.gallery_sort);  // the export follows the order on screen
  std::snprintf(st.dir, sizeof st.dir, "%s", ctx.default_dir.c_str());
  std::snprintf(st.name, sizeof st.name, "%s", default_figure_name(st, ctx).c_str());
}

bool set_export_kind(ExportDialogState& st, const std::string& kind) {
  for (int k = 0; k < 7; ++k)
    if (kind == kFigureKinds[k]) return st.kind = k, st.by = 0, true;
  for (int b = 0; b < 3; ++b)
    if (kind == std::string("breakdown-") + kByNames[b]) return st.kind = 5, st.by = b, true;
  return false;
}

ExportRequest export_request(const ExportDialogState& st, const ExportViewContext& ctx, const std::string& path) {
  ExportRequest r;
  r.kind = kFigureKinds[std::clamp(st.kind, 0, 6)];
  r.options.width_in = st.column == 0 ? kSingleColumnIn : kDoubleColumnIn;
  r.options.font_pt = st.font_pt;
  r.options.layers = {st.layers[0], st.layers[1], st.layers[2], st.layers[3], st.layers[4], st.layers[5]};
  if (st.crop_to_view) r.options.crop = crop_of_view(ctx.view);
  r.options.font_file = default_font_file();
  r.options.ci = st.ci;
  r.options.by = kByNames[std::clamp(st.by, 0, 2)];
  r.path = path;
  r.scene = ctx.scene;
  r.ref = ctx.ref, r.a = ctx.a, r.b = ctx.b;
  r.gallery_count = std::max(1, st.gallery_count);
  r.gallery_sort = static_cast<GallerySort>(std::clamp(st.gallery_sort, 0, 3));
  return r;
}

std::optional<ExportRequest> draw_export_dialog(ExportDialogState& st, const ExportViewContext& ctx) {
  std::optional<ExportRequest> out;
  if (st.open && !ImGui::IsPopupOpen("Export figure")) ImGui::OpenPopup("Export figure");
  if (!ImGui::BeginPopupModal("Export figure", &st.open, ImGuiWindowFlags_AlwaysAutoResize)) return out;
  static const char* kinds[] = {"pairs (Fig. 1)",       "registration (Fig. 2)",        "table (Table I)",
                                "compare (renderers)",  "distribution (per-scene IPD)", "breakdown",
                                "gallery (worst pairs)"};
  static const char* formats[] = {"PDF", "SVG", "PNG (300 dpi)"};
  static const char* exts[] = {".pdf", ".svg", ".png"};
  bool renamed = ImGui::Combo("figure", &st.kind, kinds, 7);
  if (st.kind == 5) {
    ImGui::SameLine();
    ImGui::SetNextItemWidth(ImGui::GetFontSize() * 7);
    renamed |= ImGui::Combo("by", &st.by, kByNames, 3);
  }
  if (renamed) std::snprintf(st.name, sizeof st.name, "%s", default_figure_name(st, ctx).c_str());
  ImGui::Combo("format", &st.format, formats, 3);
  ImGui::RadioButton("single column (3.5 in)", &st.column, 0);
  ImGui::SameLine();
  ImGui::RadioButton("double (7.16 in)", &st.column, 1);
  ImGui::SliderFloat("font (pt)", &st.font_pt, 6.0f, 12.0f, "%.1f");
  if (is_scene_kind(st.kind)) {
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
  } else if (st.kind == 2) {
    ImGui::Checkbox("95% intervals under each cell", &st.ci);
  } else if (st.kind == 3) {
    if (ctx.ref.empty())
      ImGui::TextDisabled("compares the first domain's two others (pick them in the compare panel)");
    else
      ImGui::TextDisabled("IPD(%s, %s) - IPD(%s, %s) per model (the compare panel's choice)", ctx.ref.c_str(),
                          ctx.a.c_str(), ctx.ref.c_str(), ctx.b.c_str());
  } else if (st.kind == 4) {
    ImGui::TextDisabled("model %s, every domain pair", ctx.model.c_str());
  } else if (st.kind == 6) {
    static const char* sorts[] = {"|diff|", "perf left", "perf right", "size"};  // GallerySort's order
    ImGui::SetNextItemWidth(ImGui::GetFontSize() * 8);
    ImGui::Combo("sort", &st.gallery_sort, sorts, 4);
    ImGui::SameLine();
    ImGui::SetNextItemWidth(ImGui::GetFontSize() * 6);
    ImGui::InputInt("pairs", &st.gallery_count);
    st.gallery_count = std::clamp(st.gallery_count, 1, 200);
    ImGui::TextDisabled("model %s, IPD(%s, %s), largest first", ctx.model.c_str(), ctx.left.c_str(), ctx.right.c_str());
  } else {
    ImGui::TextDisabled("model %s, IPD(%s, %s)", ctx.model.c_str(), ctx.left.c_str(), ctx.right.c_str());
  }
  keep_keyboard_after_enter(ImGui::InputText("folder", st.dir, sizeof st.dir, ImGuiInputTextFlags_EnterReturnsTrue));
  keep_keyboard_after_enter(
      ImGui::InputText("file name", st.name, sizeof st.name, ImGuiInputTextFlags_EnterReturnsTrue));
  const std::string path = (std::filesystem::path(st.dir) / (std::string(st.name) + exts[st.format])).string();
  ImGui::TextDisabled("writes %s", path.c_str());
  std::error_code ec;
  if (std::filesystem::exists(path, ec))  // said before it happens: an export replaces the file of that name
    ImGui::TextColored({1, 0.55f, 0, 1}, "replaces the file of that name");
  ImGui::TextDisabled("same figure as: ipd figure %s ... --conf %.2f%s (edits included)", kFigureKinds[st.kind],
                      ctx.conf_threshold, ctx.scene_stale ? " --skip-bad-lines" : "");
  if (ImGui::Button("Export") && st.name[0]) {
    out = export_request(st, ctx, path);
    st.open = false;
    ImGui::CloseCurrentPopup();
  }
  ImGui::SameLine();
  // ImGui 1.86 indexes keys by the backend's codes: Escape is GetKeyIndex(ImGuiKey_Escape), as the other dialogs ask.
  if (ImGui::Button("Cancel") || ImGui::IsKeyPressed(ImGui::GetKeyIndex(ImGuiKey_Escape))) {
    st.open = false;
    ImGui::CloseCurrentPopup();
  }
  ImGui::EndPopup();
  return out;
}

}  // namespace ipd::ui
