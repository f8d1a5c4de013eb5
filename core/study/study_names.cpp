#include "core/study/study_names.h"

#include <fmt/format.h>

namespace ipd {

std::string file_name_problem(const std::string& name, size_t max_bytes) {
  if (name.empty()) return "is empty";
  if (name == "." || name == "..") return fmt::format("is '{}', which names a folder, not a file", name);
  for (const char ch : name) {
    const auto c = static_cast<unsigned char>(ch);
    if (c == '/' || c == '\\') return fmt::format("contains a path separator '{}'", ch);
    if (c < 0x20 || c == 0x7f) return fmt::format("contains a control character (byte 0x{:02x})", c);
  }
  if (name.size() > max_bytes)
    return fmt::format("is {} bytes long; at most {} fit in the file names it becomes part of", name.size(), max_bytes);
  return "";
}

std::string printable_name(const std::string& name, size_t max_bytes) {
  if (name.size() > max_bytes) {
    size_t cut = max_bytes;
    while (cut > 0 && (static_cast<unsigned char>(name[cut]) & 0xC0) == 0x80) --cut;  // not inside a character
    return printable_name(name.substr(0, cut)) + "...";
  }
  std::string out;
  for (const char ch : name) {
    const auto c = static_cast<unsigned char>(ch);
    if (c < 0x20 || c == 0x7f)
      out += fmt::format("\\x{:02x}", c);
    else
      out += ch;
  }
  return out;
}

}  // namespace ipd
