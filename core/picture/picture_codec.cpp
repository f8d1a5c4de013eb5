#include "core/picture/picture_codec.h"

#include <filesystem>
#include <optional>
#include <utility>

#include "core/picture/picture_size.h"

#include "core/util/contained_file.h"
#include "core/util/loadable_module.h"

namespace ipd {

namespace {

struct Codecs {
  DecodePictureFn decode = nullptr;
  EncodePictureFn encode = nullptr;
};

// Opened on the first call (a failed open throws, and the next call tries again).
const Codecs& codecs() {
  static const Codecs c = [] {
    void* m = open_module(kPictureCodecsModule);
    Codecs out;
    out.decode = reinterpret_cast<DecodePictureFn>(module_symbol(m, kPictureCodecsModule, kDecodePictureSymbol));
    out.encode = reinterpret_cast<EncodePictureFn>(module_symbol(m, kPictureCodecsModule, kEncodePictureSymbol));
    return out;
  }();
  return c;
}

}  // namespace

namespace {

// The folder a picture the user named is read beneath (its own) and its name there.
std::pair<std::string, std::string> own_folder(const std::string& path) {
  const std::filesystem::path p(path);
  return {p.has_parent_path() ? p.parent_path().string() : std::string("."), p.filename().string()};
}

// The picture's bytes and "", or "" and why they can't be read.
std::pair<std::string, std::string> picture_file(const std::string& root, const std::optional<std::string>& rel,
                                                 const std::string& path, const WriteStepHook& hook) {
  if (!rel) return {"", path + ": is not inside " + root};
  try {
    std::optional<std::string> bytes = read_file_beneath(root, *rel, kMaxPictureBytes, hook);
    if (!bytes) return {"", path + ": no such file"};
    if (std::string why = picture_size_problem_of(path, *bytes); !why.empty()) return {"", why};
    return {std::move(*bytes), ""};
  } catch (const IoError& e) {
    return {"", e.what()};  // a link, a FIFO (never waited on), a folder, too large
  }
}

}  // namespace

PictureBytes read_study_picture_bytes(const std::string& root, const std::string& path, const WriteStepHook& hook) {
  auto [bytes, problem] = picture_file(root, path_below(root, path), path, hook);
  return {std::move(bytes), std::move(problem)};
}

cv::Mat decode_picture(const std::string& bytes, int flags) {
  cv::Mat out;
  codecs().decode(&bytes, flags, &out);
  return out;
}

PictureRead read_study_picture(const std::string& root, const std::string& path, int flags, const WriteStepHook& hook) {
  PictureRead out;
  auto [bytes, problem] = picture_file(root, path_below(root, path), path, hook);
  if (!problem.empty()) {
    out.problem = std::move(problem);
    return out;
  }
  codecs().decode(&bytes, flags, &out.image);
  if (out.image.empty()) out.problem = "cannot decode " + path;
  return out;
}

std::string picture_problem(const std::string& path) {
  const auto [folder, name] = own_folder(path);
  return picture_file(folder, name, path, {}).second;
}

cv::Mat read_picture(const std::string& path, int flags) {
  const auto [folder, name] = own_folder(path);
  auto [bytes, problem] = picture_file(folder, name, path, {});
  cv::Mat out;
  if (problem.empty()) codecs().decode(&bytes, flags, &out);
  return out;
}

bool encode_picture(const std::string& ext, const cv::Mat& image, std::vector<uchar>* out,
                    const std::vector<int>& params) {
  return codecs().encode(&ext, &image, out, &params);
}

}  // namespace ipd
