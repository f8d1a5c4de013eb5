// Reading and writing pictures (PNG, JPEG, ...) through OpenCV's codecs, which live in the module
// ipd_picture_codecs.so (picture_codecs_module.cpp), opened on the first call: only the commands that touch
// a picture pay for opencv_imgcodecs and the ~140 libraries behind it. Call these, never cv::imread or
// cv::imencode directly: the programs don't link opencv_imgcodecs (a direct call fails to link).
#pragma once

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>  // the flag names (cv::IMREAD_COLOR, cv::IMWRITE_JPEG_QUALITY, ...) only
#include <string>
#include <vector>

namespace ipd {

// cv::imread(path, flags): an empty matrix when the file can't be read or decoded, is not a regular file (a
// symbolic link is never followed: study_file_problem) or declares more than kMaxPicturePixels
// (picture_size.h). Throws
// std::runtime_error when the codecs module can't be opened.
cv::Mat read_picture(const std::string& path, int flags);

// Why read_picture would return nothing for `path` before decoding it: a symbolic link, not a regular file, or
// too many pixels declared; "" when none of these (a picture that still fails to decode is "cannot decode").
std::string picture_problem(const std::string& path);

// cv::imencode(ext, image, *out, params): false when OpenCV can't encode it. Throws std::runtime_error when
// the codecs module can't be opened.
bool encode_picture(const std::string& ext, const cv::Mat& image, std::vector<uchar>* out,
                    const std::vector<int>& params = {});

// The module's entry points (picture_codecs_module.cpp); the suffix is the interface's version.
using ReadPictureFn = void (*)(const std::string* path, int flags, cv::Mat* out);
using EncodePictureFn = bool (*)(const std::string* ext, const cv::Mat* image, std::vector<uchar>* out,
                                 const std::vector<int>* params);
inline constexpr const char* kPictureCodecsModule = "ipd_picture_codecs.so";
inline constexpr const char* kReadPictureSymbol = "ipd_read_picture_v1";
inline constexpr const char* kEncodePictureSymbol = "ipd_encode_picture_v1";

}  // namespace ipd
