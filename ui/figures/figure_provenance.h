// Where a figure's numbers come from, on the figure: the provenance note (core/report/provenance.h) goes
// into the file's metadata always, and under the figure as a footnote line when something was edited by
// hand, so a printed figure tells an automatic result from an edited one.
#pragma once

#include "core/report/provenance.h"
#include "ui/canvas/canvas.h"
#include "ui/figures/figure_options.h"

namespace ipd::ui {

// Sets fig.description to provenance_note(p); when provenance_edited(p), draws the note in the secondary
// font below everything drawn so far (the page grows by its height, so it never covers a label). Call it
// after the figure has set its page size.
void add_provenance(DisplayList& fig, const Provenance& p, const FigureOptions& options);

}  // namespace ipd::ui
