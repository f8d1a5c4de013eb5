#include "ui/gui/rock_view.h"

#include <fmt/format.h>
#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "ui/gui/studio_layout.h"

namespace ipd::ui {
namespace {

constexpr PairAxis kAxes[] = {PairAxis::kPerfA, PairAxis::kPerfB, PairAxis::kAbsDiff, PairAxis::kSize,
                              PairAxis::kX,     PairAxis::kY,     PairAxis::kConfA,   PairAxis::kConfB};
// Okabe-Ito blue and orange: told apart with every common colour-vision deficiency.
const ImU32 kPoint = IM_COL32(0, 114, 178, 255), kSelected = IM_COL32(230, 159, 0, 255);

// An axis's range: [0, 1] for the values that live there, [0, largest] for size.
std::pair<double, double> axis_range(const std::vector<RockPairPoint>& points, PairAxis axis) {
  if (axis != PairAxis::kSize) return {0, 1};
  double hi = 0;
  for (const auto& p : points) hi = std::max(hi, p.size);
  return {0, hi > 0 ? hi : 1};
}

struct Plot {
  ImVec2 p0, p1;  // screen rectangle
  double x0, x1, y0, y1;
  ImVec2 to_screen(double x, double y) const {
    return {float(p0.x + (x - x0) / (x1 - x0) * (p1.x - p0.x)), float(p1.y - (y - y0) / (y1 - y0) * (p1.y - p0.y))};
  }
  double data_x(float sx) const { return x0 + (sx - p0.x) / (p1.x - p0.x) * (x1 - x0); }
  double data_y(float sy) const { return y0 + (p1.y - sy) / (p1.y - p0.y) * (y1 - y0); }
};

std::string pair_line(const Session& s, const RockPairPoint& p) {
  return fmt::format("{}: rock {} ({}) | rock {} ({}), perf {:.3f} | {:.3f}, |diff| {:.3f}", s.scenes()[p.scene].stem,
                     p.rock_a + 1, s.left_domain(), p.rock_b + 1, s.right_domain(), p.perf_a, p.perf_b, p.abs_diff);
}

void go_to(const RockPairPoint& p, UiCommands& out) {
  out.goto_pair_scene = p.scene;
  out.goto_pair_left = p.rock_a;
  out.goto_pair_right = p.rock_b;
}

bool axis_combo(const char* label, int& axis) {
  bool changed = false;
  ImGui::SetNextItemWidth(110);
  if (ImGui::BeginCombo(label, axis_name(kAxes[axis]))) {
    for (int k = 0; k < static_cast<int>(std::size(kAxes)); ++k)
      if (ImGui::Selectable(axis_name(kAxes[k]), k == axis)) axis = k, changed = true;
    ImGui::EndCombo();
  }
  return changed;
}

// Every point once per pixel (a dense cloud costs what the plot's area costs); the hovered point's index.
int draw_points(const Plot& plot, RockViewState& st, PairAxis ax, PairAxis ay, ImDrawList* dl) {
  const int w = std::max(1, int(plot.p1.x - plot.p0.x) + 1), h = std::max(1, int(plot.p1.y - plot.p0.y) + 1);
  st.drawn.assign(static_cast<size_t>(w) * h, 0);
  const ImVec2 mouse = ImGui::GetMousePos();
  int hovered = -1;
  float best = 36;  // within 6 px
  const bool box = st.has_box && st.box_x == static_cast<int>(ax) && st.box_y == static_cast<int>(ay);
  for (size_t i = 0; i < st.points.size(); ++i) {
    const double x = axis_value(st.points[i], ax), y = axis_value(st.points[i], ay);
    if (!std::isfinite(x) || !std::isfinite(y)) continue;  // no confidence: not on a confidence axis
    const ImVec2 q = plot.to_screen(x, y);
    const float d = (q.x - mouse.x) * (q.x - mouse.x) + (q.y - mouse.y) * (q.y - mouse.y);
    if (d < best) best = d, hovered = static_cast<int>(i);
    const bool in = box && x >= std::min(st.bx0, st.bx1) && x <= std::max(st.bx0, st.bx1) &&
                    y >= std::min(st.by0, st.by1) && y <= std::max(st.by0, st.by1);
    const int px = std::clamp(int(q.x - plot.p0.x), 0, w - 1), py = std::clamp(int(q.y - plot.p0.y), 0, h - 1);
    unsigned char& cell = st.drawn[static_cast<size_t>(py) * w + px];
    const unsigned char mark = in ? 2 : 1;
    if (cell >= mark) continue;
    cell = mark;
    dl->AddRectFilled({q.x - 1.5f, q.y - 1.5f}, {q.x + 1.5f, q.y + 1.5f}, in ? kSelected : kPoint);
  }
  return hovered;
}

// Mouse: a press starts a box, a release under 4 px away is a click on the hovered point.
void handle_mouse(const Session& s, const Plot& plot, int hovered, PairAxis ax, PairAxis ay, RockViewState& st,
                  UiState& ui, UiCommands& out) {
  ImDrawList* dl = ImGui::GetWindowDrawList();
  if (ImGui::IsItemHovered() && ImGui::IsMouseClicked(0)) st.dragging = true, st.drag_from = ImGui::GetMousePos();
  if (!st.dragging) return;
  const ImVec2 m = ImGui::GetMousePos();
  dl->AddRect(st.drag_from, m, kSelected);
  if (ImGui::IsMouseDown(0)) return;
  st.dragging = false;
  if (std::abs(m.x - st.drag_from.x) < 4 && std::abs(m.y - st.drag_from.y) < 4) {
    if (hovered >= 0) go_to(st.points[hovered], out);
    return;
  }
  st.has_box = true;
  st.box_x = static_cast<int>(ax), st.box_y = static_cast<int>(ay);
  st.bx0 = plot.data_x(st.drag_from.x), st.bx1 = plot.data_x(m.x);
  st.by0 = plot.data_y(st.drag_from.y), st.by1 = plot.data_y(m.y);
  apply_pair_selection(s, select_in_box(st.points, ax, ay, st.bx0, st.by0, st.bx1, st.by1), ui);
}

void draw_scatter(const Session& s, RockViewState& st, UiState& ui, UiCommands& out) {
  axis_combo("x##rockx", st.x_axis);
  ImGui::SameLine();
  axis_combo("y##rocky", st.y_axis);
  ImGui::SameLine();
  ImGui::Checkbox("current scene only", &st.current_scene);
  ImGui::TextDisabled("%s of %s: drag a box to filter the scene list, click a point to see its pair",
                      counted(static_cast<long>(st.points.size()), "pair").c_str(),
                      st.current_scene ? "this scene" : "the listed scenes");
  const PairAxis ax = kAxes[st.x_axis], ay = kAxes[st.y_axis];
  const ImVec2 avail = ImGui::GetContentRegionAvail();
  const float line = ImGui::GetTextLineHeight();
  const ImVec2 origin = ImGui::GetCursorScreenPos();
  const ImVec2 size{std::max(80.0f, avail.x), std::max(80.0f, avail.y)};
  ImGui::InvisibleButton("##rockplot", size);
  const auto [x0, x1] = axis_range(st.points, ax);
  const auto [y0, y1] = axis_range(st.points, ay);
  Plot plot{{origin.x + 4 * line, origin.y + 4}, {origin.x + size.x - 8, origin.y + size.y - 2 * line}, x0, x1, y0, y1};
  ImDrawList* dl = ImGui::GetWindowDrawList();
  dl->AddRect(plot.p0, plot.p1, IM_COL32(140, 140, 140, 255));
  const ImU32 text = ImGui::GetColorU32(ImGuiCol_Text);
  dl->AddText({plot.p0.x, plot.p1.y + 2}, text, fmt::format("{:g}", x0).c_str());
  const std::string xhi = fmt::format("{:g}", x1);
  dl->AddText({plot.p1.x - ImGui::CalcTextSize(xhi.c_str()).x, plot.p1.y + 2}, text, xhi.c_str());
  dl->AddText({(plot.p0.x + plot.p1.x) / 2, plot.p1.y + 2}, text, axis_name(ax));
  dl->AddText({origin.x, plot.p0.y}, text, fmt::format("{:g}", y1).c_str());
  dl->AddText({origin.x, (plot.p0.y + plot.p1.y) / 2}, text, axis_name(ay));
  dl->AddText({origin.x, plot.p1.y - line}, text, fmt::format("{:g}", y0).c_str());
  dl->PushClipRect(plot.p0, plot.p1, true);
  const int hovered = draw_points(plot, st, ax, ay, dl);
  if (hovered >= 0 && ImGui::IsItemHovered()) {
    const RockPairPoint& p = st.points[hovered];
    dl->AddCircle(plot.to_screen(axis_value(p, ax), axis_value(p, ay)), 5, text);
    ImGui::SetTooltip("%s", pair_line(s, p).c_str());
  }
  dl->PopClipRect();
  handle_mouse(s, plot, ImGui::IsItemHovered() ? hovered : -1, ax, ay, st, ui, out);
}

// A rock's crop: the box and its best-IoU prediction on a neutral square, 2.5 rock sizes across.
void draw_crop(const Session& s, Side side, int scene, int rock, float px) {
  const ImVec2 p0 = ImGui::GetCursorScreenPos(), p1{p0.x + px, p0.y + px};
  ImGui::Dummy({px, px});
  ImDrawList* dl = ImGui::GetWindowDrawList();
  dl->AddRectFilled(p0, p1, IM_COL32(96, 96, 96, 255));
  const Box& g = s.gt(side, scene)[rock];
  const double span = std::max({g.w, g.h, 1e-6}) * 2.5;
  auto at = [&](double x, double y) {
    return ImVec2{float(p0.x + ((x - g.cx) / span + 0.5) * px), float(p0.y + ((y - g.cy) / span + 0.5) * px)};
  };
  dl->PushClipRect(p0, p1, true);
  dl->AddRect(at(g.x0(), g.y0()), at(g.x1(), g.y1()), IM_COL32(86, 180, 233, 255), 0, 0, 2);
  const int best = s.performance(side, scene).best_prediction[rock];
  if (best >= 0) {
    const Box& b = s.predictions(side, scene)[best];
    dl->AddRect(at(b.x0(), b.y0()), at(b.x1(), b.y1()), kSelected, 0, 0, 1.5f);
  }
  dl->PopClipRect();
}

constexpr int kGalleryPage = 8;

void draw_gallery(const Session& s, RockViewState& st, UiCommands& out) {
  static const char* kSorts[] = {"|diff|", "perf A", "perf B", "size"};
  ImGui::SetNextItemWidth(110);
  ImGui::Combo("sort (largest first)", &st.gallery_sort, kSorts, 4);
  if (st.gallery_sorted_by != st.gallery_sort) {
    st.gallery = gallery_sorted(st.points, st.gallery_sort);
    st.gallery_sorted_by = st.gallery_sort;
  }
  const int pages = std::max(1, (static_cast<int>(st.gallery.size()) + kGalleryPage - 1) / kGalleryPage);
  st.gallery_page = std::clamp(st.gallery_page, 0, pages - 1);
  ImGui::SameLine();
  if (ImGui::ArrowButton("##gprev", ImGuiDir_Left)) st.gallery_page = std::max(0, st.gallery_page - 1);
  ImGui::SameLine();
  ImGui::Text("page %d of %d", st.gallery_page + 1, pages);
  ImGui::SameLine();
  if (ImGui::ArrowButton("##gnext", ImGuiDir_Right)) st.gallery_page = std::min(pages - 1, st.gallery_page + 1);
  ImGui::TextDisabled("Boxes on a neutral background (GT blue, its best-IoU prediction orange); %s | %s. Click to go.",
                      s.left_domain().c_str(), s.right_domain().c_str());
  const float px = 5 * ImGui::GetTextLineHeight();
  for (int k = st.gallery_page * kGalleryPage;
       k < std::min<int>(st.gallery.size(), (st.gallery_page + 1) * kGalleryPage); ++k) {
    const RockPairPoint& p = st.points[st.gallery[k]];
    ImGui::PushID(k);
    ImGui::BeginGroup();
    draw_crop(s, Side::kA, p.scene, p.rock_a, px);
    ImGui::SameLine();
    draw_crop(s, Side::kB, p.scene, p.rock_b, px);
    ImGui::SameLine();
    ImGui::BeginGroup();
    ImGui::Text("%d. %s", k + 1, s.scenes()[p.scene].stem.c_str());
    ImGui::Text("rock %d | rock %d", p.rock_a + 1, p.rock_b + 1);
    ImGui::Text("perf %.3f | %.3f   |diff| %.3f", p.perf_a, p.perf_b, p.abs_diff);
    if (ImGui::SmallButton("go to pair")) go_to(p, out);
    ImGui::EndGroup();
    ImGui::EndGroup();
    if (ImGui::IsItemClicked()) go_to(p, out);
    ImGui::PopID();
  }
}

}  // namespace

bool refresh_rock_points(const Session& s, const UiState& ui, RockViewState& st) {
  std::vector<int> scenes = st.current_scene              ? std::vector<int>{ui.scene}
                            : ui.selection_scenes.empty() ? ui.order
                                                          : ui.order_without_selection;
  if (st.session == &s && scenes == st.scenes) return false;
  st.session = &s;
  st.scenes = std::move(scenes);
  std::vector<int> sorted = st.scenes;
  std::sort(sorted.begin(), sorted.end());  // points by scene, whatever the list's sort order
  st.points = rock_pair_points(s, sorted);
  st.gallery_sorted_by = -1;
  return true;
}

std::vector<int> gallery_sorted(const std::vector<RockPairPoint>& points, int sort) {
  static const GallerySort kSorts[] = {GallerySort::kDiff, GallerySort::kPerfA, GallerySort::kPerfB,
                                       GallerySort::kSize};
  return ipd::gallery_sorted(points, kSorts[std::clamp(sort, 0, 3)]);
}

void apply_pair_selection(const Session& s, const PairSelection& sel, UiState& ui) {
  if (sel.points.empty()) {
    ui.status = "the box holds no pair: the scene list is unchanged";
    return;
  }
  ui.selection_scenes = sel.scenes;
  ui.selection_label = sel.label();
  ui.selection_pair = s.pair_index();
  ui.selection_model = s.model();
  ui.order.clear();  // the app lists the scenes again
}

void draw_rock_view(const StudyView& v, RockViewState& st, UiState& ui, UiCommands& out) {
  if (!ui.show_rock_view || !v.session) return;
  ImGui::SetNextWindowSize({720, 520}, ImGuiCond_FirstUseEver);
  // Over the pictures, not the scene list: the selection's chip and the filtered list stay in sight.
  const ImVec2 display = ImGui::GetIO().DisplaySize;
  ImGui::SetNextWindowPos({display.x * 0.5f, display.y * 0.5f}, ImGuiCond_FirstUseEver, {0.3f, 0.5f});
  if (!ImGui::Begin("Rock pairs###RockView", &ui.show_rock_view)) {
    ImGui::End();
    return;
  }
  const Session& s = *v.session;
  refresh_rock_points(s, ui, st);
  if (ImGui::BeginTabBar("##rocktabs")) {
    if (ImGui::BeginTabItem("Scatter")) {
      draw_scatter(s, st, ui, out);
      ImGui::EndTabItem();
    }
    if (ImGui::BeginTabItem("Gallery")) {
      draw_gallery(s, st, out);
      ImGui::EndTabItem();
    }
    ImGui::EndTabBar();
  }
  ImGui::End();
}

}  // namespace ipd::ui
