// Fig. 1 (pairs) and Fig. 2 (registration) of one scene, drawn on the figure canvas from exactly what a
// view shows: domains, model, threshold, current pairs (edits included), excluded rocks, pictures. The CLI
// builds the input from the study on disk, the GUI from its session (figure_input.h); both draw here.
#pragma once

#include <string>
#include <vector>

#include "core/geometry/geometry.h"
#include "core/registration/registration.h"
#include "ui/canvas/canvas.h"
#include "ui/figures/figure_options.h"

namespace ipd::ui {

struct SceneFigureInput {
  std::string stem, a, b, model;  // left domain a, right domain b
  double conf_threshold = 0;      // predictions below it are already dropped; shown in the title
  std::vector<Box> gt_a, gt_b, pred_a, pred_b;
  RockPairs pairs;  // (index in a, index in b), in pair-number order
  std::vector<int> excluded_a, excluded_b;
  bool pairs_fixed = false;  // by hand (file or GUI edit) rather than registration
  // The scene's pairs file no longer matches its label files: its hand pairs are set aside (registration's
  // are drawn), and the figure's note says so.
  bool pairs_stale = false;
  Affine2 affine = identity_affine();  // a -> b, for Fig. 2
  std::string method;                  // registration method, for Fig. 2's title
  cv::Mat picture_a, picture_b;        // BGR, empty when there is none
  std::string problem_a, problem_b;    // why a picture is missing
  int image_w = 1936, image_h = 1216;  // aspect when there is no picture
  std::string label_fingerprint;       // of the study's label files (label_set_fingerprint), for the metadata
  std::string class_name;              // the class shown (provenance_class): "" for an unnamed one-class study
  Task task = Task::kDetect;           // what a performance value is (box or mask IoU)
  // The scene's review marks (core/session/review_state.h), so the figure's note says what the table's does.
  bool reviewed = false;
  int pairs_checked = 0;  // checked as correct and still pairs
};

// The scene's IPD and number of pairs for the title, from the input's boxes and pairs.
struct SceneNumbers {
  double ipd = 0;  // NaN without pairs
  int pairs = 0;
};
SceneNumbers scene_numbers(const SceneFigureInput& in);

// Where the pictures went (points), for tests.
struct PairsLayout {
  PtRect left, right;
  bool stacked = false;  // the pictures one under the other (FigureOptions::panels)
  int unnumbered = 0;    // pairs in view on both pictures, numbered on neither
};
// Draws the figure into `out` and sets its page size (width from the options, height from the content).
// Where a labels-only panel's notice ("no picture") goes: of the panel's top, bottom, corners, sides and middle
// (`inset` inside its edge), the first place whose text box of `size` covers the least area of `boxes` (the
// rocks' boxes on the page), so the notice is never drawn across rocks when a place clear of them exists.
PtRect place_notice(const PtRect& panel, Pt size, const std::vector<PtRect>& boxes, double inset);

PairsLayout draw_pairs_figure(DisplayList& out, const SceneFigureInput& in, const FigureOptions& options);
void draw_registration_figure(DisplayList& out, const SceneFigureInput& in, const FigureOptions& options);

}  // namespace ipd::ui
