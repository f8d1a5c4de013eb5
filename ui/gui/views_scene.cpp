// The scene in view: both pictures with their boxes (suspect pairs in orange, joined across the panes), the
// replayed hypothesis' sample, zoom at the cursor, and the pair table of the audit.
#include <fmt/format.h>
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "ui/gui/pane_zoom.h"
#include "ui/gui/studio_layout.h"
#include "ui/gui/views.h"

namespace ipd::ui {

int replay_step(const RegistrationReport& r, float position) {
  if (r.trace.steps.empty()) return -1;
  return std::clamp(static_cast<int>(position), 0, static_cast<int>(r.trace.steps.size()) - 1);
}

const char* iou_word(const Session& s) { return s.study().config.task == Task::kSegment ? "mask IoU" : "IoU"; }

namespace {

// The replayed step's sample on one view side (the replay is in the domain pair's A/B orientation).
std::vector<int> replay_sample(const StudyView& v, const UiState& ui, Side side) {
  if (!v.rerun || !ui.replay.playing) return {};
  const int k = replay_step(*v.rerun, ui.replay.position);
  if (k < 0 || ui.replay.position >= v.rerun->trace.steps.size()) return {};
  const TraceStep& st = v.rerun->trace.steps[k];
  const bool side_is_a = (side == Side::kA) != v.session->swapped();
  return side_is_a ? st.a_sample : st.b_sample;
}

}  // namespace

PaneAffine towards_partner(const Session& s, int scene, int k) {
  const Affine2& m = s.scenes()[scene].automatic.registration.affine;
  PaneAffine a;
  for (int i = 0; i < 6; ++i) a.m[i] = m(i / 3, i % 3);
  const bool from_a = (k == 0) != s.swapped();
  return from_a ? a : a.inverse();
}

SideInput side_input(const Session& s, const UiState& ui, Side side, const Picture& pic) {
  SideInput in;
  const int sc = ui.scene;
  in.texture = pic.texture;
  in.image_w = pic.width > 0 ? pic.width : s.study().config.image_width;
  in.image_h = pic.height > 0 ? pic.height : s.study().config.image_height;
  in.placeholder = pic.placeholder;
  in.gt = &s.gt(side, sc);
  in.predictions = &s.predictions(side, sc);
  in.best_prediction = s.performance(side, sc).best_prediction;
  const RockPairs pairs = s.view_pairs(sc);
  in.number = pair_numbers(pairs, in.gt->size(), side == Side::kA);
  in.excluded.assign(in.gt->size(), 0);
  for (size_t k = 0; k < in.gt->size(); ++k) in.excluded[k] = s.excluded(side, sc, static_cast<int>(k));
  in.suspect = s.suspect_rocks(side, sc);
  in.caption = side == Side::kA ? s.left_domain() : s.right_domain();
  // Hovering a rock highlights its partner on the other side.
  const int other_hover = side == Side::kA ? ui.hover_right : ui.hover_left;
  const int own_hover = side == Side::kA ? ui.hover_left : ui.hover_right;
  in.highlight = own_hover;
  for (const auto& [l, r] : pairs) {
    if (side == Side::kA && r == other_hover) in.highlight = l;
    if (side == Side::kB && l == other_hover) in.highlight = r;
  }
  in.selected = side == Side::kA ? ui.selected_left : ui.selected_right;
  return in;
}

float scene_toolbar_width() {
  const ImGuiStyle& st = ImGui::GetStyle();
  const float box = ImGui::GetFrameHeight() + st.ItemInnerSpacing.x;
  float w = -st.ItemSpacing.x;
  for (const char* c : {"GT", "pred.", "numbers", "conf.", "sync zoom"})
    w += box + ImGui::CalcTextSize(c).x + st.ItemSpacing.x;
  for (const char* b : {"unpair (U)", "exclude (X)", "reset to automatic"}) w += button_width(b) + st.ItemSpacing.x;
  return w;
}

void draw_side_by_side(const StudyView& v, UiState& ui, const Picture& left, const Picture& right, UiCommands& out) {
  const Session& s = *v.session;
  if (s.scenes().empty()) {
    ImGui::TextUnformatted("No scene is present in both domains.");
    return;
  }
  if (ui.blink.on) return draw_blink_view(v, ui, left, right, out);
  // The toolbar wraps onto a second line in a narrow window rather than running off its edge.
  const float box = ImGui::GetFrameHeight() + ImGui::GetStyle().ItemInnerSpacing.x;
  ImGui::Checkbox("GT", &ui.layers.gt);
  // Short labels keep the toolbar on one line above the pictures (the View menu and the tooltips say them whole).
  same_line_if_fits(box + ImGui::CalcTextSize("pred.").x);
  ImGui::Checkbox("pred.", &ui.layers.predictions);
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("predictions (red, dashed; the best-IoU one emphasised)");
  same_line_if_fits(box + ImGui::CalcTextSize("numbers").x);
  ImGui::Checkbox("numbers", &ui.layers.indices);
  same_line_if_fits(box + ImGui::CalcTextSize("conf.").x);
  ImGui::Checkbox("conf.", &ui.layers.confidences);
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("the predictions' confidences");
  same_line_if_fits(box + ImGui::CalcTextSize("sync zoom").x);
  ImGui::Checkbox("sync zoom", &ui.sync_views);
  same_line_if_fits(button_width("unpair (U)"));
  if (ImGui::Button("unpair (U)") && (ui.selected_left >= 0 || ui.selected_right >= 0))
    out.edits.push_back(ui.selected_left >= 0 ? Edit::unpair(Side::kA, ui.selected_left)
                                              : Edit::unpair(Side::kB, ui.selected_right));
  same_line_if_fits(button_width("exclude (X)"));
  if (ImGui::Button("exclude (X)") && (ui.selected_left >= 0 || ui.selected_right >= 0))
    out.edits.push_back(Edit::toggle_exclude(ui.selected_left >= 0 ? Side::kA : Side::kB,
                                             ui.selected_left >= 0 ? ui.selected_left : ui.selected_right));
  same_line_if_fits(button_width("reset to automatic"));
  // A scene whose hand pairs file no longer matches its labels: reset deletes that file, which undo does not
  // bring back, so it asks first. Elsewhere reset is an ordinary edit (undo restores the hand pairs).
  const auto [stale_file, stale_why] = s.stale_pairs(ui.scene);
  const bool stale = !stale_file.empty();
  if (ImGui::Button("reset to automatic")) {
    if (!stale)
      out.edits.push_back(Edit::reset());
    else
      ImGui::OpenPopup("Discard the hand pairs?");
  }
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("%s",
                      !stale ? "Use registration's pairs for this scene (undo brings the hand pairs back)"
                      : s.read_only()
                          ? "Use registration's pairs for this scene (read-only: its stale pairs file stays on disk)"
                          : "Delete this scene's hand pairs file, which no longer matches its labels");
  if (ImGui::BeginPopupModal("Discard the hand pairs?", nullptr, ImGuiWindowFlags_AlwaysAutoResize)) {
    ImGui::PushTextWrapPos(ImGui::GetFontSize() * 36);
    // A read-only window deletes nothing: the reset is kept in this window only.
    const std::string question =
        s.read_only() ? "Use registration's pairs for this scene? This window is read-only (" + s.read_only_reason() +
                            "): " + stale_file + " stays on disk, and the reset is kept in this window only."
                      : "Delete " + stale_file +
                            " and use registration's pairs for this scene? Undo does not bring the file back.";
    ImGui::TextUnformatted(question.c_str());
    ImGui::PopTextWrapPos();
    if (ImGui::Button(s.read_only() ? "Use registration's pairs" : "Delete the file")) {
      out.edits.push_back(Edit::reset());
      ImGui::CloseCurrentPopup();
    }
    ImGui::SameLine();
    // ImGui 1.86 indexes keys by the backend's codes: Escape is GetKeyIndex(ImGuiKey_Escape), as the other dialogs ask.
    if (ImGui::Button("Cancel") || ImGui::IsKeyPressed(ImGui::GetKeyIndex(ImGuiKey_Escape))) ImGui::CloseCurrentPopup();
    ImGui::EndPopup();
  }
  // Only when it fits: the Help menu says the same.
  const float right_edge = ImGui::GetWindowPos().x + ImGui::GetWindowContentRegionMax().x;
  if (ImGui::GetItemRectMax().x + ImGui::GetStyle().ItemSpacing.x + ImGui::CalcTextSize("F1: help").x <= right_edge) {
    ImGui::SameLine();
    ImGui::TextDisabled("F1: help");
  }
  if (stale) {
    // Short above the pictures (five wrapped lines at 1280 px left them thumbnail-sized); the whole on hover.
    ImGui::BeginGroup();  // one item for the hover, however many lines it wraps to
    text_coloured_wrapped_at_spaces(
        {1, 0.55f, 0, 1},
        "Hand pairs not applied: the pairs file no longer matches the labels; registration's "
        "pairs are shown and edits are refused (hover for why and the ways out).");
    ImGui::EndGroup();
    if (ImGui::IsItemHovered()) {
      ImGui::BeginTooltip();
      ImGui::PushTextWrapPos(ImGui::GetFontSize() * 40);
      ImGui::TextUnformatted((stale_file + ": " + stale_why +
                              ".\n\nThe scene shows registration's pairs, and edits are refused so that the file is "
                              "not overwritten. To keep the hand pairs, correct the label file and open the study "
                              "again; to discard them, \"reset to automatic\".")
                                 .c_str());
      ImGui::PopTextWrapPos();
      ImGui::EndTooltip();
    }
  }

  // The panes' captions (domain names) and notices ("no picture ... (labels only)") sit in a strip above
  // the pictures, never over rocks or their numbers. The pictures go side by side or stacked, whichever shows
  // them larger in the space left (picture_panes).
  const float line = ImGui::GetTextLineHeightWithSpacing();
  const float gap = 6;
  const ImVec2 avail0 = ImGui::GetContentRegionAvail();
  const int iw = left.width > 0 ? left.width : s.study().config.image_width;
  const int ih = left.height > 0 ? left.height : s.study().config.image_height;
  const float aspect = iw > 0 && ih > 0 ? float(iw) / ih : 1.6f;
  const float item_gap = ImGui::GetStyle().ItemSpacing.y;
  PicturePanes panes = picture_panes(avail0.x, avail0.y - 2 * item_gap, aspect, gap, line);
  const float spacer = ImGui::CalcTextSize("  ").x;
  auto notice = [](const Picture& pic) { return !pic.texture && !pic.placeholder.empty(); };
  // A notice that does not fit beside its caption goes under it, wrapped at spaces to the pane's width.
  auto measure = [](const std::string& t) { return ImGui::CalcTextSize(t.c_str()).x; };
  bool below = false;
  size_t notice_lines = 0;
  for (int k = 0; k < 2; ++k) {
    const Picture& pic = k == 0 ? left : right;
    const std::string caption = k == 0 ? s.left_domain() : s.right_domain();
    if (!notice(pic)) continue;
    if (measure(caption) + spacer + measure(pic.placeholder) > panes.pane_w) below = true;
    notice_lines = std::max(notice_lines, wrap_at_spaces(pic.placeholder, panes.pane_w, measure).size());
  }
  const float strip = below ? (1 + notice_lines) * line : line;
  if (strip > line) panes = picture_panes(avail0.x, avail0.y - 2 * item_gap, aspect, gap, strip);
  const float pane_w = panes.pane_w;
  // One pane's caption strip at `at`.
  auto draw_strip = [&](int k, ImVec2 at) {
    const Picture& pic = k == 0 ? left : right;
    ImDrawList* sl = ImGui::GetWindowDrawList();
    sl->PushClipRect(at, {at.x + pane_w, at.y + strip}, true);
    const std::string caption = k == 0 ? s.left_domain() : s.right_domain();
    sl->AddText(at, IM_COL32(255, 255, 255, 255), caption.c_str());
    if (notice(pic) && !below) {
      sl->AddText({at.x + measure(caption) + spacer, at.y}, IM_COL32(255, 200, 120, 255), pic.placeholder.c_str());
    } else if (notice(pic)) {
      float y = at.y + line;
      for (const std::string& l : wrap_at_spaces(pic.placeholder, pane_w, measure))
        sl->AddText({at.x, y}, IM_COL32(255, 200, 120, 255), l.c_str()), y += line;
    }
    sl->PopClipRect();
  };
  if (!panes.stacked) {
    const ImVec2 strip0 = ImGui::GetCursorScreenPos();
    for (int k = 0; k < 2; ++k) draw_strip(k, {strip0.x + k * (pane_w + gap), strip0.y});
    ImGui::Dummy({2 * pane_w + gap, strip - item_gap});
  }
  // As tall as the fitted picture, so it sits right under its caption (no band between them in the focus view).
  const ImVec2 size{pane_w, std::max(50.0f, std::min(panes.pane_h, std::ceil(panes.picture_h)))};
  ImDrawList* dl = ImGui::GetWindowDrawList();
  const ImVec2 mouse = ImGui::GetIO().MousePos;
  Placement placed[2];
  SideInput inputs[2];
  ImVec2 origin[2];
  for (int k = 0; k < 2; ++k) {
    const Side side = k == 0 ? Side::kA : Side::kB;
    if (panes.stacked) {
      draw_strip(k, ImGui::GetCursorScreenPos());
      ImGui::Dummy({pane_w, strip - item_gap});
    }
    const ImVec2 p0 = ImGui::GetCursorScreenPos();
    origin[k] = p0;
    ImGui::InvisibleButton(k == 0 ? "##left" : "##right", size);
    const bool hovered_area = ImGui::IsItemHovered();
    CanvasView& view = k == 0 ? ui.left_view : ui.right_view;
    SideInput& in = inputs[k];
    in = side_input(s, ui, side, k == 0 ? left : right);
    in.sample = replay_sample(v, ui, side);
    in.fill_background = false;
    in.min_box_px_for_confidence = 2.2f * ImGui::GetFontSize();
    // Drawn in the strip above instead (the caption stays in `in` for the tooltips).
    const std::string caption = std::move(in.caption), placeholder = std::move(in.placeholder);
    in.caption.clear(), in.placeholder.clear();
    const int hit = draw_side(dl, p0, size, view, in, ui.layers, mouse);
    in.caption = caption, in.placeholder = placeholder;
    placed[k] = place(p0, size, in.image_w, in.image_h, view);
    // The picture's part on screen (clipped to its pane when zoomed in), for --frame-stats' picture_px.
    ui.picture_px[k] = {std::max(0.0f, std::min(placed[k].origin.x + placed[k].size.x, p0.x + size.x) -
                                           std::max(placed[k].origin.x, p0.x)),
                        std::max(0.0f, std::min(placed[k].origin.y + placed[k].size.y, p0.y + size.y) -
                                           std::max(placed[k].origin.y, p0.y))};
    int& hover = k == 0 ? ui.hover_left : ui.hover_right;
    hover = hovered_area ? hit : -1;
    if (hovered_area) {
      const CanvasView before = view;
      const float wheel = ImGui::GetIO().MouseWheel;
      if (wheel != 0) zoom_at(view, std::pow(1.2f, wheel), mouse, p0, size, in.image_w, in.image_h);
      if (shortcuts_may_act() && ImGui::IsKeyPressed('F', false) && !ImGui::GetIO().KeyCtrl) view = CanvasView{};
      if (shortcuts_may_act() && ImGui::IsKeyPressed('1', false) && in.image_w > 0) {
        const float fit_w = place(p0, size, in.image_w, in.image_h, CanvasView{}).size.x;
        zoom_at(view, in.image_w / fit_w / view.zoom, mouse, p0, size, in.image_w, in.image_h);
      }
      if (ImGui::IsMouseDragging(ImGuiMouseButton_Left, 4.0f)) {
        const ImVec2 d = ImGui::GetIO().MouseDelta;
        view.pan.x -= d.x / placed[k].size.x;
        view.pan.y -= d.y / placed[k].size.y;
      } else if (ImGui::IsMouseReleased(ImGuiMouseButton_Left) &&
                 ImGui::GetIO().MouseDragMaxDistanceSqr[ImGuiMouseButton_Left] < 16.0f) {
        int& sel = k == 0 ? ui.selected_left : ui.selected_right;
        sel = hit;
        if (ui.selected_left >= 0 && ui.selected_right >= 0) {
          out.edits.push_back(Edit::pair(ui.selected_left, ui.selected_right));
          ui.selected_right = -1;  // the left rock stays selected: sync zoom follows it to its new partner
        }
      }
      // Only when this picture's view changed: following the cursor as it merely moves would slide the other
      // picture by the registration's offset at every hover.
      const bool moved = view.zoom != before.zoom || view.pan.x != before.pan.x || view.pan.y != before.pan.y;
      CanvasView& partner = k == 0 ? ui.right_view : ui.left_view;
      if (ui.sync_views && moved)
        partner = view.zoom == 1.0f && view.pan.x == 0 && view.pan.y == 0
                      ? CanvasView{}  // back to the whole picture: so is the other
                      : partner_view(view, {mouse.x - p0.x, mouse.y - p0.y}, size, in.image_w, in.image_h,
                                     towards_partner(s, ui.scene, k));
      if (hit >= 0) {
        const auto& pv_self = s.performance(side, ui.scene).value;
        ImGui::BeginTooltip();
        const char* iou = iou_word(s);
        ImGui::Text("%s rock %d: %s %.3f", in.caption.c_str(), hit + 1, iou,
                    hit < (int)pv_self.size() ? pv_self[hit] : 0.0);
        for (const auto& [l, r] : s.view_pairs(ui.scene)) {
          if ((k == 0 ? l : r) != hit) continue;
          const int other = k == 0 ? r : l;
          const auto& pv_other = s.performance(k == 0 ? Side::kB : Side::kA, ui.scene).value;
          const double o = other < (int)pv_other.size() ? pv_other[other] : 0.0;
          ImGui::Text("pair %d; partner: %s rock %d: %s %.3f", l + 1,
                      (k == 0 ? s.right_domain() : s.left_domain()).c_str(), other + 1, iou, o);
          ImGui::Text("|difference| %.3f", std::abs(pv_self[hit] - o));
          for (const auto& p : s.audit(ui.scene).pairs) {
            const int pl = s.swapped() ? p.b : p.a, pr = s.swapped() ? p.a : p.b;
            if (pl != l || pr != r) continue;
            ImGui::Text("residual %.1f px, aligned IoU %.2f, size ratio %.2f", p.residual_px, p.aligned_iou,
                        p.size_ratio);
            if (p.suspect) ImGui::TextColored({1, 0.55f, 0, 1}, "suspect: %s", p.why.c_str());
            if (p.checked) ImGui::TextColored({0.5f, 0.9f, 0.5f, 1}, "checked, correct (C)");
          }
        }
        if (in.excluded[hit]) ImGui::TextUnformatted("excluded from the IPD");
        ImGui::EndTooltip();
      }
    }
    if (k == 0 && !panes.stacked) ImGui::SameLine(0, gap);
  }
  // Lines across the panes: suspect pairs, and the replayed hypothesis' sample (partners in order).
  const ImVec2 clip0 = origin[0], clip1{origin[1].x + size.x, origin[1].y + size.y};
  dl->PushClipRect(clip0, clip1, true);
  auto centre = [&](int k, int rock) {
    const Box& b = (*inputs[k].gt)[rock];
    return placed[k].to_screen(b.cx, b.cy);
  };
  for (const auto& [l, r] : s.view_pairs(ui.scene))
    if (l < (int)inputs[0].suspect.size() && inputs[0].suspect[l] && r < (int)inputs[1].gt->size())
      dl->AddLine(centre(0, l), centre(1, r), kSuspect, 2.0f);
  for (size_t k = 0; k < std::min(inputs[0].sample.size(), inputs[1].sample.size()); ++k) {
    const int l = inputs[0].sample[k], r = inputs[1].sample[k];
    if (l >= 0 && l < (int)inputs[0].gt->size() && r >= 0 && r < (int)inputs[1].gt->size())
      dl->AddLine(centre(0, l), centre(1, r), kTriple, 2.0f);
  }
  dl->PopClipRect();
}

void draw_pair_table(const StudyView& v, UiState& ui, UiCommands& out) {
  const Session& s = *v.session;
  if (s.scenes().empty()) return;
  const auto& pl = s.performance(Side::kA, ui.scene).value;
  const auto& pr = s.performance(Side::kB, ui.scene).value;
  struct Row {
    int l, r;
    double a, b;
    const PairAudit* audit;
    bool excluded;  // out of the IPD: listed last, its |diff| not shown as counted
  };
  const SceneAudit& audit = s.audit(ui.scene);
  const PairAuditIndex audit_of(audit);
  std::vector<Row> rows;
  for (const auto& [l, r] : s.view_pairs(ui.scene)) {
    Row row{l,
            r,
            l < (int)pl.size() ? pl[l] : 0.0,
            r < (int)pr.size() ? pr[r] : 0.0,
            s.swapped() ? audit_of.find(r, l) : audit_of.find(l, r),
            s.excluded(Side::kA, ui.scene, l) || s.excluded(Side::kB, ui.scene, r)};
    rows.push_back(row);
  }
  // Suspect pairs first, then by |difference|: what an audit looks at.
  // Excluded pairs last: they don't count.
  std::stable_sort(rows.begin(), rows.end(), [](const Row& x, const Row& y) {
    if (x.excluded != y.excluded) return y.excluded;
    const bool sx = x.audit && x.audit->suspect, sy = y.audit && y.audit->suspect;
    if (sx != sy) return sx;
    return std::abs(x.a - x.b) > std::abs(y.a - y.b);
  });
  const long excluded_rows = std::count_if(rows.begin(), rows.end(), [](const Row& r) { return r.excluded; });
  text_wrapped_at_spaces(
      counted(long(rows.size()) - excluded_rows, "pair") + " counted (" + thousands(excluded_rows) + " excluded), " +
      (audit.waits_for_registration
           ? std::string("no audit yet: it needs the scene's registration, which is being computed")
           : thousands(audit.suspects) + " suspect; typical residual " + fixed(audit.typical_residual_px, 1) + " px"));
  const float table_h =
      std::max(60.0f, ImGui::GetContentRegionAvail().y - 2.4f * ImGui::GetTextLineHeightWithSpacing());
  const std::string partner = "its partner in " + s.right_domain();
  const bool masks = s.study().config.task == Task::kSegment;
  const std::string iou = iou_word(s);
  const std::string iou_l = iou + " of the left rock (" + s.left_domain() + ") with its best prediction";
  const std::string iou_r = iou + " of the right rock (" + s.right_domain() + ") with its best prediction";
  const std::string diff = "|" + iou + " L - " + iou + " R|: the pair's share of the IPD";
  const std::vector<TextColumn> columns = {
      {"pair", "99 x", "the pair, named by its left rock (x: excluded)"},
      {"R#", "99", partner.c_str()},
      {masks ? "mIoU L" : "IoU L", "0.000", iou_l.c_str()},
      {masks ? "mIoU R" : "IoU R", "0.000", iou_r.c_str()},
      {"|diff|", "0.000", diff.c_str()},
      {"res px", "999.9", "residual after the registration affine, pixels"},
      {"size", "0.00", "box-size ratio, aligned left / right (suspect outside 0.5-2)"}};
  // No sort arrow to leave room for (narrower, so more columns fit). A pane narrower than the columns shows them
  // in a smaller font, then scrolls (ScrollX) instead of cutting the last ones off.
  const float scale =
      table_font_scale(columns, /*sortable=*/false, ImGui::GetStyle().ScrollbarSize, ImGui::GetContentRegionAvail().x);
  ImGui::SetWindowFontScale(scale);
  if (ImGui::BeginTable(
          scaled_table_id("pairs", scale).c_str(), 7,
          ImGuiTableFlags_RowBg | ImGuiTableFlags_ScrollY | ImGuiTableFlags_ScrollX | ImGuiTableFlags_BordersInnerV,
          ImVec2(0, table_h))) {
    ImGui::TableSetupScrollFreeze(1, 1);  // the pair stays in view when the table scrolls sideways
    setup_text_columns(columns, /*sortable=*/false);
    for (const auto& row : rows) {
      ImGui::TableNextRow();
      ImGui::TableNextColumn();
      const bool suspect = row.audit && row.audit->suspect;
      const bool checked = row.audit && row.audit->checked;  // judged correct by hand: green, not orange
      const bool excl = row.excluded;
      char label[48];
      std::snprintf(label, sizeof label, "%d%s##%d", row.l + 1, excl ? " x" : "", row.l);
      if (suspect || checked)
        ImGui::PushStyleColor(ImGuiCol_Text, suspect ? ImVec4(1, 0.55f, 0, 1) : ImVec4(0.5f, 0.9f, 0.5f, 1));
      if (ImGui::Selectable(label, ui.selected_left == row.l, ImGuiSelectableFlags_SpanAllColumns)) {
        // Centre both pictures on the pair.
        const Box& bl = s.gt(Side::kA, ui.scene)[row.l];
        const Box& br = s.gt(Side::kB, ui.scene)[row.r];
        ui.left_view = {std::max(ui.left_view.zoom, 3.0f), {float(bl.cx - 0.5), float(bl.cy - 0.5)}};
        ui.right_view = {ui.left_view.zoom, {float(br.cx - 0.5), float(br.cy - 0.5)}};
        ui.selected_left = row.l;
      }
      if (suspect || checked) ImGui::PopStyleColor();
      if (ImGui::IsItemHovered()) {
        ui.hover_left = row.l;
        if (suspect) ImGui::SetTooltip("suspect: %s (C: checked, correct)", row.audit->why.c_str());
        if (checked)
          ImGui::SetTooltip("checked, correct%s%s",
                            row.audit->why.empty() ? "" : "; the audit found: ", row.audit->why.c_str());
      }
      ImGui::TableNextColumn();
      ImGui::Text("%d", row.r + 1);
      ImGui::TableNextColumn();
      ImGui::Text("%.3f", row.a);
      ImGui::TableNextColumn();
      ImGui::Text("%.3f", row.b);
      ImGui::TableNextColumn();
      if (row.excluded)
        ImGui::TextDisabled("excl.");
      else
        ImGui::Text("%.3f", std::abs(row.a - row.b));
      ImGui::TableNextColumn();
      if (row.audit) ImGui::Text("%.1f", row.audit->residual_px);
      ImGui::TableNextColumn();
      if (row.audit) ImGui::Text("%.2f", row.audit->size_ratio);
    }
    ImGui::EndTable();
  }
  ImGui::SetWindowFontScale(1.0f);
  // Rocks without a partner, with their own IoU: collapsible, one line per rock.
  for (int k = 0; k < 2; ++k) {
    const Side side = k == 0 ? Side::kA : Side::kB;
    const auto& gt = s.gt(side, ui.scene);
    const auto& pv = k == 0 ? pl : pr;
    std::vector<char> paired(gt.size(), 0);
    for (const auto& [l, r] : s.view_pairs(ui.scene)) {
      const int idx = k == 0 ? l : r;
      if (idx >= 0 && idx < static_cast<int>(paired.size())) paired[idx] = 1;
    }
    // As the scene header counts (scene_contribution): an excluded rock is out of the IPD, not unpaired.
    int n = 0, excluded = 0;
    for (size_t i = 0; i < gt.size(); ++i)
      if (!paired[i]) ++(s.excluded(side, ui.scene, static_cast<int>(i)) ? excluded : n);
    char header[128];
    std::snprintf(header, sizeof header, "unpaired %s: %d%s###unp%d",
                  (k == 0 ? s.left_domain() : s.right_domain()).c_str(), n,
                  excluded > 0 ? fmt::format(" (+{} excluded)", excluded).c_str() : "", k);
    if (n + excluded > 0 && ImGui::CollapsingHeader(header)) {
      for (size_t i = 0; i < gt.size(); ++i) {
        if (paired[i]) continue;
        ImGui::BulletText("rock %zu: %s %.2f%s", i + 1, iou_word(s), i < pv.size() ? pv[i] : 0.0,
                          s.excluded(side, ui.scene, static_cast<int>(i)) ? "  (excluded)" : "");
      }
    } else if (n + excluded == 0) {
      ImGui::TextDisabled("unpaired %s: none", (k == 0 ? s.left_domain() : s.right_domain()).c_str());
    }
  }
  (void)out;
}

}  // namespace ipd::ui
