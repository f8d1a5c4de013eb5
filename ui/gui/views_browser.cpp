// The study browser: domains, model, threshold, filter and the scene list (clipped: only visible rows are
// built, so 10,000 scenes cost what 30 do).
#include <algorithm>
#include <cmath>
#include <cstdio>

#include <imgui_internal.h>  // TableSetColumnSortDirection: a new table takes the list's sort

#include "ui/gui/studio_layout.h"
#include "ui/gui/views.h"

namespace ipd::ui {

std::vector<int> browser_order(const std::vector<SceneSummary>& sums, UiState& ui) {
  const SceneFilter filter = SceneFilter::parse(ui.filter);
  ui.filter_error = filter.error;
  std::vector<int> order;
  const auto& sel = ui.selection_scenes;
  for (int k = 0; k < static_cast<int>(sums.size()); ++k)
    if (filter.matches(sums[k]) && (sel.empty() || std::binary_search(sel.begin(), sel.end(), k))) order.push_back(k);
  auto key = [&](int k) -> double {
    const auto& m = sums[k];
    switch (ui.sort_column) {
      case kByIpd:
        return std::isnan(m.ipd) ? -1.0 : m.ipd;
      case kByPairs:
        return m.pairs;
      case kByUnpaired:
        return m.unpaired_a + m.unpaired_b;
      case kBySuspects:
        return m.suspects;
      case kByEdited:
        return m.edited;
      case kByAmbiguous:
        return m.ambiguous;
      case kByReviewed:
        return m.reviewed;
      default:
        return 0;
    }
  };
  std::stable_sort(order.begin(), order.end(), [&](int x, int y) {
    if (ui.sort_column == kByStem)
      return ui.sort_descending ? sums[x].stem > sums[y].stem : sums[x].stem < sums[y].stem;
    return ui.sort_descending ? key(x) > key(y) : key(x) < key(y);
  });
  return order;
}

void update_browser_order(const std::vector<SceneSummary>& sums, UiState& ui) {
  ui.order = browser_order(sums, ui);
  ui.order_without_selection.clear();
  if (ui.selection_scenes.empty()) return;
  std::vector<int> selection = std::move(ui.selection_scenes);
  ui.selection_scenes.clear();
  ui.order_without_selection = browser_order(sums, ui);
  ui.selection_scenes = std::move(selection);
}

const std::vector<BrowserColumn>& browser_columns() {
  const ImGuiTableColumnFlags num = ImGuiTableColumnFlags_WidthFixed | ImGuiTableColumnFlags_PreferSortDescending;
  // The IPD, the value a user looks for first, comes right after the (frozen) name, then the flags: a narrow
  // list (700 px window) shows name, IPD, amb. and susp. without scrolling sideways.
  static const std::vector<BrowserColumn> columns = {
      {{"scene", nullptr, nullptr, ImGuiTableColumnFlags_WidthStretch}, kByStem},
      {{"IPD", "0.0000", "the scene's IPD for the model (sorted worst first)", num | ImGuiTableColumnFlags_DefaultSort},
       kByIpd},
      {{"amb.", "?",
        "ambiguous registration: another alignment fits as well or almost as well (e.g. a small overlap or a "
        "repetitive layout), too few rocks are paired or they lie on a line, so the pairs may be wrong; "
        "check them",
        num},
       kByAmbiguous},
      {{"susp.", "99", "suspect pairs: paired rocks that the registration does not bring together", num}, kBySuspects},
      {{"ed.", "hand", "pairs fixed by hand", num}, kByEdited},
      {{"pairs", "999", "rock pairs counted in the IPD", num}, kByPairs},
      {{"unp.", "99/99", "unpaired rocks, left/right (excluded rocks are not counted)", num}, kByUnpaired},
      {{"rev.", "rev.", "reviewed: marked as looked at (R), so an audit can be split over days or people", num},
       kByReviewed},
  };
  return columns;
}

namespace {
const std::vector<TextColumn>& browser_text_columns() {
  static const std::vector<TextColumn> text = [] {
    std::vector<TextColumn> t;
    for (const auto& c : browser_columns()) t.push_back(c.text);
    return t;
  }();
  return text;
}

// One cell of a scene's row, by its column's sort key.
void draw_scene_cell(SceneSortKey sort_key, const SceneSummary& m, int k, const UiState& ui, UiCommands& out) {
  switch (sort_key) {
    case kByStem:
      ImGui::PushID(k);
      if (ImGui::Selectable(m.stem.c_str(), k == ui.scene, ImGuiSelectableFlags_SpanAllColumns)) out.goto_scene = k;
      // A name wider than its column: the whole of it on hover.
      if (ImGui::IsItemHovered() && ImGui::CalcTextSize(m.stem.c_str()).x > ImGui::GetColumnWidth())
        ImGui::SetTooltip("%s", m.stem.c_str());
      ImGui::PopID();
      break;
    case kByIpd:
      ImGui::TextUnformatted(fmt_ipd(m.ipd).c_str());
      break;
    case kByPairs:
      ImGui::Text("%d", m.pairs);
      break;
    case kByUnpaired:
      ImGui::Text("%d/%d", m.unpaired_a, m.unpaired_b);
      break;
    case kBySuspects:
      if (m.suspects > 0) ImGui::TextColored({1, 0.55f, 0, 1}, "%d", m.suspects);
      break;
    case kByEdited:
      if (m.edited) ImGui::TextColored({0.4f, 0.8f, 1, 1}, "hand");
      break;
    case kByReviewed:
      if (m.reviewed) ImGui::TextColored({0.5f, 0.9f, 0.5f, 1}, "yes");
      break;
    case kByAmbiguous:
      if (m.ambiguous) {
        ImGui::TextColored({1, 0.8f, 0.3f, 1}, "?");
        if (ImGui::IsItemHovered())
          ImGui::SetTooltip("ambiguous registration: %s;\ncheck this scene's pairs", ambiguity_reason(m.ambiguity));
      }
      break;
  }
}
}  // namespace

namespace {
// The longest scene name (null: none), the one the name column must fit: a scan of every scene, done once a frame.
const std::string* longest_stem(const StudyView& v) {
  size_t longest = 0;
  const std::string* name = nullptr;
  if (v.summaries)
    for (const auto& m : *v.summaries)
      if (m.stem.size() > longest) longest = m.stem.size(), name = &m.stem;
  return name;
}

// The scene list's columns at the current font, its scrollbar included.
float list_width(const std::string* longest) {
  const ImGuiStyle& st = ImGui::GetStyle();
  return (longest ? ImGui::CalcTextSize(longest->c_str()).x : 80.0f) + 2 * st.CellPadding.x +
         text_columns_width(browser_text_columns()) + st.ScrollbarSize;
}
}  // namespace

float browser_width(const StudyView& v, float min_w, float max_w) {
  return std::clamp(list_width(longest_stem(v)) + 2 * ImGui::GetStyle().WindowPadding.x + 8, min_w, max_w);
}

// The rock view's selection as a chip under the filter: its label and a button that clears it. A selection
// drawn on another domain pair or model names other scenes' pairs: it is cleared.
static void draw_selection_chip(const Session& s, UiState& ui) {
  if (ui.selection_scenes.empty()) return;
  const bool stale = ui.selection_pair != s.pair_index() || ui.selection_model != s.model();
  if (stale || (ImGui::SmallButton("x##clearselection"))) {
    ui.selection_scenes.clear();
    ui.selection_label.clear();
    ui.selection_pairs.reset();
    ui.order.clear();  // the app lists the scenes again
    return;
  }
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("clear the rock view's selection");
  ImGui::SameLine();
  ImGui::TextUnformatted(ui.selection_label.c_str());
}

namespace {
// The class every number of the window is about: the study's named classes, the classes its ground truth holds and
// "all classes" (class-blind); shown only where there is a choice, with why this class is the one shown.
void draw_class_menu(const Session& s, UiCommands& out) {
  const StudyLabels& labels = s.labels();
  const StudyClasses& classes = s.study().classes;
  std::vector<int> choices;
  for (size_t k = 0; k < classes.names.size(); ++k)
    if (!classes.names[k].empty()) choices.push_back(static_cast<int>(k));
  for (const auto& [cls, n] : labels.gt_boxes_by_class)
    if (std::find(choices.begin(), choices.end(), cls) == choices.end()) choices.push_back(cls);
  const int shown = s.study().config.rock_class;
  // A menu only where there is a choice: one class (the note may still say the task) needs none.
  const bool choice = choices.size() >= 2 || shown == kAllClasses;
  if (choice && ImGui::BeginCombo("class", class_statement(labels).c_str())) {
    for (int cls : choices)
      if (ImGui::Selectable(classes.describe(cls).c_str(), cls == shown) && cls != shown)
        out.class_word = std::to_string(cls);
    if (ImGui::Selectable("all classes (class-blind)", shown == kAllClasses) && shown != kAllClasses)
      out.class_word = "all";
    ImGui::EndCombo();
  }
  if (!s.class_note().empty()) text_disabled_wrapped_at_spaces(s.class_note());
}
}  // namespace

void draw_study_browser(const StudyView& v, UiState& ui, UiCommands& out) {
  const Session& s = *v.session;
  const Study& st = s.study();
  ImGui::TextWrapped("%s", st.root.c_str());
  if (s.read_only()) {
    // Why matters: a second window on the same study is read-only so that the first one's edits are not lost.
    ImGui::PushTextWrapPos(0);
    ImGui::TextColored({1, 0.6f, 0.2f, 1},
                       "read-only%s%s: edits stay in memory ('save as', below undo and redo, writes them elsewhere)",
                       s.read_only_reason().empty() ? "" : ": ", s.read_only_reason().c_str());
    ImGui::PopTextWrapPos();
  }
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
  if (st.models.empty()) {
    ImGui::TextColored({1, 0.8f, 0.3f, 1}, "No predictions in this study.");
    ImGui::TextWrapped(
        "IPD needs a detector's boxes. Make them with\n  ipd detect %s --onnx best.onnx --model yolo\n"
        "(or --detector classical), or put YOLO txt files under <domain>/predictions/<model>/, "
        "then reopen the study (File > Recent).",
        st.root.c_str());
  } else if (ImGui::BeginCombo("model", s.model().c_str())) {
    for (const auto& m : st.models) {
      const std::string label = m.trained_on.empty() ? m.name : m.name + " (" + m.trained_on + ")";
      if (ImGui::Selectable(label.c_str(), m.name == s.model())) out.model = m.name;
    }
    ImGui::EndCombo();
  }
  draw_class_menu(s, out);
  const double lowest = 0, highest = 1;
  if (ImGui::SliderScalar("conf >=", ImGuiDataType_Double, &ui.conf_threshold, &lowest, &highest, "%.2f"))
    out.conf_threshold = ui.conf_threshold = conf_slider_value(ui.conf_threshold);
  ImGui::SetNextItemWidth(-1);
  take_keyboard_if_asked(ui, UiState::Field::kSearch);
  keep_keyboard_after_enter(ImGui::InputTextWithHint("##filter", "filter: text, ipd>0.1, suspect, unreviewed (Ctrl+F)",
                                                     ui.filter, sizeof ui.filter,
                                                     ImGuiInputTextFlags_EnterReturnsTrue));
  if (!ui.filter_error.empty()) ImGui::TextColored({1, 0.5f, 0.3f, 1}, "%s", ui.filter_error.c_str());
  draw_selection_chip(s, ui);
  ImGui::TextDisabled("%s of %s%s", thousands(ui.order.size()).c_str(), counted(v.summaries->size(), "scene").c_str(),
                      v.loading.empty() ? "" : " so far (the rest is loading)");
  text_disabled_wrapped_at_spaces(review_progress_line(s.review_progress()));  // a narrow column clipped it
  ImGuiTableFlags flags = ImGuiTableFlags_Sortable | ImGuiTableFlags_RowBg | ImGuiTableFlags_ScrollY |
                          ImGuiTableFlags_BordersInnerV | ImGuiTableFlags_Resizable;
  // Columns that don't fit are never cut silently: a smaller font first (every column in sight at 1280 px), then
  // scrolling sideways rather than squeezing the scene names away.
  const auto& columns = browser_columns();
  const int n_columns = static_cast<int>(columns.size());
  int sorted = 0;  // the list's sort, given to each new table
  for (int k = 0; k < n_columns; ++k)
    if (columns[k].sort_key == ui.sort_column) sorted = k;
  const std::string* longest = longest_stem(v);
  auto needed_at = [&](float s) {
    ImGui::SetWindowFontScale(s);
    return list_width(longest);
  };
  const float avail = ImGui::GetContentRegionAvail().x;
  const float scale = table_font_scale(needed_at, avail);
  const float needed = needed_at(scale);
  // Always ScrollX: without it a table squeezes its fixed columns (and cuts their headers) when they don't fit.
  flags |= ImGuiTableFlags_ScrollX;
  ImGui::SetWindowFontScale(scale);  // this window's text from here on: the table only, reset below
  const std::string id = scaled_table_id("scenes", scale);
  if (ImGui::BeginTable(id.c_str(), n_columns, flags, {0, 0}, std::max(needed, avail))) {
    ImGui::TableSetupScrollFreeze(1, 1);
    setup_text_columns(browser_text_columns());
    // A new table (another font scale) starts from its default sort: it takes the list's.
    if (id != ui.list_table_id) {
      ui.list_table_id = id;
      ImGui::TableSetColumnSortDirection(
          sorted, ui.sort_descending ? ImGuiSortDirection_Descending : ImGuiSortDirection_Ascending, false);
    }
    if (ImGuiTableSortSpecs* spec = ImGui::TableGetSortSpecs(); spec && spec->SpecsDirty && spec->SpecsCount > 0) {
      ui.sort_column = columns[std::clamp<int>(spec->Specs[0].ColumnIndex, 0, n_columns - 1)].sort_key;
      ui.sort_descending = spec->Specs[0].SortDirection == ImGuiSortDirection_Descending;
      spec->SpecsDirty = false;
      ui.order.clear();  // the app recomputes it
    }
    // The scene in view, when it changed, scrolled into the list's middle unless its row is visible already
    // (a click on a row must not move the list under the mouse).
    int reveal = -1;
    if (ui.scene != ui.list_scrolled_to) {
      const auto at = std::find(ui.order.begin(), ui.order.end(), ui.scene);
      if (at != ui.order.end()) reveal = static_cast<int>(at - ui.order.begin());
      ui.list_scrolled_to = ui.scene;
    }
    ImGuiListClipper clipper;
    clipper.Begin(static_cast<int>(ui.order.size()));
    if (reveal >= 0) clipper.ForceDisplayRangeByIndices(reveal, reveal + 1);
    while (clipper.Step()) {
      for (int row = clipper.DisplayStart; row < clipper.DisplayEnd; ++row) {
        const int k = ui.order[row];
        const SceneSummary& m = (*v.summaries)[k];
        ImGui::TableNextRow();
        for (const auto& c : columns) {
          ImGui::TableNextColumn();
          if (row == reveal && &c == &columns.front()) {
            const ImVec2 p = ImGui::GetCursorScreenPos();
            if (!ImGui::IsRectVisible(p, {p.x + 1, p.y + ImGui::GetTextLineHeight()})) ImGui::SetScrollHereY(0.5f);
          }
          draw_scene_cell(c.sort_key, m, k, ui, out);
        }
      }
    }
    ImGui::EndTable();
  }
  ImGui::SetWindowFontScale(1.0f);
}

}  // namespace ipd::ui
