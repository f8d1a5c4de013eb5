// A picture's size from its header, before anything is decoded. A PNG of 60 KB can declare 20,000 x 20,000
// pixels, and decoding it (then the image metrics, ~100 bytes a pixel) would take tens of gigabytes: readers
// refuse a picture over kMaxPicturePixels first. PNG, JPEG, BMP and WebP headers are read; other formats are
// left to OpenCV's own limit.
#pragma once

#include <cstddef>
#include <optional>
#include <string>

namespace ipd {

inline constexpr long long kMaxPicturePixels = 50'000'000;  // more than the cameras of the studies deliver
// A picture file is read whole before it is decoded (the bytes checked are the bytes decoded): 50 megapixels
// stored uncompressed at 4 bytes a pixel (BMP) are 200 MB, so 256 MB refuses only what no picture needs.
inline constexpr size_t kMaxPictureBytes = size_t{256} << 20;

struct PictureSize {
  long long width = 0, height = 0;
};

// The size a picture's header declares; nullopt when the format is not one of the four or the header is cut.
// `_of` reads the header from a picture's bytes; the path forms read the file first (never through a link).
std::optional<PictureSize> declared_picture_size_of(const std::string& bytes);
std::optional<PictureSize> declared_picture_size(const std::string& path);

// "PATH: declares W x H pixels, over the 50-megapixel limit for a picture" when the header declares more than
// kMaxPicturePixels; "" otherwise (an unreadable header is the decoder's to report).
std::string picture_size_problem_of(const std::string& path, const std::string& bytes);
std::string picture_size_problem(const std::string& path);

}  // namespace ipd
