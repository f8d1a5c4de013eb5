#include "ui/gui/rock_view.h"

#include <fmt/format.h>
#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "ui/figures/figure_charts.h"
#include "ui/figures/figure_common.h"
#include "ui/figures/figure_gallery.h"
#include "ui/gui/canvas_imgui.h"
#include "ui/gui/studio_layout.h"

namespace ipd::ui {
namespace {

constexpr PairAxis kAxes[] = {PairAxis::kPerfA, PairAxis::kPerfB, PairAxis::kAbsDiff, PairAxis::kSize,
                              PairAxis::kX,     PairAxis::kY,     PairAxis::kConfA,   PairAxis::kConfB};
// Okabe-Ito blue and orange: told apart with every common colour-vision deficiency.
const ImU32 kSelected = IM_COL32(230, 159, 0, 255);
constexpr int kCellPx = 3;  // one square per 3 x 3 pixels of plot

struct Plot {
  ImVec2 p0, p1;  // screen rectangle
  ScatterRange r;
  ImVec2 to_screen(double x, double y) const {
    return {float(p0.x + (x - r.x0) / (r.x1 - r.x0) * (p1.x - p0.x)),
            float(p1.y - (y - r.y0) / (r.y1 - r.y0) * (p1.y - p0.y))};
  }
  double data_x(float sx) const { return r.x0 + (sx - p0.x) / (p1.x - p0.x) * (r.x1 - r.x0); }
  double data_y(float sy) const { return r.y0 + (p1.y - sy) / (p1.y - p0.y) * (r.y1 - r.y0); }
};

// Wide enough for an axis or sort name with either domain's name in it.
float name_combo_width(const Session& s) {
  const float domain =
      std::max(ImGui::CalcTextSize(s.left_domain().c_str()).x, ImGui::CalcTextSize(s.right_domain().c_str()).x);
  return std::max(ImGui::CalcTextSize("conf ").x + domain, ImGui::CalcTextSize("size (px²)").x) +
         ImGui::GetFrameHeight() * 1.5f;
}

// "pair 7: real rock 7 | principled rock 10": the pair as the pictures number it (by its left rock, on both
// pictures), then each rock's own number, as the status line names rocks.
std::string pair_rocks(const Session& s, const RockPairPoint& p) {
  return fmt::format("pair {}: {} rock {} | {} rock {}", p.rock_a + 1, s.left_domain(), p.rock_a + 1, s.right_domain(),
                     p.rock_b + 1);
}

std::string pair_line(const Session& s, const RockPairPoint& p) {
  return fmt::format("{}: {}, perf {:.3f} | {:.3f}, |diff| {:.3f}", s.scenes()[p.scene].stem, pair_rocks(s, p),
                     p.perf_a, p.perf_b, p.abs_diff);
}

void go_to(const RockPairPoint& p, UiCommands& out) {
  out.goto_pair_scene = p.scene;
  out.goto_pair_left = p.rock_a;
  out.goto_pair_right = p.rock_b;
}

bool axis_combo(const char* label, int& axis, const Session& s) {
  bool changed = false;
  ImGui::SetNextItemWidth(name_combo_width(s));
  if (ImGui::BeginCombo(label, pair_axis_label(kAxes[axis], s.left_domain(), s.right_domain()).c_str())) {
    for (int k = 0; k < static_cast<int>(std::size(kAxes)); ++k)
      if (ImGui::Selectable(pair_axis_label(kAxes[k], s.left_domain(), s.right_domain()).c_str(), k == axis))
        axis = k, changed = true;
    ImGui::EndCombo();
  }
  return changed;
}

// Bins the points again when they, the axes, the plot's size or the selection changed. The selection is
// highlighted by its pairs, so it stays lit on axes other than the ones its box was drawn on.
void rebin(const Session& s, const UiState& ui, RockViewState& st, PairAxis ax, PairAxis ay, int w, int h) {
  const bool current = ui.selection_pair == s.pair_index() && ui.selection_model == s.model();
  const auto& selection = current ? ui.selection_pairs : nullptr;
  if (st.binned_points == st.points.get() && st.binned_x == static_cast<int>(ax) &&
      st.binned_y == static_cast<int>(ay) && st.binned_w == w && st.binned_h == h && st.binned_selection == selection)
    return;
  st.binned_points = st.points.get();
  st.binned_x = static_cast<int>(ax), st.binned_y = static_cast<int>(ay), st.binned_w = w, st.binned_h = h;
  st.binned_selection = selection;
  static const std::vector<RockPairPoint> kNone;
  const auto& points = st.points ? st.points->points : kNone;
  const auto [x0, x1] = scatter_axis_range(points, ax);
  const auto [y0, y1] = scatter_axis_range(points, ay);
  st.range = {x0, x1, y0, y1};
  const std::vector<char> marked = selection ? marked_pairs(points, *selection) : std::vector<char>();
  st.density = bin_pair_points(points, ax, ay, st.range, std::max(1, w / kCellPx), std::max(1, h / kCellPx),
                               selection ? &marked : nullptr);
}

// A cell's blue: light for one pair, darker as more pairs share it (log scale: a few dense cells must not
// wash out the rest).
ImU32 density_colour(int count, int max_count) {
  const float t = max_count > 1 ? float(std::log(double(count)) / std::log(double(max_count))) : 1.0f;
  const float light = 0.4f * (1 - t);  // 0: Okabe-Ito blue (0, 114, 178)
  return IM_COL32(int(0 + (255 - 0) * light), int(114 + (255 - 114) * light), int(178 + (255 - 178) * light), 255);
}

// The occupied cells (a frame costs what they cost); the index of the hovered cell's first point.
int draw_cells(const Plot& plot, const PairDensity& d, ImDrawList* dl) {
  const ImVec2 mouse = ImGui::GetMousePos();
  const float cw = (plot.p1.x - plot.p0.x) / d.cells_x, ch = (plot.p1.y - plot.p0.y) / d.cells_y;
  int hovered = -1;
  float best = 36;  // within 6 px
  for (const DensityCell& c : d.cells) {
    const ImVec2 q0{plot.p0.x + c.cx * cw, plot.p1.y - (c.cy + 1) * ch};
    // At least 4 x 4 pixels: a lone pair stays visible, and a click finds it.
    const ImVec2 q1{q0.x + std::max(cw, 4.0f), q0.y + std::max(ch, 4.0f)};
    dl->AddRectFilled(q0, q1, c.selected > 0 ? kSelected : density_colour(c.count, d.max_count));
    const float dx = (q0.x + q1.x) / 2 - mouse.x, dy = (q0.y + q1.y) / 2 - mouse.y;
    if (dx * dx + dy * dy < best) best = dx * dx + dy * dy, hovered = c.first;
  }
  return hovered;
}

// Round ticks with their labels and faint grid lines, on both axes.
void draw_axes(const Plot& plot, PairAxis ax, PairAxis ay, const Session& s, ImVec2 origin, ImDrawList* dl) {
  const ImU32 text = ImGui::GetColorU32(ImGuiCol_Text), grid = IM_COL32(128, 128, 128, 60);
  const float line = ImGui::GetTextLineHeight();
  const auto xt = nice_ticks(plot.r.x0, plot.r.x1, std::max(2, int((plot.p1.x - plot.p0.x) / (6 * line))));
  const auto yt = nice_ticks(plot.r.y0, plot.r.y1, std::max(2, int((plot.p1.y - plot.p0.y) / (3 * line))));
  const double xs = xt.size() > 1 ? xt[1] - xt[0] : 1, ys = yt.size() > 1 ? yt[1] - yt[0] : 1;
  for (const double t : xt) {
    if (t < plot.r.x0 - 1e-12 || t > plot.r.x1 + 1e-12) continue;
    const float x = plot.to_screen(t, plot.r.y0).x;
    dl->AddLine({x, plot.p0.y}, {x, plot.p1.y}, grid);
    const std::string label = tick_text(t, xs);
    const float w = ImGui::CalcTextSize(label.c_str()).x;
    dl->AddText({std::clamp(x - w / 2, plot.p0.x - w / 2, plot.p1.x - w), plot.p1.y + 2}, text, label.c_str());
  }
  for (const double t : yt) {
    if (t < plot.r.y0 - 1e-12 || t > plot.r.y1 + 1e-12) continue;
    const float y = plot.to_screen(plot.r.x0, t).y;
    dl->AddLine({plot.p0.x, y}, {plot.p1.x, y}, grid);
    const std::string label = tick_text(t, ys);
    dl->AddText({plot.p0.x - ImGui::CalcTextSize(label.c_str()).x - 4, y - line / 2}, text, label.c_str());
  }
  const std::string xn = pair_axis_label(ax, s.left_domain(), s.right_domain());
  const std::string yn = pair_axis_label(ay, s.left_domain(), s.right_domain());
  dl->AddText({(plot.p0.x + plot.p1.x - ImGui::CalcTextSize(xn.c_str()).x) / 2, plot.p1.y + 2 + line}, text,
              xn.c_str());
  dl->AddText({origin.x, origin.y}, text, yn.c_str());
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
    if (hovered >= 0) go_to(st.points->points[hovered], out);
    return;
  }
  select_pairs_in_box(s, st, plot.data_x(st.drag_from.x), plot.data_y(st.drag_from.y), plot.data_x(m.x),
                      plot.data_y(m.y), ui);
}

void draw_scatter(const Session& s, bool gathering, RockViewState& st, UiState& ui, UiCommands& out) {
  axis_combo("x##rockx", st.x_axis, s);
  ImGui::SameLine();
  axis_combo("y##rocky", st.y_axis, s);
  ImGui::SameLine();
  ImGui::Checkbox("current scene only", &st.current_scene);
  const long n = st.points ? static_cast<long>(st.points->points.size()) : 0;
  // What the points are: the model and threshold they are scored with, and with a drag box, what it selected
  // (the scatter keeps the pairs of the list the filter alone gives; the list shows the selection's scenes).
  const std::string cell = "model " + (s.model().empty() ? std::string("none") : s.model()) +
                           ", conf >= " + fmt::format("{:g}", s.conf_threshold()) +
                           (s.study().config.task == Task::kSegment ? ", perf = mask IoU" : "");
  if (!st.points)
    ImGui::TextDisabled("gathering the pairs...");
  else if (!st.current_scene && !ui.selection_label.empty())
    text_disabled_wrapped_at_spaces(
        fmt::format("{} of the scenes the text filter lists ({}); {} (orange), listed{}: drag "
                    "another box, or clear it under the filter",
                    counted(n, "pair"), cell, ui.selection_label, gathering ? " (updating...)" : ""));
  else
    text_disabled_wrapped_at_spaces(
        fmt::format("{} of {} ({}){}: drag a box to filter the scene list, click a point "
                    "to see its pair",
                    counted(n, "pair"), st.current_scene ? "this scene" : "the listed scenes", cell,
                    gathering ? " (updating...)" : ""));
  const PairAxis ax = kAxes[st.x_axis], ay = kAxes[st.y_axis];
  const ImVec2 avail = ImGui::GetContentRegionAvail();
  const float line = ImGui::GetTextLineHeight();
  const ImVec2 origin = ImGui::GetCursorScreenPos();
  const ImVec2 size{std::max(80.0f, avail.x), std::max(80.0f, avail.y)};
  ImGui::InvisibleButton("##rockplot", size);
  if (!st.points) return;
  const ImVec2 p0{origin.x + ImGui::CalcTextSize("0.000").x + 8, origin.y + line + 4};
  const ImVec2 p1{origin.x + size.x - ImGui::CalcTextSize("0.0").x, origin.y + size.y - 2 * line - 4};
  rebin(s, ui, st, ax, ay, std::max(1, int(p1.x - p0.x)), std::max(1, int(p1.y - p0.y)));
  const Plot plot{p0, p1, st.range};
  ImDrawList* dl = ImGui::GetWindowDrawList();
  draw_axes(plot, ax, ay, s, origin, dl);
  dl->AddRect(plot.p0, plot.p1, IM_COL32(140, 140, 140, 255));
  dl->PushClipRect(plot.p0, plot.p1, true);
  const int hovered = draw_cells(plot, st.density, dl);
  if (hovered >= 0 && ImGui::IsItemHovered() && !st.dragging) {
    const RockPairPoint& p = st.points->points[hovered];
    dl->AddCircle(plot.to_screen(axis_value(p, ax), axis_value(p, ay)), 5, ImGui::GetColorU32(ImGuiCol_Text));
    ImGui::SetTooltip("%s", pair_line(s, p).c_str());
  }
  dl->PopClipRect();
  handle_mouse(s, plot, ImGui::IsItemHovered() ? hovered : -1, ax, ay, st, ui, out);
}

// A rock's crop: the picture around it (when the study has one and it is loaded), the box and its best-IoU
// prediction, on the region `ipd figure gallery` shows (a square of pixels 2.5 rock sizes across, so a rock
// keeps its shape); a neutral square where there is no picture.
void draw_crop(const StudyView& v, Side side, int scene, int rock, float px) {
  const Session& s = *v.session;
  const ImVec2 p0 = ImGui::GetCursorScreenPos(), p1{p0.x + px, p0.y + px};
  ImGui::Dummy({px, px});
  ImDrawList* dl = ImGui::GetWindowDrawList();
  dl->AddRectFilled(p0, p1, IM_COL32(96, 96, 96, 255));
  const Box& g = s.gt(side, scene)[rock];
  Picture pic;
  if (v.picture_of) pic = v.picture_of(side == Side::kA ? s.left_domain() : s.right_domain(), s.scenes()[scene].stem);
  // The study's image_size first, as the figure measures it, else the picture's own, else the cameras'.
  const StudyConfig& config = s.study().config;
  const bool configured = config.image_width > 0 && config.image_height > 0;
  const auto [w, h] =
      gallery_picture_size(configured ? config.image_width : pic.width, configured ? config.image_height : pic.height);
  const Crop r = gallery_crop_region(g, w, h);
  auto at = [&](double x, double y) {
    return ImVec2{float(p0.x + (x - r.x0) / (r.x1 - r.x0) * px), float(p0.y + (y - r.y0) / (r.y1 - r.y0) * px)};
  };
  dl->PushClipRect(p0, p1, true);
  // Normalised label coordinates are the texture's: the crop's part inside the picture, nothing repeated.
  const double u0 = std::max(0.0, r.x0), v0 = std::max(0.0, r.y0);
  const double u1 = std::min(1.0, r.x1), v1 = std::min(1.0, r.y1);
  if (pic.texture && u1 > u0 && v1 > v0)
    dl->AddImage(pic.texture, at(u0, v0), at(u1, v1), ImVec2(float(u0), float(v0)), ImVec2(float(u1), float(v1)));
  // The styles of `ipd figure gallery`, so the window previews the figure: the best prediction dashed on a
  // light halo, the GT box solid on a dark halo (told apart in greyscale and by every colour-vision deficiency).
  // A segmentation study's rocks as their outlines, as the figure draws them.
  ImGuiCanvas canvas(dl, {0, 0}, 1.0f, nullptr);
  constexpr double kStroke = 2.0, kDash = 6.0;
  const int best = s.performance(side, scene).best_prediction[rock];
  draw_gallery_instances(
      canvas,
      [&](double x, double y) {
        const ImVec2 q = at(x, y);
        return Pt{q.x, q.y};
      },
      g, best >= 0 ? &s.predictions(side, scene)[best] : nullptr, kStroke, kDash);
  dl->PopClipRect();
}

constexpr int kGalleryPage = 8;

void draw_gallery(const StudyView& v, RockViewState& st, UiCommands& out) {
  const Session& s = *v.session;
  const auto sort_label = [&](GallerySort g) { return gallery_sort_label(g, s.left_domain(), s.right_domain()); };
  ImGui::SetNextItemWidth(name_combo_width(s));
  if (ImGui::BeginCombo("sort (largest first)", sort_label(st.gallery_sort).c_str())) {
    for (const GallerySort g : kGallerySorts)
      if (ImGui::Selectable(sort_label(g).c_str(), g == st.gallery_sort)) st.gallery_sort = g;
    ImGui::EndCombo();
  }
  static const std::vector<RockPairPoint> kNone;
  const auto& points = st.points ? st.points->points : kNone;
  if (st.gallery_sorted_by != st.gallery_sort) {
    st.gallery = gallery_sorted(points, st.gallery_sort);
    st.gallery_sorted_by = st.gallery_sort;
  }
  const int pages = std::max(1, (static_cast<int>(st.gallery.size()) + kGalleryPage - 1) / kGalleryPage);
  st.gallery_page = std::clamp(st.gallery_page, 0, pages - 1);
  ImGui::SameLine();
  if (ImGui::ArrowButton("##gprev", ImGuiDir_Left)) st.gallery_page = std::max(0, st.gallery_page - 1);
  ImGui::SameLine();
  ImGui::TextUnformatted(fmt::format("page {} of {}", thousands(st.gallery_page + 1), thousands(pages)).c_str());
  ImGui::SameLine();
  if (ImGui::ArrowButton("##gnext", ImGuiDir_Right)) st.gallery_page = std::min(pages - 1, st.gallery_page + 1);
  text_wrapped_at_spaces(
      fmt::format("The picture around each rock (a grey square where the study has none), GT solid yellow, its "
                  "best-IoU prediction dashed blue; {} | {}. Click to go.",
                  s.left_domain(), s.right_domain()));
  // Thumbnails as large as the window's width allows for the two crops and their text (8 to 12 lines tall).
  const float px = std::clamp((ImGui::GetContentRegionAvail().x - ImGui::CalcTextSize("rock 99 (principled) | "
                                                                                      "rock 99 (principled)  ")
                                                                      .x) /
                                  2,
                              5 * ImGui::GetTextLineHeight(), 9 * ImGui::GetTextLineHeight());
  ImGui::BeginChild("##gallerypairs");
  for (int k = st.gallery_page * kGalleryPage;
       k < std::min<int>(st.gallery.size(), (st.gallery_page + 1) * kGalleryPage); ++k) {
    const RockPairPoint& p = points[st.gallery[k]];
    ImGui::PushID(k);
    ImGui::BeginGroup();
    draw_crop(v, Side::kA, p.scene, p.rock_a, px);
    ImGui::SameLine();
    draw_crop(v, Side::kB, p.scene, p.rock_b, px);
    ImGui::SameLine();
    ImGui::BeginGroup();
    ImGui::Text("%s. %s", thousands(k + 1).c_str(), s.scenes()[p.scene].stem.c_str());
    ImGui::TextUnformatted(pair_rocks(s, p).c_str());
    ImGui::Text("%s %.3f | %.3f   |diff| %.3f", iou_word(s), p.perf_a, p.perf_b, p.abs_diff);
    ImGui::Text("size %s px² (%s rock)", thousands(std::llround(p.size)).c_str(), s.left_domain().c_str());
    if (ImGui::SmallButton("go to pair")) go_to(p, out);
    ImGui::EndGroup();
    ImGui::EndGroup();
    if (ImGui::IsItemClicked()) go_to(p, out);
    ImGui::PopID();
  }
  ImGui::EndChild();
}

}  // namespace

std::string pair_axis_label(PairAxis axis, const std::string& left, const std::string& right) {
  switch (axis) {
    case PairAxis::kPerfA:
      return "perf " + left;
    case PairAxis::kPerfB:
      return "perf " + right;
    case PairAxis::kConfA:
      return "conf " + left;
    case PairAxis::kConfB:
      return "conf " + right;
    default:
      return axis_name(axis);
  }
}

std::vector<int> rock_view_scenes(const UiState& ui, const RockViewState& st) {
  std::vector<int> scenes = st.current_scene              ? std::vector<int>{ui.scene}
                            : ui.selection_scenes.empty() ? ui.order
                                                          : ui.order_without_selection;
  std::sort(scenes.begin(), scenes.end());  // points by scene, whatever the list's sort order
  return scenes;
}

bool adopt_rock_points(const Session& s, const std::shared_ptr<const RockPointSet>& points, RockViewState& st) {
  if (!points || points == st.points) return false;
  if (points->pair != s.pair_index() || points->swapped != s.swapped() || points->model != s.model()) {
    if (st.points &&
        (st.points->pair != s.pair_index() || st.points->swapped != s.swapped() || st.points->model != s.model()))
      st.points.reset(), st.gallery_sorted_by.reset();  // another cell's points: nothing to show meanwhile
    return false;
  }
  st.points = points;
  st.gallery_sorted_by.reset();
  return true;
}

void apply_pair_selection(const Session& s, const PairSelection& sel, UiState& ui) {
  if (sel.points.empty()) {
    ui.status = "the box holds no pair: the scene list is unchanged";
    return;
  }
  ui.selection_scenes = sel.scenes;
  ui.selection_label = sel.label();
  ui.selection_pairs = std::make_shared<const std::vector<RockPairKey>>(sel.pairs);
  ui.selection_pair = s.pair_index();
  ui.selection_model = s.model();
  ui.order.clear();  // the app lists the scenes again
}

void select_pairs_in_box(const Session& s, const RockViewState& st, double x0, double y0, double x1, double y1,
                         UiState& ui) {
  static const std::vector<RockPairPoint> kNone;
  apply_pair_selection(
      s, select_in_box(st.points ? st.points->points : kNone, kAxes[st.x_axis], kAxes[st.y_axis], x0, y0, x1, y1), ui);
}

int highlighted_pairs(const RockViewState& st) {
  int n = 0;
  for (const DensityCell& c : st.density.cells) n += c.selected;
  return n;
}

void draw_rock_view(const StudyView& v, const std::shared_ptr<const RockPointSet>& points, bool gathering,
                    RockViewState& st, UiState& ui, UiCommands& out) {
  if (!ui.show_rock_view || !v.session) return;
  // Over the pictures, not the scene list: the selection's chip and the filtered list stay in sight. A share of
  // the screen, so a large one shows a larger scatter and a whole gallery page.
  const ImVec2 display = ImGui::GetIO().DisplaySize;
  ImGui::SetNextWindowSize({std::clamp(display.x * 0.6f, std::min(720.0f, display.x), 1280.0f),
                            std::clamp(display.y * 0.7f, std::min(520.0f, display.y), 860.0f)},
                           ImGuiCond_FirstUseEver);
  ImGui::SetNextWindowPos({display.x * 0.5f, display.y * 0.5f}, ImGuiCond_FirstUseEver, {0.3f, 0.5f});
  if (!ImGui::Begin("Rock pairs###RockView", &ui.show_rock_view)) {
    ImGui::End();
    return;
  }
  const Session& s = *v.session;
  adopt_rock_points(s, points, st);
  if (ImGui::BeginTabBar("##rocktabs")) {
    const int select = std::exchange(st.select_tab, -1);
    if (ImGui::BeginTabItem("Scatter", nullptr, select == 0 ? ImGuiTabItemFlags_SetSelected : 0)) {
      draw_scatter(s, gathering, st, ui, out);
      ImGui::EndTabItem();
    }
    if (ImGui::BeginTabItem("Gallery", nullptr, select == 1 ? ImGuiTabItemFlags_SetSelected : 0)) {
      draw_gallery(v, st, out);
      ImGui::EndTabItem();
    }
    ImGui::EndTabBar();
  }
  ImGui::End();
}

}  // namespace ipd::ui
