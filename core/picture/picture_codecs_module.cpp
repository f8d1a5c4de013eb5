// The module ipd_picture_codecs.so: OpenCV's picture codecs behind the entry points picture_codec.h names,
// opened by picture_codec.cpp on the first picture read or written. cv::Mat and the standard containers cross
// the boundary as they are: the module is built with the programs, against the same shared libraries.
#include <opencv2/imgcodecs.hpp>

#include "core/picture/picture_codec.h"

extern "C" {

// A picture over OpenCV's own pixel limit throws cv::Exception from imdecode: it reads as one that can't be
// decoded.
void ipd_decode_picture_v1(const std::string* bytes, int flags, cv::Mat* out) {
  try {
    if (bytes->empty()) {
      *out = cv::Mat();
      return;
    }
    const cv::Mat raw(1, static_cast<int>(bytes->size()), CV_8UC1, const_cast<char*>(bytes->data()));
    *out = cv::imdecode(raw, flags);
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
static_assert(std::is_same_v<decltype(&ipd_decode_picture_v1), ipd::DecodePictureFn>);
static_assert(std::is_same_v<decltype(&ipd_encode_picture_v1), ipd::EncodePictureFn>);
