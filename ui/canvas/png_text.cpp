#include "ui/canvas/png_text.h"

#include <array>
#include <cstdint>
#include <stdexcept>

namespace ipd::ui {

namespace {

constexpr char kSignature[] = "\x89PNG\r\n\x1a\n";
constexpr size_t kSignatureSize = 8;

// The CRC-32 every PNG chunk ends with (ISO 3309, over the chunk type and data).
uint32_t crc32(const std::string& bytes) {
  static const std::array<uint32_t, 256> table = [] {
    std::array<uint32_t, 256> t{};
    for (uint32_t n = 0; n < 256; ++n) {
      uint32_t c = n;
      for (int k = 0; k < 8; ++k) c = (c & 1) ? 0xEDB88320u ^ (c >> 1) : c >> 1;
      t[n] = c;
    }
    return t;
  }();
  uint32_t c = 0xFFFFFFFFu;
  for (unsigned char b : bytes) c = table[(c ^ b) & 0xFF] ^ (c >> 8);
  return c ^ 0xFFFFFFFFu;
}

std::string be32(uint32_t v) { return {char(v >> 24), char((v >> 16) & 0xFF), char((v >> 8) & 0xFF), char(v & 0xFF)}; }

uint32_t read_be32(const std::string& s, size_t at) {
  return uint32_t((unsigned char)s[at]) << 24 | uint32_t((unsigned char)s[at + 1]) << 16 |
         uint32_t((unsigned char)s[at + 2]) << 8 | uint32_t((unsigned char)s[at + 3]);
}

void check_png(const std::string& png) {
  if (png.size() < kSignatureSize + 12 || png.compare(0, kSignatureSize, kSignature, kSignatureSize) != 0 ||
      png.compare(kSignatureSize + 4, 4, "IHDR") != 0)
    throw std::invalid_argument("not a PNG file");
}

}  // namespace

std::string png_with_text(const std::string& png, const std::string& keyword, const std::string& text) {
  check_png(png);
  if (keyword.empty() || keyword.size() > 79) throw std::invalid_argument("a PNG text keyword has 1-79 characters");
  std::string data = keyword + '\0';
  for (char ch : text) data += (ch >= 0x20 && ch < 0x7F) ? ch : '?';
  const std::string body = "tEXt" + data;
  const std::string chunk = be32(static_cast<uint32_t>(data.size())) + body + be32(crc32(body));
  const size_t after_ihdr = kSignatureSize + 12 + read_be32(png, kSignatureSize);
  if (after_ihdr > png.size()) throw std::invalid_argument("not a PNG file");
  return png.substr(0, after_ihdr) + chunk + png.substr(after_ihdr);
}

std::string png_text(const std::string& png, const std::string& keyword) {
  check_png(png);
  for (size_t at = kSignatureSize; at + 12 <= png.size();) {
    const size_t len = read_be32(png, at);
    if (at + 12 + len > png.size()) break;
    if (png.compare(at + 4, 4, "tEXt") == 0) {
      const std::string data = png.substr(at + 8, len);
      const size_t nul = data.find('\0');
      if (nul != std::string::npos && data.substr(0, nul) == keyword) return data.substr(nul + 1);
    }
    at += 12 + len;
  }
  return {};
}

}  // namespace ipd::ui
