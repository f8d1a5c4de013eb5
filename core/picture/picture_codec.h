// Reading and writing pictures (PNG, JPEG, ...) through OpenCV's codecs, which live in the module
// ipd_picture_codecs.so (picture_codecs_module.cpp), opened on the first call: only the commands that touch
// a picture pay for opencv_imgcodecs and the ~140 libraries behind it. Call these, never cv::imread or
// cv::imencode directly: the programs don't link opencv_imgcodecs (a direct call fails to link).
#pragma once

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>  // the flag names (cv::IMREAD_COLOR, cv::IMWRITE_JPEG_QUALITY, ...) only
#include <string>
#include <vector>

#include "core/util/atomic_file.h"

namespace ipd {

// A picture read, or why not.
struct PictureRead {
  cv::Mat image;        // empty when it could not be read
  std::string problem;  // "" when read; else "PATH: ..." (missing, a link, a FIFO, too many pixels, cannot decode)
};

// The picture `path` of the study at `root`, read as every file a study holds is (contained_file.h): opened
// once beneath root, no link followed on the way or at the file, O_NONBLOCK (a FIFO is refused, never waited
// on), checked as a regular file with fstat, read whole through that descriptor (at most kMaxPictureBytes);
// its declared size checked and its pixels decoded from those same bytes (cv::imdecode), so a file swapped
// after a check is never the one decoded. `hook` as read_file_beneath's. Throws std::runtime_error when the
// codecs module can't be opened.
PictureRead read_study_picture(const std::string& root, const std::string& path, int flags,
                               const WriteStepHook& hook = {});

// read_study_picture in two steps, for a reader that decodes the same bytes twice (a preview, then the whole):
// the bytes (or the problem, bytes then empty), then their pixels (empty when they can't be decoded).
struct PictureBytes {
  std::string bytes, problem;
};
PictureBytes read_study_picture_bytes(const std::string& root, const std::string& path, const WriteStepHook& hook = {});
cv::Mat decode_picture(const std::string& bytes, int flags);

// read_study_picture(the picture's own folder, path, flags).image: for a picture the user named (its folders
// are theirs); the file itself is still never followed through a link, nor waited on as a FIFO.
cv::Mat read_picture(const std::string& path, int flags);

// Why read_picture would return nothing for `path` before decoding it: a symbolic link, not a regular file, or
// too many pixels declared; "" when none of these (a picture that still fails to decode is "cannot decode").
std::string picture_problem(const std::string& path);

// cv::imencode(ext, image, *out, params): false when OpenCV can't encode it. Throws std::runtime_error when
// the codecs module can't be opened.
bool encode_picture(const std::string& ext, const cv::Mat& image, std::vector<uchar>* out,
                    const std::vector<int>& params = {});

// The module's entry points (picture_codecs_module.cpp); the suffix is the interface's version. Pictures are
// decoded from bytes already read: the module never opens a file.
using DecodePictureFn = void (*)(const std::string* bytes, int flags, cv::Mat* out);
using EncodePictureFn = bool (*)(const std::string* ext, const cv::Mat* image, std::vector<uchar>* out,
                                 const std::vector<int>* params);
inline constexpr const char* kPictureCodecsModule = "ipd_picture_codecs.so";
inline constexpr const char* kDecodePictureSymbol = "ipd_decode_picture_v1";
inline constexpr const char* kEncodePictureSymbol = "ipd_encode_picture_v1";

}  // namespace ipd
