// The blink view (B): the right picture laid over the left one through the scene's registration affine, shown
// in turn or blended, with both domains' boxes in the same frame (blink_view.h).
#include <fmt/format.h>
#include <algorithm>
#include <cmath>

#include "ui/gui/pane_zoom.h"
#include "ui/gui/studio_layout.h"
#include "ui/gui/views.h"

namespace ipd::ui {

namespace {

// A box's or an outline's corners in the left picture's normalised coordinates (`map`: from its own picture).
std::vector<ImVec2> shape_points(const Box& b, const PaneAffine& map) {
  std::vector<ImVec2> q;
  if (b.outline) {
    q.reserve(b.outline->points.size());
    for (const Eigen::Vector2d& p : b.outline->points) q.push_back(map({float(p.x()), float(p.y())}));
  } else {
    q = {map({float(b.x0()), float(b.y0())}), map({float(b.x1()), float(b.y0())}), map({float(b.x1()), float(b.y1())}),
         map({float(b.x0()), float(b.y1())})};
  }
  return q;
}

// One side's boxes on screen: predictions dashed (the best-IoU ones thicker), GT solid; `wide` rocks thicker in
// their own colour. Returns how many GT boxes and predictions were drawn.
std::pair<int, int> draw_domain(ImDrawList* dl, const Placement& pl, const PaneAffine& map, const std::vector<Box>& gt,
                                const std::vector<Box>& predictions, const std::vector<int>& best, ImU32 gt_colour,
                                ImU32 prediction_colour, const std::vector<ImU32>& wide, const SideLayers& layers) {
  auto screen = [&](std::vector<ImVec2> q) {
    for (ImVec2& p : q) p = pl.to_screen(p.x, p.y);
    return q;
  };
  int n_gt = 0, n_pred = 0;
  if (layers.predictions) {
    std::vector<char> is_best(predictions.size(), 0);
    for (const int k : best)
      if (k >= 0 && k < static_cast<int>(is_best.size())) is_best[k] = 1;
    for (size_t k = 0; k < predictions.size(); ++k) {
      const ImU32 c = is_best[k] ? prediction_colour : (prediction_colour & ~IM_COL32_A_MASK) | IM_COL32(0, 0, 0, 150);
      draw_closed_path(dl, screen(shape_points(predictions[k], map)), c, is_best[k] ? 2.0f : 1.2f, true);
      ++n_pred;
    }
  }
  if (layers.gt) {
    for (size_t k = 0; k < gt.size(); ++k) {
      const ImU32 w = k < wide.size() ? wide[k] : 0;
      draw_closed_path(dl, screen(shape_points(gt[k], map)), w ? w : gt_colour, w ? 3.0f : 1.5f, false);
      ++n_gt;
    }
  }
  return {n_gt, n_pred};
}

}  // namespace

std::string blink_legend(const Session& s) {
  return fmt::format(
      "{0} GT (pink, solid), {0} predictions (red, dashed); {1} GT (green, solid), {1} predictions "
      "(blue, dashed); yellow: pairs set by hand",
      s.left_domain(), s.right_domain());
}

void draw_blink_view(const StudyView& v, UiState& ui, const Picture& left, const Picture& right, UiCommands& out) {
  const Session& s = *v.session;
  BlinkState& b = ui.blink;
  BlinkDrawn drawn;
  if (s.scenes().empty()) {
    ImGui::TextUnformatted("No scene is present in both domains.");
    return;
  }
  const int sc = ui.scene;
  // The toolbar: the mode, then its control, and the way back to the two panes.
  if (ImGui::RadioButton("blink", !b.overlay)) b.overlay = false;
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("one picture at a time: V flips, or set a rate");
  ImGui::SameLine();
  if (ImGui::RadioButton("overlay", b.overlay)) b.overlay = true;
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("the right picture over the left one at the opacity set");
  ImGui::SameLine();
  if (b.overlay) {
    ImGui::SetNextItemWidth(ImGui::GetFontSize() * 10);
    ImGui::SliderFloat("##opacity", &b.opacity, 0, 1, (s.right_domain() + " %.2f").c_str());
  } else {
    const std::string shown = blink_shows_right(ImGui::GetTime() - b.rate_started, b.flips_per_second, b.manual_right)
                                  ? s.right_domain()
                                  : s.left_domain();
    if (ImGui::Button(("flip (V): " + shown).c_str())) b.manual_right = !b.manual_right, b.flips_per_second = 0;
    ImGui::SameLine();
    ImGui::SetNextItemWidth(ImGui::GetFontSize() * 8);
    const float before = b.flips_per_second;
    ImGui::SliderFloat("flips/s", &b.flips_per_second, 0, 8, b.flips_per_second > 0 ? "%.1f" : "off (V)");
    if (b.flips_per_second != before) b.rate_started = ImGui::GetTime();
  }
  same_line_if_fits(button_width("panes (B)"));
  if (ImGui::Button("panes (B)")) b.on = false;
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("back to the two pictures side by side (B)");
  const bool pictures = left.texture || right.texture;
  // The legend strip: each domain's colour and line style, then what the pane can show.
  const ImVec2 strip0 = ImGui::GetCursorScreenPos();
  const float line = ImGui::GetTextLineHeight();
  {
    ImDrawList* sl = ImGui::GetWindowDrawList();
    float x = strip0.x;
    const float y = strip0.y + 0.5f * line;
    auto swatch = [&](ImU32 c, bool dashed, const std::string& text) {
      const float w = 1.6f * line;
      if (dashed)
        for (float t = 0; t < w; t += 7) sl->AddLine({x + t, y}, {x + std::min(w, t + 4), y}, c, 2);
      else
        sl->AddLine({x, y}, {x + w, y}, c, 2);
      x += w + 4;
      sl->AddText({x, strip0.y}, IM_COL32(230, 230, 230, 255), text.c_str());
      x += ImGui::CalcTextSize(text.c_str()).x + 12;
    };
    swatch(kPink, false, s.left_domain() + " GT");
    swatch(kRed, true, s.left_domain() + " pred.");
    swatch(kRightGt, false, s.right_domain() + " GT");
    swatch(kRightPrediction, true, s.right_domain() + " pred.");
    swatch(kHandPair, false, "set by hand");
    ImGui::Dummy({std::max(1.0f, x - strip0.x), line});
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", blink_legend(s).c_str());
  }
  if (!pictures) {
    text_coloured_wrapped_at_spaces({1, 0.78f, 0.47f, 1},
                                    "labels only: no pictures to blink; the boxes of both domains are laid over each "
                                    "other through the registration");
  }
  const ImVec2 p0 = ImGui::GetCursorScreenPos();
  const ImVec2 avail = ImGui::GetContentRegionAvail();
  const ImVec2 size{std::max(50.0f, avail.x), std::max(50.0f, avail.y)};
  ImGui::InvisibleButton("##blink", size);
  const bool hovered = ImGui::IsItemHovered();
  const int w = left.width > 0 ? left.width : right.width > 0 ? right.width : s.study().config.image_width;
  const int h = left.height > 0 ? left.height : right.height > 0 ? right.height : s.study().config.image_height;
  const ImVec2 mouse = ImGui::GetIO().MousePos;
  if (hovered) {
    if (const float wheel = ImGui::GetIO().MouseWheel; wheel != 0)
      zoom_at(b.view, std::pow(1.2f, wheel), mouse, p0, size, w, h);
    if (shortcuts_may_act() && ImGui::IsKeyPressed('F', false) && !ImGui::GetIO().KeyCtrl) b.view = CanvasView{};
  }
  const Placement pl = place(p0, size, w, h, b.view);
  if (hovered && ImGui::IsMouseDragging(ImGuiMouseButton_Left, 4.0f)) {
    b.view.pan.x -= ImGui::GetIO().MouseDelta.x / pl.size.x;
    b.view.pan.y -= ImGui::GetIO().MouseDelta.y / pl.size.y;
  }
  ImDrawList* dl = ImGui::GetWindowDrawList();
  dl->PushClipRect(p0, {p0.x + size.x, p0.y + size.y}, true);
  dl->AddRectFilled(p0, {p0.x + size.x, p0.y + size.y}, IM_COL32(20, 20, 24, 255));
  const PaneAffine left_from_right = towards_partner(s, sc, 1);
  const PaneAffine identity;
  const ImVec2 pic1{pl.origin.x + pl.size.x, pl.origin.y + pl.size.y};
  const float right_opacity =
      b.overlay
          ? std::clamp(b.opacity, 0.0f, 1.0f)
          : (blink_shows_right(ImGui::GetTime() - b.rate_started, b.flips_per_second, b.manual_right) ? 1.0f : 0.0f);
  if (!pictures) {
    dl->AddRectFilled(pl.origin, pic1, IM_COL32(70, 70, 76, 255));
  } else {
    if (left.texture && right_opacity < 1) dl->AddImage(left.texture, pl.origin, pic1);
    if (right.texture && right_opacity > 0) {
      const Quad q = warped_corners(left_from_right);
      const ImU32 tint = IM_COL32(255, 255, 255, static_cast<int>(std::lround(255 * right_opacity)));
      dl->AddImageQuad(right.texture, pl.to_screen(q.p[0].x, q.p[0].y), pl.to_screen(q.p[1].x, q.p[1].y),
                       pl.to_screen(q.p[2].x, q.p[2].y), pl.to_screen(q.p[3].x, q.p[3].y), {0, 0}, {1, 0}, {1, 1},
                       {0, 1}, tint);
    }
  }
  // Highlighted rocks: the pairs set by hand (those registration did not make), and the selected rock with its
  // partner.
  const SceneState& st = s.scenes()[sc];
  const auto& gt_l = s.gt(Side::kA, sc);
  const auto& gt_r = s.gt(Side::kB, sc);
  std::vector<ImU32> wide_l(gt_l.size(), 0), wide_r(gt_r.size(), 0);
  const RockPairs pairs = s.view_pairs(sc);
  RockPairs automatic = st.automatic.pairs;
  if (s.swapped())
    for (auto& p : automatic) std::swap(p.first, p.second);
  std::sort(automatic.begin(), automatic.end());
  std::vector<std::pair<ImVec2, ImVec2>> joins;
  for (const auto& [l, r] : pairs) {
    if (l < 0 || r < 0 || l >= (int)gt_l.size() || r >= (int)gt_r.size()) continue;
    const bool hand = st.edited && !std::binary_search(automatic.begin(), automatic.end(), std::make_pair(l, r));
    const bool selected = l == ui.selected_left || r == ui.selected_right;
    if (!hand && !selected) continue;
    const ImU32 c = selected ? kSelected : kHandPair;
    wide_l[l] = wide_r[r] = c;
    drawn.hand_pairs += hand;
    const ImVec2 cr = left_from_right({float(gt_r[r].cx), float(gt_r[r].cy)});
    joins.push_back({pl.to_screen(gt_l[l].cx, gt_l[l].cy), pl.to_screen(cr.x, cr.y)});
  }
  if (ui.selected_left >= 0 && ui.selected_left < (int)wide_l.size() && !wide_l[ui.selected_left])
    wide_l[ui.selected_left] = kSelected;
  const auto [gl, pl_n] = draw_domain(dl, pl, identity, gt_l, s.predictions(Side::kA, sc),
                                      s.performance(Side::kA, sc).best_prediction, kPink, kRed, wide_l, ui.layers);
  const auto [gr, pr_n] =
      draw_domain(dl, pl, left_from_right, gt_r, s.predictions(Side::kB, sc),
                  s.performance(Side::kB, sc).best_prediction, kRightGt, kRightPrediction, wide_r, ui.layers);
  for (const auto& [a, c] : joins) dl->AddLine(a, c, kHandPair, 2.0f);
  dl->PopClipRect();
  // A click selects the left rock under the cursor (U, X and C then act on it), as in the panes.
  if (hovered && ImGui::IsMouseReleased(ImGuiMouseButton_Left) &&
      ImGui::GetIO().MouseDragMaxDistanceSqr[ImGuiMouseButton_Left] < 16.0f) {
    ui.selected_left = -1;
    for (size_t k = 0; k < gt_l.size(); ++k) {
      const ImVec2 q0 = pl.to_screen(gt_l[k].x0(), gt_l[k].y0()), q1 = pl.to_screen(gt_l[k].x1(), gt_l[k].y1());
      if (mouse.x >= q0.x && mouse.x <= q1.x && mouse.y >= q0.y && mouse.y <= q1.y) ui.selected_left = int(k);
    }
  }
  drawn.drawn = true;
  drawn.pictures = pictures;
  drawn.right_opacity = right_opacity;
  drawn.gt_left = gl, drawn.gt_right = gr, drawn.predictions_left = pl_n, drawn.predictions_right = pr_n;
  drawn.pane = size;
  drawn.picture = {std::max(0.0f, std::min(pic1.x, p0.x + size.x) - std::max(pl.origin.x, p0.x)),
                   std::max(0.0f, std::min(pic1.y, p0.y + size.y) - std::max(pl.origin.y, p0.y))};
  ui.blink_drawn = drawn;
  ui.picture_px[0] = drawn.picture;  // --frame-stats: the one picture on screen
  ui.picture_px[1] = ImVec2{};
  (void)out;
}

}  // namespace ipd::ui
