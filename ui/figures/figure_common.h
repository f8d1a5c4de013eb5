// Pieces every figure kind uses: colours, wrapped text, a legend row, labels placed without collisions.
#pragma once

#include <string>
#include <vector>

#include "ui/canvas/canvas.h"
#include "core/geometry/label_placer.h"

namespace ipd::ui::fig {

constexpr Colour kInk = rgb(20, 20, 20), kGrey = rgb(110, 110, 110), kPinkC = rgb(255, 105, 200),
                 kRedC = rgb(235, 40, 40), kUnpairedC = rgb(160, 160, 160), kBlueC = rgb(40, 110, 230),
                 kGreenC = rgb(40, 160, 80), kBackdrop = rgb(0, 0, 0, 165), kWhite = rgb(255, 255, 255);

// The blank border of every figure kind, on all four sides, in points: nothing is drawn inside it, so a
// figure placed in a paper never has ink touching its edge.
constexpr double kFigureMargin = 4.0;

// Breaks `text` at spaces into lines no wider than `width` (a word longer than the width gets a line).
std::vector<std::string> wrap(Canvas& c, const TextStyle& st, const std::string& text, double width);
// Draws wrapped text from (x, y) down; returns the height used.
double draw_wrapped(Canvas& c, Pt at, const TextStyle& st, const std::string& text, double width);

enum class Swatch { kBox, kDot, kRing, kLine, kStruckBox };  // kStruckBox: a box with a diagonal
struct LegendItem {
  Swatch swatch;
  Colour colour;
  std::string text;
};
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
  double keep_off_clearance = 0;  // LabelRequest::keep_off_clearance
};
// Places labels inside `bounds` avoiding each other and `taken`; draws them (on a dark backdrop, leaders
// in the label's colour) and returns how many were left out; `placement` (optional): where each went.
int draw_labels(Canvas& c, const std::vector<Label>& labels, const PtRect& bounds, const std::vector<PtRect>& taken,
                bool backdrop, LabelPlacement* placement = nullptr);
// A leader's width: thin enough not to read as a box edge, thick enough to survive print (~0.6 pt).
constexpr double kLeaderPt = 0.6;
// The clearance an exclusive label keeps from the other exclusive targets, in points.
constexpr double kExclusiveClearancePt = 2.0;

// "3 labels left out (no room at this size)"-style footnote; returns the height used (0 when none).
double draw_footnote(Canvas& c, Pt at, double width, double font_pt, int left_out);

// Text style helpers: never below kMinTextPt.
TextStyle style(double size_pt, Colour colour, bool bold = false);

}  // namespace ipd::ui::fig
