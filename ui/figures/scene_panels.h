// The pieces both scene figures (pairs: figure_scene.cpp, registration: figure_registration.cpp) share: where
// normalised picture coordinates go on a panel, the panels' arrangement (side by side or stacked), pair numbers
// placed on both panels or on neither, the title and the note on unnumbered pairs. Internal to ipd_figures.
#pragma once

#include <functional>
#include <set>
#include <string>
#include <vector>

#include "ui/figures/figure_common.h"
#include "ui/figures/figure_scene.h"

namespace ipd::ui::scene {

using fig::Label;

constexpr double kMargin = fig::kFigureMargin;

// The aspect (width / height) of a panel showing `crop` of the scene's pictures.
double aspect_of(const SceneFigureInput& in, const Crop& crop);

// Normalised picture coordinates -> points inside a panel showing `crop`.
struct PanelMap {
  PtRect panel;
  Crop crop;
  Pt operator()(double x, double y) const {
    return {panel.x0 + (x - crop.x0) / (crop.x1 - crop.x0) * panel.width(),
            panel.y0 + (y - crop.y0) / (crop.y1 - crop.y0) * panel.height()};
  }
  // The box on the page, clipped to the panel; false when it is entirely outside.
  bool box(const Box& b, PtRect& out) const {
    const Pt p0 = (*this)(b.x0(), b.y0()), p1 = (*this)(b.x1(), b.y1());
    out = {std::max(p0.x, panel.x0), std::max(p0.y, panel.y0), std::min(p1.x, panel.x1), std::min(p1.y, panel.y1)};
    return out.x0 < out.x1 && out.y0 < out.y1;
  }
  PtRect raw(const Box& b) const {
    const Pt p0 = (*this)(b.x0(), b.y0()), p1 = (*this)(b.x1(), b.y1());
    return {p0.x, p0.y, p1.x, p1.y};
  }
  std::vector<Pt> outline(const Outline& o) const {
    std::vector<Pt> out;
    out.reserve(o.points.size());
    for (const Eigen::Vector2d& p : o.points) out.push_back((*this)(p.x(), p.y()));
    return out;
  }
};

// The labels of one side and, for each, the pair it numbers (0: an unpaired rock's "x" index, a plain
// index or a confidence).
struct SideLabels {
  std::vector<Label> labels;
  std::vector<int> pair;
};

// Two panels' labels placed so that a pair's number shows on both panels or on neither: a reader matches a
// pair by its number. Pairs that fit on one side only are dropped from both and the placement redone
// (dropping only frees room) until every shown pair number shows twice. `make(side, unnumbered)` gives a
// side's labels without the numbers of `unnumbered`.
struct TwoPanelLabels {
  SideLabels side[2];
  LabelPlacement placed[2];
  std::set<int> unnumbered;        // pairs in view on both panels, numbered on neither
  int left_out_other[2] = {0, 0};  // labels not shown that number no pair in view on both panels
};
TwoPanelLabels place_on_both(Canvas& c, const std::function<SideLabels(int, const std::set<int>&)>& make,
                             const PtRect bounds[2], const std::vector<PtRect> taken[2]);

// "N pairs unnumbered: ..." for both scene figures.
std::string unnumbered_note(int n, const FigureOptions& o);
// The figure's title, wrapped at the top margin; returns the y below it.
double draw_title(Canvas& c, const std::string& title, const FigureOptions& o);

// Where a scene figure's two panels go: side by side (each half the width) or stacked (each the whole width,
// the second under the first), from y down, with a caption above each.
struct PanelPlan {
  PtRect panel[2];
  Pt caption[2];  // top left of each panel's caption
  double bottom = 0;
};
PanelPlan plan_panels(Canvas& c, const SceneFigureInput& in, const FigureOptions& o, double y, bool stacked);

// Whether the figure should stack its panels: --panels stacked, or (auto) when side by side numbers fewer than
// kNumberedShare of the pairs in view and stacked numbers more. `draw(out, stacked)` draws the figure and returns
// its counts.
struct Numbered {
  int pairs = 0, unnumbered = 0;
};
constexpr double kNumberedShare = 0.8;
bool choose_stacked(const FontMetrics& metrics, const FigureOptions& o,
                    const std::function<Numbered(DisplayList&, bool)>& draw);

// --crop auto: the region of the pictures holding every GT box of both sides (and, for the registration figure,
// every A centre moved by the affine) with kCropMargin of the picture around it for the numbers beside the
// rocks, of the picture's own shape (so the panels keep their height and the rocks grow), within the picture.
// The whole picture when there are no rocks.
constexpr double kCropMargin = 0.05;
Crop rocks_crop(const SceneFigureInput& in, bool registration);

}  // namespace ipd::ui::scene
