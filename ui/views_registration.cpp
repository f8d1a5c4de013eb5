// The registration panel: the recorded search replayed (each hypothesis' sample joined across the sets,
// its inliers lit, the best-so-far score as a curve), then the refinement and the raw -> aligned motion.
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "views.h"

namespace ipd::ui {

namespace {

const char* kind_name(TraceStepKind k) {
  switch (k) {
    case TraceStepKind::kHypothesis: return "hypothesis";
    case TraceStepKind::kRefinement: return "refinement";
    case TraceStepKind::kIteration: return "EM iteration";
    case TraceStepKind::kPolish: return "polish";
  }
  return "";
}

}  // namespace

void draw_registration(const StudyView& v, UiState& ui, UiCommands& out) {
  const Session& s = *v.session;
  if (s.scenes().empty()) return;
  const SceneState& sc = s.scenes()[ui.scene];
  const bool have_rerun = v.rerun && !ui.rerun_discarded;
  const RegistrationReport& r = have_rerun ? *v.rerun : sc.automatic.registration;
  const auto& [da, db] = s.domain_pairs()[s.pair_index()];
  const int steps = static_cast<int>(r.trace.steps.size());
  ImGui::TextWrapped("%s -> %s: %s, %d trials, %d hypotheses, %d inliers, score %.4f, confidence %.2f", da.c_str(), db.c_str(),
              to_string(r.method), r.trials, r.hypotheses, r.inliers, r.score, r.confidence);
  if (r.ambiguous) ImGui::TextColored({1, 0.8f, 0.3f, 1}, "ambiguous: the overlap is too small to decide; check the pairs");
  ImGui::TextDisabled("stopped: %s%s%s", to_string(r.stop), r.note.empty() ? "" : "; ", r.note.c_str());
  ReplayState& rp = ui.replay;
  const float end = static_cast<float>(steps) + 1.0f;  // the steps, then one unit of raw -> aligned motion
  if (ImGui::Button(rp.playing ? "pause" : "play")) {
    rp.playing = !rp.playing;
    if (rp.playing && rp.position >= end) rp.position = 0;
  }
  ImGui::SameLine();
  ImGui::SetNextItemWidth(std::max(80.0f, ImGui::GetContentRegionAvail().x * 0.35f));
  if (ImGui::SliderFloat("##scrub", &rp.position, 0.0f, end, steps > 0 ? "step %.0f" : "%.2f")) rp.playing = false;
  ImGui::SameLine();
  ImGui::SetNextItemWidth(90);
  ImGui::SliderFloat("steps/s", &rp.speed, 1.0f, 2000.0f, "%.0f", ImGuiSliderFlags_Logarithmic);
  if (rp.playing) {
    // Hypotheses at the chosen speed; the final motion always takes 1.5 s.
    const float dt = ImGui::GetIO().DeltaTime;
    rp.position += rp.position < steps ? dt * rp.speed : dt / 1.5f;
    if (rp.position >= end) rp.position = end, rp.playing = false;
  }
  const auto& methods = registration_methods();
  ImGui::SetNextItemWidth(100);
  ImGui::Combo(
      "##method", &ui.rerun_method,
      [](void* table, int k, const char** name) {
        *name = (*static_cast<const std::vector<RegistrationMethodInfo>*>(table))[k].name;
        return true;
      },
      const_cast<std::vector<RegistrationMethodInfo>*>(&methods), static_cast<int>(methods.size()));
  if (ImGui::IsItemHovered() && ui.rerun_method >= 0 && ui.rerun_method < static_cast<int>(methods.size()))
    ImGui::SetTooltip("%s", methods[ui.rerun_method].description);
  ImGui::SameLine();
  ImGui::SetNextItemWidth(70);
  ImGui::InputInt("seed", &ui.rerun_seed, 0);
  ImGui::SameLine();
  if (ImGui::Button("re-run")) out.rerun_registration = true;
  if (have_rerun && !v.rerun_is_automatic) {
    ImGui::SameLine();
    if (ImGui::Button("apply these pairs")) {
      RockPairs pairs = v.rerun->pairs;  // registration's (A, B) order; the view may show (B, A)
      if (s.swapped())
        for (auto& p : pairs) std::swap(p.first, p.second);
      out.edits.push_back(Edit::replace(std::move(pairs)));
      ui.rerun_discarded = true;
    }
    ImGui::SameLine();
    if (ImGui::Button("discard")) ui.rerun_discarded = true;
  }
  // Where on the timeline: a step of the search, or the final motion.
  const int k = rp.position < steps ? replay_step(r, rp.position) : -1;
  const TraceStep* step = k >= 0 ? &r.trace.steps[k] : nullptr;
  if (step)
    ImGui::Text("%s %d of %d: score %.4f, best so far %.4f%s, %zu inliers", kind_name(step->kind), k + 1, steps,
                step->score, step->best_score, step->new_best ? " (new best)" : "", step->inliers_a.size());
  else if (steps == 0)
    ImGui::TextDisabled(v.rerun ? "no search recorded for this method" : "recording the search...");
  else
    ImGui::TextDisabled("final affine: raw -> aligned%s", r.trace.truncated ? " (trace truncated)" : "");

  // Canvas: B's centres (pink rings) fixed, A's moved by the current affine, in B's frame; the score curve
  // as a strip under it, full width (a column beside it left both too narrow and cut its caption).
  const ImVec2 p0 = ImGui::GetCursorScreenPos(), avail = ImGui::GetContentRegionAvail();
  const float text_h = ImGui::GetTextLineHeightWithSpacing();
  const float curve_h = steps > 0 ? std::clamp(avail.y * 0.25f, 36.0f, 110.0f) : 0.0f;
  const float below = steps > 0 ? curve_h + 2 * text_h + ImGui::GetStyle().ItemSpacing.y : 0.0f;
  const ImVec2 size{avail.x, std::max(40.0f, avail.y - below)};
  ImGui::InvisibleButton("##reg", size);
  ImDrawList* dl = ImGui::GetWindowDrawList();
  const auto& ga = s.labels().gt_of(da, sc.stem).boxes;
  const auto& gb = s.labels().gt_of(db, sc.stem).boxes;
  const Placement pl = place({p0.x + 10, p0.y + 10}, {size.x - 20, size.y - 20 - 3 * ImGui::GetTextLineHeight()}, s.study().config.image_width,
                             s.study().config.image_height, CanvasView{});
  dl->AddRect(pl.origin, {pl.origin.x + pl.size.x, pl.origin.y + pl.size.y}, IM_COL32(90, 90, 100, 255));
  const Affine2 m = step ? step->b_from_a
                         : interpolate_from_identity(r.affine, steps > 0 ? std::clamp(rp.position - steps, 0.0f, 1.0f)
                                                                         : std::clamp(rp.position, 0.0f, 1.0f));
  std::vector<ImVec2> pa, pb;
  for (const auto& b : ga) {
    const Eigen::Vector2d q = apply(m, b.centre());
    pa.push_back(pl.to_screen(q.x(), q.y()));
  }
  for (const auto& b : gb) pb.push_back(pl.to_screen(b.cx, b.cy));
  std::vector<char> lit(pa.size(), 0);
  if (step)
    for (int i : step->inliers_a)
      if (i >= 0 && i < (int)lit.size()) lit[i] = 1;
  if (!step) {
    // The final pairs: green when the aligned centres agree, orange for suspect pairs.
    const RockPairs& pairs = have_rerun ? v.rerun->pairs : sc.current.pairs;
    const SceneAudit& audit = s.audit(ui.scene);
    for (const auto& [i, j] : pairs) {
      if (i >= (int)pa.size() || j >= (int)pb.size()) continue;
      bool suspect = false;
      for (const auto& p : audit.pairs)
        if (p.a == i && p.b == j) suspect = p.suspect;
      dl->AddLine(pa[i], pb[j], suspect ? kSuspect : IM_COL32(90, 220, 120, 200), 1.5f);
    }
  }
  for (size_t q = 0; q < pb.size(); ++q) dl->AddCircle(pb[q], 7, kPink, 10, 1.5f);
  for (size_t q = 0; q < pa.size(); ++q)
    lit[q] ? dl->AddCircleFilled(pa[q], 4.5f, IM_COL32(120, 255, 140, 255), 8)
           : dl->AddCircleFilled(pa[q], 3.0f, IM_COL32(80, 170, 255, 255), 8);
  if (step) {
    // The sample: A rocks (where the hypothesis moves them) joined to the B rocks they were matched with.
    for (size_t q = 0; q < std::min(step->a_sample.size(), step->b_sample.size()); ++q) {
      const int i = step->a_sample[q], j = step->b_sample[q];
      if (i < 0 || i >= (int)pa.size() || j < 0 || j >= (int)pb.size()) continue;
      dl->AddLine(pa[i], pb[j], kTriple, 2.5f);
      dl->AddCircle(pb[j], 10, kTriple, 12, 2.5f);
    }
  }
  // The legend stays inside the plot (two lines), never under the score curve beside it.
  dl->PushClipRect(p0, {p0.x + size.x, p0.y + size.y}, true);
  const float line = ImGui::GetTextLineHeight();
  const char* legend[] = {"blue: A moved   green: inliers", "rings: B   bright: the sample", "orange: suspect"};
  for (int k = 0; k < 3; ++k)
    dl->AddText({p0.x + 14, p0.y + size.y - (3 - k) * line - 4}, IM_COL32(200, 200, 200, 255), legend[k]);
  dl->PopClipRect();
  if (steps > 0) {
    // Best-so-far score over the steps, with the current one marked.
    std::vector<float> best(steps);
    for (int q = 0; q < steps; ++q) best[q] = static_cast<float>(r.trace.steps[q].best_score);
    int news = 0;
    for (const auto& st : r.trace.steps) news += st.new_best;
    // One line of caption (two when the stop reason is long), then the strip.
    ImGui::PushTextWrapPos(ImGui::GetCursorPosX() + avail.x);
    ImGui::TextDisabled("best score so far: %d improvement%s over %d steps; %s", news, news == 1 ? "" : "s", steps,
                        r.trace.stop.c_str());
    ImGui::PopTextWrapPos();
    const ImVec2 c0 = ImGui::GetCursorScreenPos();
    const ImVec2 csz{avail.x - 4, std::max(30.0f, std::min(curve_h, ImGui::GetContentRegionAvail().y - 8))};  // a margin like the other sides
    ImGui::PlotLines("##best", best.data(), steps, 0, nullptr, FLT_MAX, FLT_MAX, csz);
    const float x = c0.x + csz.x * std::clamp(rp.position / steps, 0.0f, 1.0f);
    dl->AddLine({x, c0.y}, {x, c0.y + csz.y}, kHighlight, 1.5f);
  }
}

}  // namespace ipd::ui
