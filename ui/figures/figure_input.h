// Where a scene figure's input comes from: the study on disk (`ipd figure`) or the GUI's session (its
// current view, edits and threshold included). Both give a SceneFigureInput, drawn by the same code, so the
// CLI and the GUI's "Export figure…" produce the same figure for the same view.
#pragma once

#include <string>

#include "core/ipd/ipd.h"
#include "core/session/session.h"
#include "ui/figures/figure_scene.h"

namespace ipd::ui {

// The study on disk: pairs as `ipd table` finds them (fixed pairs files or registration), predictions below
// `conf_threshold` dropped (on top of study.yaml's). Domains are paired in study order, as the GUI does.
// The scene's review marks come from review/<A>__<B>.json; throws StudyError naming that file when it is bad.
SceneFigureInput scene_input_from_study(const StudyLabels& labels, const std::string& a, const std::string& b,
                                        const std::string& model, const std::string& stem, double conf_threshold,
                                        const RegistrationOptions& registration);

// The session's current domain pair (left, right), model, threshold and the scene's current pairs.
SceneFigureInput scene_input_from_session(const Session& session, int scene);

// Reads both pictures (when the study has them); a picture that can't be decoded is named in problem_*.
// File I/O: call it off the UI thread.
void load_pictures(SceneFigureInput& in, const Study& study);

// Draws the figure of kind "pairs" or "registration" (throws std::invalid_argument for other kinds).
void draw_scene_figure(DisplayList& out, const std::string& kind, const SceneFigureInput& in,
                       const FigureOptions& options);

}  // namespace ipd::ui
