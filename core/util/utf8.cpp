#include "core/util/utf8.h"

#include <fmt/format.h>

namespace ipd {

namespace {

// Length of the UTF-8 sequence starting at s[k], or 0 when it is not one.
size_t utf8_sequence(std::string_view s, size_t k) {
  const auto byte = [&](size_t i) { return static_cast<unsigned char>(s[i]); };
  const unsigned char c = byte(k);
  if (c < 0x80) return 1;
  size_t n = 0;
  unsigned min = 0, cp = 0;
  if ((c & 0xE0) == 0xC0)
    n = 2, cp = c & 0x1F, min = 0x80;
  else if ((c & 0xF0) == 0xE0)
    n = 3, cp = c & 0x0F, min = 0x800;
  else if ((c & 0xF8) == 0xF0)
    n = 4, cp = c & 0x07, min = 0x10000;
  else
    return 0;
  if (k + n > s.size()) return 0;
  for (size_t i = 1; i < n; ++i) {
    if ((byte(k + i) & 0xC0) != 0x80) return 0;
    cp = (cp << 6) | (byte(k + i) & 0x3F);
  }
  if (cp < min || cp > 0x10FFFF || (cp >= 0xD800 && cp <= 0xDFFF)) return 0;
  return n;
}

}  // namespace

bool is_utf8(std::string_view s) {
  for (size_t k = 0; k < s.size();) {
    const size_t n = utf8_sequence(s, k);
    if (n == 0) return false;
    k += n;
  }
  return true;
}

std::string escape_non_utf8(std::string_view s) {
  std::string out;
  for (size_t k = 0; k < s.size();) {
    const size_t n = utf8_sequence(s, k);
    const unsigned char c = static_cast<unsigned char>(s[k]);
    if (n == 0 || c < 0x20 || c == 0x7f) {
      out += fmt::format("\\x{:02X}", c);
      ++k;
    } else {
      out.append(s.substr(k, n));
      k += n;
    }
  }
  return out;
}

}  // namespace ipd

namespace ipd {

std::string ascii_lower(std::string s) {
  for (char& c : s)
    if (c >= 'A' && c <= 'Z') c = static_cast<char>(c - 'A' + 'a');
  return s;
}

}  // namespace ipd
