// What every figure kind shares: physical size, font size, layers, crop; validated once.
#pragma once

#include <optional>
#include <string>

namespace ipd::ui {

constexpr double kSingleColumnIn = 3.5, kDoubleColumnIn = 7.16;  // IEEE column widths
constexpr double kMinTextPt = 6;                                 // nothing smaller on the page
// A journal's smallest print size: no text goes below it unless --font-pt itself asks for smaller.
constexpr double kReadablePt = 7;
// Footnotes, confidences, ticks and intervals: a little smaller than the body, never under kReadablePt
// (or under --font-pt when that is smaller still).
double secondary_pt(double font_pt);

struct FigureLayers {
  bool gt = true, pred = true, conf = false, indices = true, pairs = true, legend = true;
  bool operator==(const FigureLayers& o) const;
};
// "gt,pred,conf,indices,pairs,legend" (any subset, any order); throws std::invalid_argument naming the bad
// layer and the accepted ones.
FigureLayers parse_layers(const std::string& list);
std::string to_string(const FigureLayers& layers);
// All but conf for a single column (confidences don't fit), all for wider figures.
FigureLayers default_layers(double width_in);

// A region of the pictures in normalised coordinates (0..1, y down).
struct Crop {
  double x0 = 0, y0 = 0, x1 = 1, y1 = 1;
  bool whole() const { return x0 == 0 && y0 == 0 && x1 == 1 && y1 == 1; }
};
// "X0,Y0,X1,Y1"; throws std::invalid_argument unless 0 <= X0 < X1 <= 1 and 0 <= Y0 < Y1 <= 1.
Crop parse_crop(const std::string& text);

// How the pairs and registration figures place their two pictures: side by side, stacked (each the figure's
// whole width, the second under the first), or (auto) side by side unless that leaves more than a fifth of the
// pairs unnumbered and stacking numbers more (scene::choose_stacked).
enum class PanelArrangement { kAuto, kSideBySide, kStacked };
// "auto", "side" or "stacked"; throws std::invalid_argument naming the accepted words otherwise.
PanelArrangement parse_panels(const std::string& text);

struct FigureOptions {
  double width_in = kSingleColumnIn;
  double font_pt = 8;
  double dpi = 300;  // PNG only
  FigureLayers layers = default_layers(kSingleColumnIn);
  Crop crop;
  // --crop auto: the pictures cut to the rocks' extent (both sides' GT boxes, and for the registration figure
  // the aligned centres), with a margin for their numbers (scene::rocks_crop); `crop` is then ignored.
  bool crop_auto = false;
  PanelArrangement panels = PanelArrangement::kAuto;
  std::string font_file;    // empty: default_font_file()
  bool ci = false;          // table: confidence intervals
  std::string by = "size";  // breakdown: size|region|confidence
  double width_pt() const { return width_in * 72.0; }
  // Empty when usable; otherwise the option that is wrong and the accepted range, in one sentence.
  std::string validate() const;
  // Throws std::invalid_argument(validate()) when not usable.
  void check() const;
};

}  // namespace ipd::ui
