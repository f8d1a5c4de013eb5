// Pieces every figure kind uses: colours, wrapped text, a legend row, labels placed without collisions.
#pragma once

#include <string>
#include <vector>

#include "core/geometry/label_placer.h"
#include "ui/canvas/canvas.h"

namespace ipd::ui::fig {

constexpr Colour kInk = rgb(20, 20, 20), kGrey = rgb(110, 110, 110), kPinkC = rgb(255, 105, 200),
                 kRedC = rgb(235, 40, 40), kUnpairedC = rgb(160, 160, 160), kBlueC = rgb(40, 110, 230),
                 kGreenC = rgb(40, 160, 80), kBackdrop = rgb(0, 0, 0, 165), kWhite = rgb(255, 255, 255);

// Fig. 1's boxes must survive greyscale print and the common colour-vision deficiencies, on dark and on
// bright terrain: GT and predictions differ by line style (solid, dashed), by luminance (a light stroke on a
// dark halo, a dark stroke on a light halo) and by hue along the blue-yellow axis every deficiency keeps
// (Okabe-Ito yellow and blue); the halo keeps each stroke apart from the terrain whatever its brightness.
constexpr Colour kGtC = rgb(240, 228, 66), kGtUnpairedC = rgb(175, 175, 175), kPredC = rgb(0, 114, 178),
                 kPredTextC = rgb(86, 180, 233), kDarkHalo = rgb(0, 0, 0, 210), kLightHalo = rgb(255, 255, 255, 225);
// The halo's width over the stroke's.
constexpr double kHaloRatio = 2.4;

// The blank border of every figure kind, on all four sides, in points: nothing is drawn inside it, so a
// figure placed in a paper never has ink touching its edge.
constexpr double kFigureMargin = 4.0;

// Breaks `text` at spaces into lines no wider than `width` (a word longer than the width gets a line).
std::vector<std::string> wrap(Canvas& c, const TextStyle& st, const std::string& text, double width);
// Draws wrapped text from (x, y) down; returns the height used.
double draw_wrapped(Canvas& c, Pt at, const TextStyle& st, const std::string& text, double width);

// kStruckBox: a box with a diagonal; kDashedBox: a prediction's dashed box. kOutline, kDashedOutline: a line
// sample, solid or dashed, for the figures that draw outlines (masks) rather than boxes.
enum class Swatch { kBox, kDot, kRing, kLine, kStruckBox, kDashedBox, kOutline, kDashedOutline };
struct LegendItem {
  Swatch swatch;
  Colour colour;
  std::string text;
  Colour halo = rgb(0, 0, 0, 0);  // drawn under the swatch's strokes, as on the pictures (alpha 0: none)
};

// A dashed outline keeps at least kMinDashes dashes around its perimeter, so a small prediction's outline reads
// as dashed (not as a broken solid line) at a single column and in greyscale; its dashes never get shorter than
// kMinDashPt (a dotted line), and never longer than the `dash` asked for.
constexpr int kMinDashes = 5;
constexpr double kMinDashPt = 0.8;
// The dash length for an outline of `perimeter_pt`: min(dash, perimeter / (kMinDashes x 1.6)), at least kMinDashPt.
double outline_dash(double perimeter_pt, double dash);

// A box outline in dashes starting at each corner (so corners always show), `dash` long with `dash` * 0.6 gaps
// (outline_dash of its perimeter).
void dashed_rect(Canvas& c, const PtRect& r, Colour colour, double width_pt, double dash);
// A closed polygon's edges dashed like dashed_rect's (a predicted outline), outline_dash of its perimeter.
void dashed_polygon(Canvas& c, const std::vector<Pt>& points, Colour colour, double width_pt, double dash);
// Items flowing left to right, wrapping to new rows; returns the height used.
double draw_legend(Canvas& c, Pt at, double width, const TextStyle& st, const std::vector<LegendItem>& items);

// A label to place: the text, its style, what it names (in points) and whether it sits on a dark backdrop.
struct Label {
  std::string text;
  TextStyle style;
  PtRect target;
  bool exclusive = false;  // must read as its own target's among the exclusive ones (LabelRequest::exclusive)
  int group = 0;           // LabelRequest::group
  std::vector<PtRect> keep_off = {};  // LabelRequest::keep_off, in points
  double keep_off_clearance = 0;      // LabelRequest::keep_off_clearance
  bool nearest_own = false;           // LabelRequest::nearest_own
};
// Places labels inside `bounds` avoiding each other and `taken`; draws them (on a dark backdrop, leaders
// in the label's colour) and returns how many were left out; `placement` (optional): where each went.
int draw_labels(Canvas& c, const std::vector<Label>& labels, const PtRect& bounds, const std::vector<PtRect>& taken,
                bool backdrop, LabelPlacement* placement = nullptr);
// The two halves of draw_labels, for figures that decide what to show from where labels would go.
LabelPlacement place_figure_labels(Canvas& c, const std::vector<Label>& labels, const PtRect& bounds,
                                   const std::vector<PtRect>& taken);
void draw_placed_labels(Canvas& c, const std::vector<Label>& labels, const LabelPlacement& placement, bool backdrop);
// A leader's width: thin enough not to read as a box edge, thick enough to survive print (~0.6 pt).
constexpr double kLeaderPt = 0.6;
// The clearance an exclusive label keeps from the other exclusive targets, in points.
constexpr double kExclusiveClearancePt = 2.0;

// "3 labels left out: no room at this size (try HINT)" footnote (no parentheses when `hint` is empty);
// returns the height used (0 when none).
double draw_footnote(Canvas& c, Pt at, double width, double font_pt, int left_out, const std::string& hint);
// What makes a figure wider: "--column double" for a single-column figure, "a larger --width-in" otherwise
// (a figure already double-column gains nothing from --column double).
std::string wider_hint(double width_in);

// Text style helpers: never below kMinTextPt.
TextStyle style(double size_pt, Colour colour, bool bold = false);

}  // namespace ipd::ui::fig
