#include "ui/figures/figure_provenance.h"

#include <cmath>
#include <string>

#include "ui/figures/figure_common.h"

namespace ipd::ui {

void add_provenance(DisplayList& fig, const Provenance& p, const FigureOptions& o) {
  fig.description = provenance_note(p);
  // The whole note when a number may differ from the automatic result; otherwise only the class, when the study
  // names one: a figure of shadows must not pass for one of rocks (the metadata always has the whole note).
  const std::string shown = provenance_edited(p)   ? fig.description
                            : p.class_name.empty() ? std::string()
                                                   : "Class " + p.class_name + ".";
  if (shown.empty()) return;
  const double m = fig::kFigureMargin, pt = secondary_pt(o.font_pt);
  // Below the figure's own bottom margin, a little apart from its content.
  const double y = fig.height_pt - m + 0.3 * pt;
  const double h = fig::draw_wrapped(fig, {m, y}, fig::style(pt, fig::kGrey), shown, fig.width_pt - 2 * m);
  fig.height_pt = std::ceil(y + h + m);
}

}  // namespace ipd::ui
