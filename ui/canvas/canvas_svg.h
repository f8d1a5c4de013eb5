// SVG output of a figure: real <text> elements (searchable, editable) with the font embedded as a
// base64 @font-face cut to the glyphs used, pictures as embedded JPEG (quality 90) at their native resolution.
#pragma once

#include <string>

#include "ui/canvas/canvas.h"

namespace ipd::ui {

std::string render_svg(const DisplayList& figure, const FontMetrics& metrics);

}  // namespace ipd::ui
