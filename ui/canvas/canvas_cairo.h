// The cairo backend of the figure canvas: vector PDF (text as text, the font embedded as a subset), SVG
// (canvas_svg.h: <text> elements, the used glyphs embedded as @font-face) and PNG through cairo's image
// surface (no GL context needed, e.g. on the GUI's export worker).
#pragma once

#include <optional>
#include <string>

#include "ui/canvas/canvas.h"

namespace ipd::ui {

enum class FigureFormat { kPdf, kSvg, kPng };

// From the file name's extension (.pdf, .svg, .png, any case); nullopt for anything else.
std::optional<FigureFormat> figure_format_of(const std::string& path);
const char* to_string(FigureFormat f);

// The bytes of the figure's file; `dpi` matters for PNG only (width = width_pt / 72 * dpi pixels).
// `title` goes into the PDF's metadata.
std::string render_figure_file(const DisplayList& figure, const FontMetrics& metrics, FigureFormat format, double dpi,
                               const std::string& title = {});

}  // namespace ipd::ui
