// The Rank window: `ipd rank`'s ranking of the study's renderer settings (every domain but the left one) by their
// IPD against the left domain for the current model, computed off the UI thread (app/studio/studio_rank.h) on
// the live session. A click on a row (or on a point of the sweep plot) shows that setting as the right-hand
// domain. When the settings differ in one `params` value (study.yaml), a small plot of the IPD along it, with
// its intervals, the best and the settings not distinguishable from it (ui/figures/figure_sweep.h's rule).
#pragma once

#include <string>
#include <vector>

#include "core/session/session_ranking.h"
#include "ui/gui/views.h"

namespace ipd::ui {

// The request for the session in view: its model, the left domain as the reference, `ipd rank`'s defaults.
SessionRankRequest rank_request(const Session& s);

// The window (open while ui.show_rank). `result`: the latest ranking (may be null or of an earlier request, then
// shown as "updating..."); `current`: it is of this session and request.
void draw_rank_window(const StudyView& v, const SessionRanking* result, bool current, UiState& ui, UiCommands& out);

// Choosing a ranked setting: the reference stays on the left, the setting goes to the right.
void choose_ranked_domain(const Session& s, const std::string& domain, UiCommands& out);

// One row of the window's table, as its cells read: "1", "hapke-w030", "w=0.3", "0.0412 [0.031, 0.052]", "78",
// "+0.0123 [−0.004, 0.021]" (the typographic minus), "0.0312", "best" / "≈ best" / "".
std::vector<std::string> rank_row_cells(const RankedCandidate& r);

}  // namespace ipd::ui
