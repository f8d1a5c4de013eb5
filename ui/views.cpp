#include "views.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>

namespace ipd::ui {

namespace {

std::string fmt_ipd(double v) {
  if (std::isnan(v)) return "n/a";
  char b[32];
  std::snprintf(b, sizeof b, "%.4f", v);
  return b;
}

bool key_pressed(int glfw_key) { return ImGui::IsKeyPressed(glfw_key, true); }

}  // namespace

std::vector<int> browser_order(const Session& s, const UiState& ui) {
  std::vector<int> order;
  std::vector<SceneSummary> sums;
  for (int k = 0; k < static_cast<int>(s.scenes().size()); ++k) {
    sums.push_back(s.summary(k));
    if (ui.filter[0] && sums.back().stem.find(ui.filter) == std::string::npos) continue;
    order.push_back(k);
  }
  auto key = [&](int k) -> double {
    const auto& m = sums[k];
    switch (ui.sort_column) {
      case 1: return std::isnan(m.ipd) ? -1.0 : m.ipd;
      case 2: return m.pairs;
      case 3: return m.unpaired_a + m.unpaired_b;
      case 4: return m.edited;
      default: return 0;
    }
  };
  std::stable_sort(order.begin(), order.end(), [&](int x, int y) {
    if (ui.sort_column == 0) return ui.sort_descending ? sums[x].stem > sums[y].stem : sums[x].stem < sums[y].stem;
    return ui.sort_descending ? key(x) > key(y) : key(x) < key(y);
  });
  return order;
}

void draw_study_browser(const Session& s, UiState& ui, UiCommands& out) {
  const Study& st = s.study();
  ImGui::TextUnformatted(st.root.c_str());
  if (s.read_only()) ImGui::TextColored({1, 0.6f, 0.2f, 1}, "read-only: edits stay in memory (Save as below)");
  auto domain_combo = [&](const char* label, const std::string& current, std::string* choice) {
    if (ImGui::BeginCombo(label, current.c_str())) {
      for (const auto& d : st.domains)
        if (ImGui::Selectable(d.name.c_str(), d.name == current)) *choice = d.name;
      ImGui::EndCombo();
    }
  };
  std::string left, right;
  domain_combo("left", s.left_domain(), &left);
  domain_combo("right", s.right_domain(), &right);
  if (!left.empty() && left != s.right_domain()) out.left_domain = left, out.right_domain = s.right_domain();
  if (!right.empty() && right != s.left_domain()) out.left_domain = s.left_domain(), out.right_domain = right;
  if (ImGui::BeginCombo("model", s.model().c_str())) {
    for (const auto& m : st.models) {
      const std::string label = m.trained_on.empty() ? m.name : m.name + " (" + m.trained_on + ")";
      if (ImGui::Selectable(label.c_str(), m.name == s.model())) out.model = m.name;
    }
    ImGui::EndCombo();
  }
  if (ImGui::SliderFloat("conf >=", &ui.conf_threshold, 0.0f, 1.0f, "%.2f")) out.conf_threshold = ui.conf_threshold;
  ImGui::InputTextWithHint("##filter", "filter scenes", ui.filter, sizeof ui.filter);
  const ImGuiTableFlags flags = ImGuiTableFlags_Sortable | ImGuiTableFlags_RowBg | ImGuiTableFlags_ScrollY |
                                ImGuiTableFlags_BordersInnerV | ImGuiTableFlags_Resizable;
  if (ImGui::BeginTable("scenes", 5, flags)) {
    ImGui::TableSetupScrollFreeze(0, 1);
    ImGui::TableSetupColumn("scene", ImGuiTableColumnFlags_WidthStretch);
    ImGui::TableSetupColumn("IPD", ImGuiTableColumnFlags_DefaultSort | ImGuiTableColumnFlags_PreferSortDescending |
                                       ImGuiTableColumnFlags_WidthFixed);
    ImGui::TableSetupColumn("pairs", ImGuiTableColumnFlags_WidthFixed);
    ImGui::TableSetupColumn("unp.", ImGuiTableColumnFlags_WidthFixed);
    ImGui::TableSetupColumn("ed.", ImGuiTableColumnFlags_WidthFixed);
    ImGui::TableHeadersRow();
    if (ImGuiTableSortSpecs* spec = ImGui::TableGetSortSpecs(); spec && spec->SpecsDirty && spec->SpecsCount > 0) {
      ui.sort_column = spec->Specs[0].ColumnIndex;
      ui.sort_descending = spec->Specs[0].SortDirection == ImGuiSortDirection_Descending;
      spec->SpecsDirty = false;
    }
    for (int k : ui.order) {
      const SceneSummary m = s.summary(k);
      ImGui::TableNextRow();
      ImGui::TableNextColumn();
      if (ImGui::Selectable(m.stem.c_str(), k == ui.scene, ImGuiSelectableFlags_SpanAllColumns)) out.goto_scene = k;
      if (k == ui.scene && ImGui::IsWindowAppearing()) ImGui::SetScrollHereY();
      ImGui::TableNextColumn();
      ImGui::TextUnformatted(fmt_ipd(m.ipd).c_str());
      ImGui::TableNextColumn();
      ImGui::Text("%d", m.pairs);
      ImGui::TableNextColumn();
      ImGui::Text("%d/%d", m.unpaired_a, m.unpaired_b);
      ImGui::TableNextColumn();
      if (m.edited) ImGui::TextColored({0.4f, 0.8f, 1, 1}, "hand");
    }
    ImGui::EndTable();
  }
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

void draw_side_by_side(const Session& s, UiState& ui, const Picture& left, const Picture& right, UiCommands& out) {
  if (s.scenes().empty()) {
    ImGui::TextUnformatted("No scene is present in both domains.");
    return;
  }
  ImGui::Checkbox("GT", &ui.layers.gt);
  ImGui::SameLine();
  ImGui::Checkbox("predictions", &ui.layers.predictions);
  ImGui::SameLine();
  ImGui::Checkbox("indices", &ui.layers.indices);
  ImGui::SameLine();
  ImGui::Checkbox("confidence", &ui.layers.confidences);
  ImGui::SameLine();
  ImGui::Checkbox("sync zoom", &ui.sync_views);
  ImGui::SameLine();
  if (ImGui::Button("unpair (U)") && ui.selected_left >= 0)
    out.edits.push_back(Edit::unpair(Side::kA, ui.selected_left));
  ImGui::SameLine();
  if (ImGui::Button("exclude (X)") && (ui.selected_left >= 0 || ui.selected_right >= 0))
    out.edits.push_back(Edit::toggle_exclude(ui.selected_left >= 0 ? Side::kA : Side::kB,
                                             ui.selected_left >= 0 ? ui.selected_left : ui.selected_right));
  ImGui::SameLine();
  if (ImGui::Button("reset to automatic")) out.edits.push_back(Edit::reset());
  ImGui::SameLine();
  if (ImGui::Button("export figure")) out.export_figures = true;
  ImGui::SameLine();
  ImGui::TextDisabled("click left then right to pair; wheel zoom, drag pan");

  const ImVec2 avail = ImGui::GetContentRegionAvail();
  const float gap = 6;
  const ImVec2 size{(avail.x - gap) * 0.5f, std::max(50.0f, avail.y)};
  ImDrawList* dl = ImGui::GetWindowDrawList();
  const ImVec2 mouse = ImGui::GetIO().MousePos;
  for (int k = 0; k < 2; ++k) {
    const Side side = k == 0 ? Side::kA : Side::kB;
    const ImVec2 p0 = ImGui::GetCursorScreenPos();
    ImGui::InvisibleButton(k == 0 ? "##left" : "##right", size);
    const bool hovered_area = ImGui::IsItemHovered();
    CanvasView& view = k == 0 ? ui.left_view : ui.right_view;
    SideInput in = side_input(s, ui, side, k == 0 ? left : right);
    in.fill_background = false;
    in.min_box_px_for_confidence = 2.2f * ImGui::GetFontSize();
    const int hit = draw_side(dl, p0, size, view, in, ui.layers, mouse);
    int& hover = k == 0 ? ui.hover_left : ui.hover_right;
    hover = hovered_area ? hit : -1;
    if (hovered_area) {
      const float wheel = ImGui::GetIO().MouseWheel;
      if (wheel != 0) view.zoom = std::clamp(view.zoom * std::pow(1.2f, wheel), 0.5f, 20.0f);
      if (ImGui::IsMouseDragging(ImGuiMouseButton_Left, 4.0f)) {
        const Placement pl = place(p0, size, in.image_w, in.image_h, view);
        const ImVec2 d = ImGui::GetIO().MouseDelta;
        view.pan.x -= d.x / pl.size.x;
        view.pan.y -= d.y / pl.size.y;
      } else if (ImGui::IsMouseReleased(ImGuiMouseButton_Left) &&
                 ImGui::GetIO().MouseDragMaxDistanceSqr[ImGuiMouseButton_Left] < 16.0f) {
        int& sel = k == 0 ? ui.selected_left : ui.selected_right;
        sel = hit;
        if (ui.selected_left >= 0 && ui.selected_right >= 0) {
          out.edits.push_back(Edit::pair(ui.selected_left, ui.selected_right));
          ui.selected_left = ui.selected_right = -1;
        }
      }
      if (ui.sync_views) (k == 0 ? ui.right_view : ui.left_view) = view;
      if (hit >= 0) {
        const auto& pv_self = s.performance(side, ui.scene).value;
        ImGui::BeginTooltip();
        ImGui::Text("%s rock %d: IoU %.3f", in.caption.c_str(), hit + 1, hit < (int)pv_self.size() ? pv_self[hit] : 0.0);
        for (const auto& [l, r] : s.view_pairs(ui.scene)) {
          if ((k == 0 ? l : r) != hit) continue;
          const int other = k == 0 ? r : l;
          const auto& pv_other = s.performance(k == 0 ? Side::kB : Side::kA, ui.scene).value;
          const double o = other < (int)pv_other.size() ? pv_other[other] : 0.0;
          ImGui::Text("partner: %s rock %d: IoU %.3f", (k == 0 ? s.right_domain() : s.left_domain()).c_str(), other + 1, o);
          ImGui::Text("|difference| %.3f", std::abs(pv_self[hit] - o));
        }
        if (in.excluded[hit]) ImGui::TextUnformatted("excluded from the IPD");
        ImGui::EndTooltip();
      }
    }
    if (k == 0) ImGui::SameLine(0, gap);
  }
}

void draw_registration(const Session& s, UiState& ui, UiCommands& out) {
  if (s.scenes().empty()) return;
  const SceneState& sc = s.scenes()[ui.scene];
  const RegistrationReport& r = ui.rerun ? *ui.rerun : sc.automatic.registration;
  const auto& [da, db] = s.domain_pairs()[s.pair_index()];
  if (sc.edited && !ui.rerun) ImGui::TextColored({0.4f, 0.8f, 1, 1}, "pairs fixed by hand; lines show the current pairs");
  ImGui::Text("%s -> %s: %s, %d trials, %d hypotheses, %d inliers, score %.4f", da.c_str(), db.c_str(),
              to_string(r.method), r.trials, r.hypotheses, r.inliers, r.score);
  ImGui::TextDisabled("stopped: %s%s%s", to_string(r.stop), r.note.empty() ? "" : "; ", r.note.c_str());
  if (ImGui::Button(ui.playing ? "pause" : "play")) {
    ui.playing = !ui.playing;
    if (ui.playing && ui.anim_t >= 1.0f) ui.anim_t = 0.0f;
  }
  ImGui::SameLine();
  ImGui::SetNextItemWidth(160);
  ImGui::SliderFloat("before -> after", &ui.anim_t, 0.0f, 1.0f, "%.2f");
  if (ui.playing) {
    ui.anim_t = std::min(1.0f, ui.anim_t + ImGui::GetIO().DeltaTime / 1.5f);
    if (ui.anim_t >= 1.0f) ui.playing = false;
  }
  const char* methods[] = {"consensus", "paper", "cpd"};
  ImGui::SetNextItemWidth(100);
  ImGui::Combo("##method", &ui.rerun_method, methods, 3);
  ImGui::SameLine();
  ImGui::SetNextItemWidth(70);
  ImGui::InputInt("seed", &ui.rerun_seed, 0);
  ImGui::SameLine();
  if (ImGui::Button("re-run")) out.rerun_registration = true;
  if (ui.rerun) {
    ImGui::SameLine();
    if (ImGui::Button("apply these pairs")) {
      RockPairs pairs = ui.rerun->pairs;  // registration's (A, B) order; the view may show (B, A)
      if (s.swapped())
        for (auto& p : pairs) std::swap(p.first, p.second);
      out.edits.push_back(Edit::replace(std::move(pairs)));
      ui.rerun.reset();
    }
    ImGui::SameLine();
    if (ImGui::Button("discard")) ui.rerun.reset();
  }
  // Canvas: B's centres (pink rings) fixed, A's moving from raw (t = 0) to registered (t = 1), in B's frame.
  const ImVec2 p0 = ImGui::GetCursorScreenPos(), avail = ImGui::GetContentRegionAvail();
  const ImVec2 size{avail.x, std::max(40.0f, avail.y)};
  ImGui::InvisibleButton("##reg", size);
  ImDrawList* dl = ImGui::GetWindowDrawList();
  const auto& ga = s.labels().gt_of(da, sc.stem).boxes;
  const auto& gb = s.labels().gt_of(db, sc.stem).boxes;
  const Placement pl = place({p0.x + 10, p0.y + 10}, {size.x - 20, size.y - 20}, s.study().config.image_width,
                             s.study().config.image_height, CanvasView{});
  dl->AddRect(pl.origin, {pl.origin.x + pl.size.x, pl.origin.y + pl.size.y}, IM_COL32(90, 90, 100, 255));
  const Affine2 m = interpolate_from_identity(r.affine, ui.anim_t);
  std::vector<ImVec2> pa, pb;
  for (const auto& b : ga) {
    const Eigen::Vector2d q = apply(m, b.centre());
    pa.push_back(pl.to_screen(q.x(), q.y()));
  }
  for (const auto& b : gb) pb.push_back(pl.to_screen(b.cx, b.cy));
  const RockPairs& pairs = ui.rerun ? ui.rerun->pairs : sc.current.pairs;
  std::vector<char> paired_a(pa.size(), 0), paired_b(pb.size(), 0);
  for (const auto& [i, j] : pairs) {
    if (i >= (int)pa.size() || j >= (int)pb.size()) continue;
    paired_a[i] = paired_b[j] = 1;
    // Inlier: the registered centres land within 2% of the picture width.
    const Eigen::Vector2d q = apply(r.affine, ga[i].centre());
    const bool inlier = std::hypot(q.x() - gb[j].cx, q.y() - gb[j].cy) < 0.02;
    dl->AddLine(pa[i], pb[j], inlier ? IM_COL32(90, 220, 120, 200) : IM_COL32(255, 150, 40, 220), 1.5f);
  }
  // B as rings, A as dots, so both stay visible where registration puts them on top of each other.
  // Markers this small don't need many segments (a software rasteriser pays per vertex).
  for (size_t k = 0; k < pb.size(); ++k) dl->AddCircle(pb[k], 7, kPink, 10, paired_b[k] ? 2.0f : 1.0f);
  for (size_t k = 0; k < pa.size(); ++k)
    paired_a[k] ? dl->AddCircleFilled(pa[k], 3.5f, IM_COL32(80, 170, 255, 255), 8)
                : dl->AddCircle(pa[k], 4, IM_COL32(80, 170, 255, 255), 8, 1.5f);
  dl->AddText({p0.x + 14, p0.y + size.y - 22}, IM_COL32(200, 200, 200, 255),
              "blue dots: A moved by the affine   pink rings: B   green: inlier pair   orange: outlier pair   thin/hollow: unpaired");
}

void draw_pair_table(const Session& s, UiState& ui, UiCommands& out) {
  if (s.scenes().empty()) return;
  const auto& pl = s.performance(Side::kA, ui.scene).value;
  const auto& pr = s.performance(Side::kB, ui.scene).value;
  struct Row {
    int l, r;
    double a, b;
  };
  std::vector<Row> rows;
  for (const auto& [l, r] : s.view_pairs(ui.scene))
    rows.push_back({l, r, l < (int)pl.size() ? pl[l] : 0.0, r < (int)pr.size() ? pr[r] : 0.0});
  std::stable_sort(rows.begin(), rows.end(), [](const Row& x, const Row& y) { return std::abs(x.a - x.b) > std::abs(y.a - y.b); });
  const float table_h = std::max(60.0f, ImGui::GetContentRegionAvail().y - 3.2f * ImGui::GetTextLineHeightWithSpacing());
  if (ImGui::BeginTable("pairs", 5, ImGuiTableFlags_RowBg | ImGuiTableFlags_ScrollY | ImGuiTableFlags_BordersInnerV,
                        ImVec2(0, table_h))) {
    ImGui::TableSetupScrollFreeze(0, 1);
    ImGui::TableSetupColumn(s.left_domain().c_str());
    ImGui::TableSetupColumn(s.right_domain().c_str());
    ImGui::TableSetupColumn("IoU left");
    ImGui::TableSetupColumn("IoU right");
    ImGui::TableSetupColumn("|diff|");
    ImGui::TableHeadersRow();
    for (const auto& row : rows) {
      ImGui::TableNextRow();
      ImGui::TableNextColumn();
      char label[32];
      std::snprintf(label, sizeof label, "%d##%d", row.l + 1, row.l);
      if (ImGui::Selectable(label, ui.selected_left == row.l, ImGuiSelectableFlags_SpanAllColumns)) {
        // Centre both pictures on the pair.
        const Box& bl = s.gt(Side::kA, ui.scene)[row.l];
        const Box& br = s.gt(Side::kB, ui.scene)[row.r];
        ui.left_view = {std::max(ui.left_view.zoom, 3.0f), {float(bl.cx - 0.5), float(bl.cy - 0.5)}};
        ui.right_view = {ui.left_view.zoom, {float(br.cx - 0.5), float(br.cy - 0.5)}};
        ui.selected_left = row.l;
      }
      if (ImGui::IsItemHovered()) ui.hover_left = row.l;
      ImGui::TableNextColumn();
      ImGui::Text("%d", row.r + 1);
      ImGui::TableNextColumn();
      ImGui::Text("%.3f", row.a);
      ImGui::TableNextColumn();
      ImGui::Text("%.3f", row.b);
      ImGui::TableNextColumn();
      ImGui::Text("%.3f", std::abs(row.a - row.b));
    }
    ImGui::EndTable();
  }
  // Rocks without a partner, with their own IoU: the ones an audit looks at next.
  for (int k = 0; k < 2; ++k) {
    const Side side = k == 0 ? Side::kA : Side::kB;
    const auto& gt = s.gt(side, ui.scene);
    const auto& pv = k == 0 ? pl : pr;
    std::vector<char> paired(gt.size(), 0);
    for (const auto& [l, r] : s.view_pairs(ui.scene)) {
      const int idx = k == 0 ? l : r;
      if (idx >= 0 && idx < static_cast<int>(paired.size())) paired[idx] = 1;
    }
    std::string list;
    for (size_t i = 0; i < gt.size(); ++i) {
      if (paired[i]) continue;
      char item[48];
      std::snprintf(item, sizeof item, "%s%zu (IoU %.2f%s)", list.empty() ? "" : ", ", i + 1, i < pv.size() ? pv[i] : 0.0,
                    s.excluded(side, ui.scene, static_cast<int>(i)) ? ", excluded" : "");
      list += item;
    }
    ImGui::TextWrapped("unpaired %s: %s", (k == 0 ? s.left_domain() : s.right_domain()).c_str(),
                       list.empty() ? "none" : list.c_str());
  }
  (void)out;
}

void draw_ipd_panel(const Session& s, UiState& ui, UiCommands& out) {
  if (!s.scenes().empty()) {
    const SceneSummary m = s.summary(ui.scene);
    ImGui::Text("scene %s", m.stem.c_str());
    ImGui::Text("IPD %s  (%d pairs, unpaired %d / %d)", fmt_ipd(m.ipd).c_str(), m.pairs, m.unpaired_a, m.unpaired_b);
  }
  const CellTotals t = s.totals();
  ImGui::Separator();
  ImGui::Text("IPD(%s, %s) for %s", s.left_domain().c_str(), s.right_domain().c_str(), s.model().c_str());
  ImGui::Text("%s over %ld pairs in %d scenes", fmt_ipd(t.ipd()).c_str(), t.pairs, t.scenes);
  ImGui::Separator();
  ImGui::TextUnformatted("Cross table (lower is better)");
  const auto& pairs = s.domain_pairs();
  if (ImGui::BeginTable("cross", static_cast<int>(pairs.size()) + 1,
                        ImGuiTableFlags_Borders | ImGuiTableFlags_SizingFixedFit | ImGuiTableFlags_ScrollX,
                        ImVec2(0, ImGui::GetTextLineHeightWithSpacing() * (s.study().models.size() + 2.5f)))) {
    ImGui::TableSetupColumn("train \\ eval");
    for (const auto& [a, b] : pairs) ImGui::TableSetupColumn((a + " - " + b).c_str());
    ImGui::TableHeadersRow();
    for (const auto& m : s.study().models) {
      ImGui::TableNextRow();
      ImGui::TableNextColumn();
      ImGui::TextUnformatted(m.trained_on.empty() ? m.name.c_str() : (m.name + " (" + m.trained_on + ")").c_str());
      for (size_t p = 0; p < pairs.size(); ++p) {
        ImGui::TableNextColumn();
        const bool involves = m.trained_on.empty() || m.trained_on == pairs[p].first || m.trained_on == pairs[p].second;
        const double v = s.totals_for(m.name, static_cast<int>(p)).ipd();
        const bool current = m.name == s.model() && static_cast<int>(p) == s.pair_index();
        if (!involves) ImGui::TextDisabled("-");
        else if (current) ImGui::TextColored({1, 0.85f, 0.3f, 1}, "%s", fmt_ipd(v).c_str());
        else ImGui::TextUnformatted(fmt_ipd(v).c_str());
      }
    }
    ImGui::EndTable();
  }
  ImGui::Separator();
  ImGui::BeginDisabled(!s.can_undo());
  if (ImGui::Button("undo (Ctrl+Z)")) out.undo = true;
  ImGui::EndDisabled();
  ImGui::SameLine();
  ImGui::BeginDisabled(!s.can_redo());
  if (ImGui::Button("redo (Ctrl+Y)")) out.redo = true;
  ImGui::EndDisabled();
  if (s.read_only()) {
    ImGui::InputTextWithHint("##saveas", "directory for the edited pairs", ui.save_as_dir, sizeof ui.save_as_dir);
    ImGui::SameLine();
    if (ImGui::Button("save as")) out.save_as = true;
  }
  if (!ui.status.empty()) ImGui::TextWrapped("%s", ui.status.c_str());
}

void handle_shortcuts(const Session& s, UiState& ui, UiCommands& out) {
  ImGuiIO& io = ImGui::GetIO();
  if (io.WantTextInput || s.scenes().empty()) return;
  const bool ctrl = io.KeyCtrl;
  if (ctrl && key_pressed('Z')) out.undo = true;
  if (ctrl && key_pressed('Y')) out.redo = true;
  if (ctrl) return;
  const std::vector<int>& order = ui.order;
  const auto pos = std::find(order.begin(), order.end(), ui.scene);
  const int at = pos == order.end() ? -1 : static_cast<int>(pos - order.begin());
  if ((key_pressed(ImGui::GetKeyIndex(ImGuiKey_RightArrow)) || key_pressed('J')) && !order.empty())
    out.goto_scene = order[std::min<int>(at + 1, order.size() - 1)];
  if ((key_pressed(ImGui::GetKeyIndex(ImGuiKey_LeftArrow)) || key_pressed('K')) && !order.empty())
    out.goto_scene = order[std::max(at - 1, 0)];
  if (key_pressed('U') && ui.selected_left >= 0) out.edits.push_back(Edit::unpair(Side::kA, ui.selected_left));
  if (key_pressed('U') && ui.selected_left < 0 && ui.selected_right >= 0)
    out.edits.push_back(Edit::unpair(Side::kB, ui.selected_right));
  if (key_pressed('X') && (ui.selected_left >= 0 || ui.selected_right >= 0))
    out.edits.push_back(Edit::toggle_exclude(ui.selected_left >= 0 ? Side::kA : Side::kB,
                                             ui.selected_left >= 0 ? ui.selected_left : ui.selected_right));
  if (key_pressed(ImGui::GetKeyIndex(ImGuiKey_Escape))) ui.selected_left = ui.selected_right = -1;
}

}  // namespace ipd::ui
