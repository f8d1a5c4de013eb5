// A text chunk in a PNG file: how a raster figure carries its description (the label files and hand edits
// it was drawn from) the way a PDF carries it in its Subject; image viewers and `identify -verbose` show it.
#pragma once

#include <string>

namespace ipd::ui {

// `png` with a tEXt chunk (keyword, text) inserted after its IHDR chunk. The keyword is 1-79 Latin-1
// characters; characters of `text` outside printable ASCII become '?' (tEXt is Latin-1, and the figures'
// descriptions are ASCII). Throws std::invalid_argument when `png` is not a PNG file.
std::string png_with_text(const std::string& png, const std::string& keyword, const std::string& text);

// The text of the first tEXt chunk with `keyword` ("" when there is none), for tests and readers.
std::string png_text(const std::string& png, const std::string& keyword);

}  // namespace ipd::ui
