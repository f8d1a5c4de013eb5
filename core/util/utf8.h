// Names from the file system are bytes; JSON, terminals and the studio's font want UTF-8 text.
#pragma once

#include <string>
#include <string_view>

namespace ipd {

// Strict UTF-8: no overlong forms, no surrogates, nothing above U+10FFFF.
bool is_utf8(std::string_view s);
// `s` with A-Z lowered (file extensions, class and layout words compared without case); other bytes kept.
std::string ascii_lower(std::string s);

// `s` for a message: its bytes that are not UTF-8, and control bytes (a NUL, an escape), as \xHH; the rest
// as it is.
std::string escape_non_utf8(std::string_view s);

}  // namespace ipd
