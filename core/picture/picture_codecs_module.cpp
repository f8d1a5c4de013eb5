// The module ipd_picture_codecs.so: OpenCV's picture codecs behind the entry points picture_codec.h names,
// opened by picture_codec.cpp on the first picture read or written. cv::Mat and the standard containers cross
// the boundary as they are: the module is built with the programs, against the same shared libraries.
#include <opencv2/imgcodecs.hpp>

#include "core/picture/picture_codec.h"

extern "C" {

// A picture over OpenCV's own pixel limit throws cv::Exception from imread: it reads as one that can't be decoded.
void ipd_read_picture_v1(const std::string* path, int flags, cv::Mat* out) {
  try {
    *out = cv::imread(*path, flags);
  } catch (const cv::Exception&) {
    *out = cv::Mat();
  }
}

bool ipd_encode_picture_v1(const std::string* ext, const cv::Mat* image, std::vector<uchar>* out,
                           const std::vector<int>* params) {
  return cv::imencode(*ext, *image, *out, *params);
}
}

// The entry points must have the types the loader casts them to.
static_assert(std::is_same_v<decltype(&ipd_read_picture_v1), ipd::ReadPictureFn>);
static_assert(std::is_same_v<decltype(&ipd_encode_picture_v1), ipd::EncodePictureFn>);
