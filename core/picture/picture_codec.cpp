#include "core/picture/picture_codec.h"

#include "core/picture/picture_size.h"

#include "core/util/contained_file.h"
#include "core/util/loadable_module.h"

namespace ipd {

namespace {

struct Codecs {
  ReadPictureFn read = nullptr;
  EncodePictureFn encode = nullptr;
};

// Opened on the first call (a failed open throws, and the next call tries again).
const Codecs& codecs() {
  static const Codecs c = [] {
    void* m = open_module(kPictureCodecsModule);
    Codecs out;
    out.read = reinterpret_cast<ReadPictureFn>(module_symbol(m, kPictureCodecsModule, kReadPictureSymbol));
    out.encode = reinterpret_cast<EncodePictureFn>(module_symbol(m, kPictureCodecsModule, kEncodePictureSymbol));
    return out;
  }();
  return c;
}

}  // namespace

std::string picture_problem(const std::string& path) {
  std::string why = study_file_problem(path);  // a link out of the study, or a FIFO that would block
  return why.empty() ? picture_size_problem(path) : why;
}

cv::Mat read_picture(const std::string& path, int flags) {
  cv::Mat out;
  if (!picture_problem(path).empty()) return out;
  codecs().read(&path, flags, &out);
  return out;
}

bool encode_picture(const std::string& ext, const cv::Mat& image, std::vector<uchar>* out,
                    const std::vector<int>& params) {
  return codecs().encode(&ext, &image, out, &params);
}

}  // namespace ipd
