#include "ui/figures/figure_options.h"

#include <fmt/format.h>

#include <algorithm>
#include <sstream>
#include <stdexcept>
#include <vector>

namespace ipd::ui {

namespace {
std::vector<std::string> split(const std::string& s, char sep) {
  std::vector<std::string> out;
  std::stringstream in(s);
  for (std::string part; std::getline(in, part, sep);) out.push_back(part);
  return out;
}
}  // namespace

bool FigureLayers::operator==(const FigureLayers& o) const {
  return gt == o.gt && pred == o.pred && conf == o.conf && indices == o.indices && pairs == o.pairs &&
         legend == o.legend;
}

FigureLayers parse_layers(const std::string& list) {
  FigureLayers l{false, false, false, false, false, false};
  for (const std::string& name : split(list, ',')) {
    if (name == "gt")
      l.gt = true;
    else if (name == "pred")
      l.pred = true;
    else if (name == "conf")
      l.conf = true;
    else if (name == "indices")
      l.indices = true;
    else if (name == "pairs")
      l.pairs = true;
    else if (name == "legend")
      l.legend = true;
    else
      throw std::invalid_argument(fmt::format(
          "--layers: unknown layer '{}' (accepted: gt, pred, conf, indices, pairs, legend, comma-separated)", name));
  }
  return l;
}

std::string to_string(const FigureLayers& l) {
  std::string s;
  auto add = [&](bool on, const char* name) {
    if (on) s += (s.empty() ? "" : ",") + std::string(name);
  };
  add(l.gt, "gt"), add(l.pred, "pred"), add(l.conf, "conf"), add(l.indices, "indices"), add(l.pairs, "pairs");
  add(l.legend, "legend");
  return s;
}

double secondary_pt(double font_pt) { return std::max(std::min(font_pt, kReadablePt), 0.85 * font_pt); }

FigureLayers default_layers(double width_in) {
  FigureLayers l;
  l.conf = width_in > kSingleColumnIn + 0.01;
  return l;
}

PanelArrangement parse_panels(const std::string& text) {
  if (text == "auto") return PanelArrangement::kAuto;
  if (text == "side") return PanelArrangement::kSideBySide;
  if (text == "stacked") return PanelArrangement::kStacked;
  throw std::invalid_argument("--panels: expected auto, side or stacked, found '" + text + "'");
}

Crop parse_crop(const std::string& text) {
  const auto parts = split(text, ',');
  const std::string usage =
      "--crop: expected X0,Y0,X1,Y1 normalised to 0..1 with X0 < X1 and Y0 < Y1, found '" + text + "'";
  if (parts.size() != 4) throw std::invalid_argument(usage);
  double v[4];
  for (int i = 0; i < 4; ++i) {
    size_t used = 0;
    try {
      v[i] = std::stod(parts[i], &used);
    } catch (const std::exception&) {
      throw std::invalid_argument(usage);
    }
    if (used != parts[i].size() || !(v[i] >= 0 && v[i] <= 1)) throw std::invalid_argument(usage);
  }
  if (!(v[0] < v[2] && v[1] < v[3])) throw std::invalid_argument(usage);
  return {v[0], v[1], v[2], v[3]};
}

std::string FigureOptions::validate() const {
  if (!(width_in >= 1 && width_in <= 40))
    return fmt::format("--width-in: {} is not a figure width (1 to 40 inches)", width_in);
  if (!(font_pt >= kMinTextPt && font_pt <= 72))
    return fmt::format("--font-pt: {} is outside 6..72 (nothing smaller than 6 pt on the page)", font_pt);
  if (!(dpi >= 30 && dpi <= 2400)) return fmt::format("--dpi: {} is outside 30..2400", dpi);
  if (!(crop.x0 >= 0 && crop.x0 < crop.x1 && crop.x1 <= 1 && crop.y0 >= 0 && crop.y0 < crop.y1 && crop.y1 <= 1))
    return "--crop: the region must satisfy 0 <= X0 < X1 <= 1 and 0 <= Y0 < Y1 <= 1";
  if (by != "size" && by != "region" && by != "confidence")
    return "--by: expected size, region or confidence, found '" + by + "'";
  return {};
}

void FigureOptions::check() const {
  if (const std::string problem = validate(); !problem.empty()) throw std::invalid_argument(problem);
}

}  // namespace ipd::ui
