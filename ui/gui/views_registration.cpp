// The registration panel: the recorded search replayed (each hypothesis' sample joined across the sets,
// its inliers lit, the best-so-far score as a curve), then the refinement and the raw -> aligned motion.
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "ui/figures/score_curve.h"
#include "ui/gui/canvas_imgui.h"
#include "ui/gui/stats_panels.h"
#include "ui/gui/studio_layout.h"
#include "ui/gui/views.h"

namespace ipd::ui {

namespace {

const char* kind_name(TraceStepKind k) {
  switch (k) {
    case TraceStepKind::kHypothesis:
      return "hypothesis";
    case TraceStepKind::kRefinement:
      return "refinement";
    case TraceStepKind::kIteration:
      return "EM iteration";
    case TraceStepKind::kPolish:
      return "final fit";  // the polished, searched or least-squares fit that goes out
  }
  return "";
}

}  // namespace

std::string registration_summary(const std::string& a, const std::string& b, const RegistrationReport& r) {
  // cpd counts EM iterations; paper and consensus draw trials (samples) and score hypotheses.
  const std::string searched =
      r.method == RegistrationMethod::kCpd
          ? counted(r.em_iterations, "EM iteration")
          : counted(r.samples, "trial") + ", " + counted(r.hypotheses, "hypothesis", "hypotheses");
  return a + " -> " + b + ": " + to_string(r.method) + ", " + searched + ", " + counted(r.inliers, "inlier") + ", " +
         fit_text(r.fit, 4) + ", confidence " + fixed(r.confidence, 2);
}

std::string replay_step_line(const TraceStep& step, FitMeasure measure, int k, int steps) {
  return "step " + thousands(k + 1) + " of " + thousands(steps) + " (" + kind_name(step.kind) +
         "): " + fit_text({measure, step.fit}, 4) + ", best so far " + fixed(step.best_fit, 4) +
         (step.new_best ? " (new best)" : "") + ", " + counted(static_cast<long>(step.inliers_a.size()), "inlier");
}

RegistrationCanvas registration_canvas(ImVec2 p0, ImVec2 size, float line_h) {
  RegistrationCanvas c;
  c.legend_top = p0.y + size.y - 3 * line_h - 4;
  c.plot_min = p0;
  c.plot_max = {p0.x + size.x, std::max(p0.y, c.legend_top - 2)};
  c.box_min = {p0.x + 10, p0.y + 10};
  c.box_size = {std::max(0.0f, size.x - 20), std::max(0.0f, c.plot_max.y - p0.y - 20)};
  return c;
}

std::string trace_cap_note(int steps, int hypotheses) {
  return "the replay holds the first " + thousands(steps) + " steps of " +
         counted(hypotheses, "hypothesis", "hypotheses") + " tried (the recording stops at " + thousands(steps) +
         "; the search went on)";
}

std::string registration_stop_line(const RegistrationReport& r) {
  std::string line = std::string("stopped: ") + to_string(r.stop);
  if (r.note.empty()) return line;
  if (r.stop != StopReason::kTimeBudget) return line + "; " + r.note;
  // The note's sentences are joined by "; " (add_note); each one the budget cut short starts with the reason.
  static const std::string kSpent = "time budget spent";
  std::string rest = r.note;
  for (size_t from = 0; from < rest.size();) {
    if (rest.compare(from, kSpent.size(), kSpent) == 0) {
      size_t cut = kSpent.size();
      if (rest.compare(from + cut, 2, ": ") == 0)
        cut += 2;  // "time budget spent: EM's alignment, ..."
      else if (rest.compare(from + cut, 1, " ") == 0)
        cut += 1;  // "time budget spent while setting up ..."
      rest.erase(from, cut);
    }
    const size_t next = rest.find("; ", from);
    from = next == std::string::npos ? rest.size() : next + 2;
  }
  return line + "; " + rest;
}

std::string ambiguity_line(const RegistrationReport& r) {
  std::string line = std::string("ambiguous: ") + ambiguity_reason(r.ambiguity) + "; check the pairs";
  if (r.stop == StopReason::kTimeBudget) line += ", or re-run with a larger time budget, which may settle it";
  return line;
}

std::string no_steps_line(const RegistrationReport& r, bool rerun) {
  if (!rerun) return "recording the search...";
  if (r.stop == StopReason::kTimeBudget) return "no search recorded: the time budget was spent before it began";
  return "no search recorded for this method";
}

float rerun_budget_ms(const UiState& ui, const RegistrationOptions& study) {
  return ui.rerun_budget_ms >= 0 ? ui.rerun_budget_ms : static_cast<float>(study.time_budget_ms.value_or(0));
}

std::optional<double> rerun_time_budget(const UiState& ui, const RegistrationOptions& study) {
  if (ui.rerun_budget_ms < 0) return study.time_budget_ms;  // the study's, unrounded
  if (ui.rerun_budget_ms > 0) return static_cast<double>(ui.rerun_budget_ms);
  return std::nullopt;
}

void draw_registration(const StudyView& v, UiState& ui, UiCommands& out) {
  const Session& s = *v.session;
  if (s.scenes().empty()) return;
  const SceneState& sc = s.scenes()[ui.scene];
  if (!sc.registered && !(v.rerun && !ui.rerun_discarded)) {
    text_disabled_wrapped_at_spaces(
        "registering this scene: it was opened with its hand pairs, and its registration is computed when "
        "it is first shown");
    return;
  }
  const bool have_rerun = v.rerun && !ui.rerun_discarded;
  const RegistrationReport& r = have_rerun ? *v.rerun : sc.automatic.registration;
  const auto& [da, db] = s.domain_pairs()[s.pair_index()];
  const int steps = static_cast<int>(r.trace.steps.size());
  text_wrapped_at_spaces(registration_summary(da, db, r));
  // The registration maps the pair's first domain onto its second, whichever the view puts on the left.
  if (s.swapped())
    text_disabled_wrapped_at_spaces("(the view is swapped: " + db + " on the left, " + da + " on the right)");
  if (r.ambiguous) text_coloured_wrapped_at_spaces({1, 0.8f, 0.3f, 1}, ambiguity_line(r));
  text_disabled_wrapped_at_spaces(registration_stop_line(r));
  ReplayState& rp = ui.replay;
  const float end = static_cast<float>(steps) + 1.0f;  // the steps, then one unit of raw -> aligned motion
  // A position left from another registration's longer trace (a discarded re-run) ends at this one's motion.
  rp.position = std::min(rp.position, end);
  if (ImGui::Button(rp.playing ? "pause" : "play")) {
    rp.playing = !rp.playing;
    if (rp.playing && rp.position >= end) rp.position = 0;
  }
  // The scrubber names the same step as the line under it ("step K of N"), K = replay_step() + 1.
  const int shown = rp.position < steps ? replay_step(r, rp.position) : -1;
  const std::string scrub_label = steps == 0   ? "raw -> aligned"
                                  : shown >= 0 ? "step " + thousands(shown + 1) + " of " + thousands(steps)
                                               : "final motion";
  // Wide enough for its longest label ("step 5,000 of 5,000", or "final motion" on a short search) with
  // the grab clear of the centred text at either end: on the play button's line when that fits, else on a
  // line of its own, never cut ("step 2,316 of 5,0") nor covered by the grab ("final motio").
  const float longest =
      std::max({ImGui::CalcTextSize(("step " + thousands(steps) + " of " + thousands(steps)).c_str()).x,
                ImGui::CalcTextSize("final motion").x, ImGui::CalcTextSize("raw -> aligned").x});
  const float scrub_w = longest + 2 * (ImGui::GetStyle().GrabMinSize + ImGui::GetStyle().FramePadding.x + 2);
  same_line_if_fits(scrub_w);
  ImGui::SetNextItemWidth(std::max(80.0f, std::min(ImGui::GetContentRegionAvail().x, scrub_w)));
  if (ImGui::SliderFloat("##scrub", &rp.position, 0.0f, end, scrub_label.c_str())) rp.playing = false;
  same_line_if_fits(90 + ImGui::CalcTextSize("steps/s").x + ImGui::GetStyle().ItemInnerSpacing.x);
  ImGui::SetNextItemWidth(90);
  ImGui::SliderFloat("steps/s", &rp.speed, 1.0f, 2000.0f, "%.0f", ImGuiSliderFlags_Logarithmic);
  if (rp.playing) {
    // Hypotheses at the chosen speed; the final motion always takes 1.5 s.
    const float dt = ImGui::GetIO().DeltaTime;
    rp.position += rp.position < steps ? dt * rp.speed : dt / 1.5f;
    if (rp.position >= end) rp.position = end, rp.playing = false;
  }
  // The combo shows the method of the registration on display; choosing another re-runs with it.
  const auto& methods = registration_methods();
  int displayed = 0;
  for (size_t m = 0; m < methods.size(); ++m)
    if (methods[m].method == r.method) displayed = static_cast<int>(m);
  int chosen = displayed;
  ImGui::SetNextItemWidth(100);
  if (ImGui::Combo(
          "##method", &chosen,
          [](void* table, int k, const char** name) {
            *name = (*static_cast<const std::vector<RegistrationMethodInfo>*>(table))[k].name;
            return true;
          },
          const_cast<std::vector<RegistrationMethodInfo>*>(&methods), static_cast<int>(methods.size())) &&
      chosen != displayed) {
    ui.rerun_method = chosen;
    out.rerun_registration = true;
  }
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("%s\n(the method of the registration shown; pick another to re-run with it)",
                      methods[displayed].description);
  ImGui::SameLine();
  ImGui::SetNextItemWidth(70);
  ImGui::InputInt("seed", &ui.rerun_seed, 0);
  // The time budget the re-run gets: the study's (registration.budget_ms) until edited here; 0 is none.
  float budget = rerun_budget_ms(ui, s.study().config.registration);
  same_line_if_fits(70 + ImGui::CalcTextSize("budget ms").x + ImGui::GetStyle().ItemInnerSpacing.x);
  ImGui::SetNextItemWidth(70);
  // No budget reads "none", not a bare 0; the whole text is selected on a click, so typing a number replaces it.
  // A number too large for a float (inf) is no limit either.
  if (ImGui::InputFloat("budget ms", &budget, 0, 0, budget > 0 ? "%g" : "none", ImGuiInputTextFlags_AutoSelectAll))
    ui.rerun_budget_ms = std::isfinite(budget) ? std::max(0.0f, budget) : 0.0f;
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip(
        "time budget of the re-run, in milliseconds (0 or none: no limit)\n"
        "when it is spent the registration stops and keeps what it found so far\n"
        "starts at study.yaml's registration.budget_ms");
  same_line_if_fits(button_width("re-run"));
  if (ImGui::Button("re-run")) ui.rerun_method = displayed, out.rerun_registration = true;
  if (have_rerun && !v.rerun_is_automatic) {
    same_line_if_fits(button_width("apply these pairs"));
    if (ImGui::Button("apply these pairs")) {
      RockPairs pairs = v.rerun->pairs;  // registration's (A, B) order; the view may show (B, A)
      if (s.swapped())
        for (auto& p : pairs) std::swap(p.first, p.second);
      out.edits.push_back(Edit::replace(std::move(pairs)));
      ui.rerun_discarded = true;
    }
    same_line_if_fits(button_width("discard"));
    if (ImGui::Button("discard")) ui.rerun_discarded = true;
  }
  // Where on the timeline: a step of the search, or the final motion.
  const int k = shown;
  const TraceStep* step = k >= 0 ? &r.trace.steps[k] : nullptr;
  if (step)
    text_wrapped_at_spaces(replay_step_line(*step, fit_measure_of(r.method), k, steps));
  else if (steps == 0)
    text_disabled_wrapped_at_spaces(no_steps_line(r, have_rerun));
  else
    ImGui::TextDisabled("final affine: raw -> aligned");
  if (r.trace.truncated) text_disabled_wrapped_at_spaces(trace_cap_note(steps, r.hypotheses));

  // Canvas: B's centres (pink rings) fixed, A's moved by the current affine, in B's frame; the score curve
  // as a strip under it, full width (a column beside it left both too narrow and cut its caption).
  const ImVec2 p0 = ImGui::GetCursorScreenPos(), avail = ImGui::GetContentRegionAvail();
  const float text_h = ImGui::GetTextLineHeightWithSpacing();
  // Room for the curve, its step axis's labels and its caption below it, as many lines as the caption wraps to
  // (it took three lines at 1024 px where two were kept, and the curve was squashed to nothing).
  int news = 0;
  for (const auto& st : r.trace.steps) news += st.new_best;
  const FitMeasure measure = fit_measure_of(r.method);
  const std::string caption = "best fit so far (" + std::string(fit_measure_name(measure)) + ", " +
                              score_direction(measure) + "): " + counted(news, "improvement") + " over " +
                              counted(steps, "step") + "; " + r.trace.stop;
  const size_t caption_lines = wrap_at_spaces(caption, std::max(40.0f, avail.x), [](const std::string& t) {
                                 return ImGui::CalcTextSize(t.c_str()).x;
                               }).size();
  const float curve_h = steps > 0 ? std::clamp(avail.y * 0.25f, 36.0f + text_h, 110.0f + text_h) : 0.0f;
  const float below =
      steps > 0 ? curve_h + (float(caption_lines) + 1) * text_h + ImGui::GetStyle().ItemSpacing.y : 0.0f;
  // At least 80 px for the picture box itself, besides the three legend lines and margins: a short panel
  // scrolls rather than squeezing the rings into one blob (as at 700 x 800).
  const float min_canvas = 3 * ImGui::GetTextLineHeight() + 4 + 2 + 20 + 80;
  const ImVec2 size{avail.x, std::max(min_canvas, avail.y - below)};
  ImGui::InvisibleButton("##reg", size);
  ImDrawList* dl = ImGui::GetWindowDrawList();
  const auto& ga = s.labels().gt_of(da, sc.stem).boxes;
  const auto& gb = s.labels().gt_of(db, sc.stem).boxes;
  const RegistrationCanvas canvas = registration_canvas(p0, size, ImGui::GetTextLineHeight());
  const Placement pl =
      place(canvas.box_min, canvas.box_size, s.study().config.image_width, s.study().config.image_height, CanvasView{});
  // A hypothesis can throw A's centres far off the picture: everything is drawn inside the plot's own rect,
  // never over the text above it or the legend and curve below.
  dl->PushClipRect(canvas.plot_min, canvas.plot_max, true);
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
    const PairAuditIndex audit_of(s.audit(ui.scene));
    for (const auto& [i, j] : pairs) {
      if (i >= (int)pa.size() || j >= (int)pb.size()) continue;
      const PairAudit* audit = audit_of.find(i, j);
      const bool suspect = audit && audit->suspect;
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
  dl->PopClipRect();
  // The legend stays inside the canvas (three lines), under the plot, never under the score curve.
  dl->PushClipRect(p0, {p0.x + size.x, p0.y + size.y}, true);
  const float line = ImGui::GetTextLineHeight();
  // The domains by name, as every other panel names them (the registration maps the pair's first onto its
  // second, whichever the view puts on the left).
  const std::string legend[] = {"blue: " + da + " moved   green: inliers", "rings: " + db + "   frame: its picture",
                                "bright: the sample   orange: suspect"};
  for (int k = 0; k < 3; ++k)
    dl->AddText({p0.x + 14, p0.y + size.y - (3 - k) * line - 4}, IM_COL32(200, 200, 200, 255), legend[k].c_str());
  dl->PopClipRect();
  if (steps > 0) {
    // Best-so-far score over the steps, with axes, which way is better and the current step marked.
    ScoreCurveInput curve;
    curve.measure = measure;
    for (const auto& st : r.trace.steps) curve.best.push_back(st.best_fit);
    curve.current = shown >= 0 ? shown : steps - 1;  // the final motion: after the last step
    text_disabled_wrapped_at_spaces(caption);        // then the strip
    const ImVec2 c0 = ImGui::GetCursorScreenPos();
    // Never under the height its labels need: a short panel scrolls instead.
    const ImVec2 csz{avail.x - 4, std::max(36.0f + text_h, std::min(curve_h, ImGui::GetContentRegionAvail().y -
                                                                                 8))};  // a margin like the other sides
    ImGui::Dummy(csz);
    ImGuiCanvas chart(ImGui::GetWindowDrawList(), c0, 1, {});
    const TextStyle text = gui_text();
    draw_score_curve(chart, text, layout_score_curve(chart, text, curve, {0, 0, csz.x, csz.y}), gui_colours());
  }
}

}  // namespace ipd::ui
