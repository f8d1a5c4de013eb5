#include "ui/figures/figure_provenance.h"

#include <cmath>

#include "ui/figures/figure_common.h"

namespace ipd::ui {

void add_provenance(DisplayList& fig, const Provenance& p, const FigureOptions& o) {
  fig.description = provenance_note(p);
  if (!provenance_edited(p)) return;
  const double m = fig::kFigureMargin, pt = secondary_pt(o.font_pt);
  // Below the figure's own bottom margin, a little apart from its content.
  const double y = fig.height_pt - m + 0.3 * pt;
  const double h = fig::draw_wrapped(fig, {m, y}, fig::style(pt, fig::kGrey), fig.description, fig.width_pt - 2 * m);
  fig.height_pt = std::ceil(y + h + m);
}

}  // namespace ipd::ui
