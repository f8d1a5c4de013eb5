#include "core/picture/picture_size.h"

#include <fmt/format.h>

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>

#include "core/util/contained_file.h"

namespace ipd {

namespace {

std::uint32_t be16(const unsigned char* p) { return (p[0] << 8) | p[1]; }
std::uint32_t be32(const unsigned char* p) { return (std::uint32_t(p[0]) << 24) | (p[1] << 16) | (p[2] << 8) | p[3]; }
std::uint32_t le16(const unsigned char* p) { return p[0] | (p[1] << 8); }
std::uint32_t le24(const unsigned char* p) { return p[0] | (p[1] << 8) | (p[2] << 16); }
std::int32_t le32(const unsigned char* p) {
  return static_cast<std::int32_t>(p[0] | (p[1] << 8) | (p[2] << 16) | (std::uint32_t(p[3]) << 24));
}

// JPEG: the first start-of-frame marker (SOF0..SOF15 but DHT, JPG and DAC) after the segments before it
// (EXIF and its thumbnail may come first), read segment by segment.
std::optional<PictureSize> jpeg_size(const std::string& bytes) {
  const auto* b = reinterpret_cast<const unsigned char*>(bytes.data());
  size_t at = 2;
  for (int segments = 0; segments < 10000 && at + 4 <= bytes.size(); ++segments) {
    const unsigned char* m = b + at;
    if (m[0] != 0xff) return std::nullopt;
    const int marker = m[1];
    const std::uint32_t length = be16(m + 2);
    if (marker >= 0xc0 && marker <= 0xcf && marker != 0xc4 && marker != 0xc8 && marker != 0xcc) {
      if (at + 9 > bytes.size()) return std::nullopt;
      const unsigned char* f = m + 4;
      return PictureSize{be16(f + 3), be16(f + 1)};
    }
    if (length < 2) return std::nullopt;
    at += 2 + length;
  }
  return std::nullopt;
}

}  // namespace

std::optional<PictureSize> declared_picture_size_of(const std::string& bytes) {
  if (bytes.size() < 4) return std::nullopt;
  unsigned char h[32] = {};
  std::memcpy(h, bytes.data(), std::min(bytes.size(), sizeof h));
  if (h[0] == 0x89 && h[1] == 'P' && h[2] == 'N' && h[3] == 'G') return PictureSize{be32(h + 16), be32(h + 20)};
  if (h[0] == 0xff && h[1] == 0xd8) return jpeg_size(bytes);
  if (h[0] == 'B' && h[1] == 'M') return PictureSize{std::abs(le32(h + 18)), std::abs(le32(h + 22))};
  if (h[0] == 'R' && h[1] == 'I' && h[2] == 'F' && h[3] == 'F' && h[8] == 'W' && h[9] == 'E' && h[10] == 'B') {
    const std::string chunk(reinterpret_cast<const char*>(h + 12), 4);
    if (chunk == "VP8X") return PictureSize{le24(h + 24) + 1, le24(h + 27) + 1};
    if (chunk == "VP8 ") return PictureSize{le16(h + 26) & 0x3fff, le16(h + 28) & 0x3fff};
    if (chunk == "VP8L") {
      const std::uint32_t bits = h[21] | (h[22] << 8) | (h[23] << 16) | (std::uint32_t(h[24]) << 24);
      return PictureSize{(bits & 0x3fff) + 1, ((bits >> 14) & 0x3fff) + 1};
    }
  }
  return std::nullopt;
}

std::string picture_size_problem_of(const std::string& path, const std::string& bytes) {
  const auto size = declared_picture_size_of(bytes);
  if (!size || size->width * size->height <= kMaxPicturePixels) return "";
  return fmt::format("{}: declares {} x {} pixels, over the {}-megapixel limit for a picture", path, size->width,
                     size->height, kMaxPicturePixels / 1'000'000);
}

namespace {

// The bytes of the picture `path`, read through its folder's descriptor (the file itself never followed);
// "" when it can't be read (the decoder's to report).
std::string picture_bytes(const std::string& path) {
  const std::filesystem::path p(path);
  const std::string folder = p.has_parent_path() ? p.parent_path().string() : std::string(".");
  try {
    return read_file_beneath(folder, p.filename().string(), kMaxPictureBytes).value_or("");
  } catch (const IoError&) {
    return "";
  }
}

}  // namespace

std::optional<PictureSize> declared_picture_size(const std::string& path) {
  return declared_picture_size_of(picture_bytes(path));
}

std::string picture_size_problem(const std::string& path) { return picture_size_problem_of(path, picture_bytes(path)); }

}  // namespace ipd
