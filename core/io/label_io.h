// Reading YOLO-format label files (ground truth: `class cx cy w h`, or YOLO-seg's outline `class x1 y1 ... xn yn`;
// predictions: either, then `conf`).
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "core/geometry/geometry.h"

namespace ipd {

enum class LabelKind { kGroundTruth, kPrediction };

// One problem in one line of one file, printed as `FILE:LINE: message`.
struct LabelError {
  std::string file;
  int line = 0;  // 1-based; 0 when the problem is the file itself (or this is a summary, below)
  std::string message;
  // A summary: `more` further malformed lines of `file` that are counted but not listed (a file lists at
  // most kMaxListedErrors, so 10^6 bad lines don't make 67 MB of messages).
  int more = 0;
  std::string to_string() const;
  int malformed_lines() const { return line > 0 ? 1 : more; }
  // The file itself can't be used (a FIFO, a link, no permission, over kMaxLabelFileBytes or kMaxBoxesPerFile):
  // every command and ipd-studio refuse the study then, since its rocks would silently count as none.
  bool unusable_file() const { return malformed_lines() == 0; }
};
constexpr int kMaxListedErrors = 50;
// A box's sides are at least this (normalised): below, its area underflows and no IoU can pair it, not even with
// its own copy; a millionth of the picture is far below a pixel of any camera.
inline constexpr double kMinBoxSide = 1e-6;

// More boxes than this in one file is refused (an error naming the file): pairing and IoU tables grow with
// the product of two images' rock counts, so 10^6-line files would run for minutes.
constexpr size_t kMaxBoxesPerFile = 20000;
// A label file larger than this is refused unread (its size and the limit named), as pairs files are: 20,000
// boxes written with every digit (~60 bytes a line) are 1.2 MB, and parsing takes about 4 bytes of memory per
// byte of file, so 16 MB bounds a file at ~64 MB where an unbounded one (a sparse 1 GiB file costs no disk) took 4 GB.
constexpr size_t kMaxLabelFileBytes = size_t{16} << 20;

struct LabelFile {
  std::string path;
  bool exists = false;           // a missing file means an image with no rocks
  std::vector<Box> boxes;        // the valid box lines, in file order (a rock's index is its position here)
  std::vector<int> line_of_box;  // 1-based source line of each box
  std::vector<LabelError> errors;
};

struct LabelParseOptions {
  LabelKind kind = LabelKind::kGroundTruth;
  double range_tolerance = 1e-3;  // how far outside [0, 1] a normalised value may stray (rounding)

  // Empty when usable; otherwise the field that is wrong and the accepted range, in one sentence.
  std::string validate() const;
  // Throws std::invalid_argument("label parse options: " + validate()) when not usable.
  void check() const;
};

// Parses text that came from `file_name`; every malformed line becomes one LabelError (the first
// kMaxListedErrors; then one summary with the count), the others are kept. A leading UTF-8 BOM is skipped.
LabelFile parse_labels(const std::string& text, const std::string& file_name, const LabelParseOptions& options);

// parse_labels on text that arrives in pieces (a file read 64 KiB at a time): it holds one line, not the file.
// feed() the pieces in order, then finish() once; the result is parse_labels' on their concatenation.
class LabelParser {
 public:
  LabelParser(const std::string& file_name, const LabelParseOptions& options);
  void feed(std::string_view piece);
  LabelFile finish();

 private:
  void line(std::string_view text);
  LabelParseOptions options_;
  LabelFile out_;
  std::string partial_;  // a line whose end has not arrived yet
  std::vector<std::string> fields_;
  int line_no_ = 0, unlisted_ = 0;
  size_t boxes_ = 0;
};

// Reads and parses a file. A missing file is not an error (exists = false); an unreadable one is.
LabelFile read_labels(const std::string& path, const LabelParseOptions& options);
// The same for root/relative, a file of a study: reached without following a symbolic link below root (a link,
// the file or a folder on the way, is an error naming it: a study never makes the tool read outside it).
LabelFile read_labels_beneath(const std::string& root, const std::string& relative, const LabelParseOptions& options);

// Keeps only boxes of `cls` (and their line numbers); cls < 0 keeps all.
void keep_class(LabelFile* file, int cls);
// Drops the predictions a confidence threshold does not keep (kept_at_threshold).
void keep_confident(LabelFile* file, double threshold);

// Boxes as YOLO txt lines (with confidence for predictions); a box with an outline as its YOLO-seg line.
// How labels_text writes numbers. kFixed: as detectors write them, 6 decimals for a box and 4 for a confidence
// (`ipd detect`, the demo). kExact: the shortest decimal that reads back as the same double, for numbers given
// in full elsewhere (`ipd import coco`'s scores and boxes): a score of 0.24996 written as 0.2500 passed
// `--conf 0.25`, and two scores 0.50004 > 0.50001 written as equal changed AP's ranking.
enum class LabelDigits { kFixed, kExact };
std::string labels_text(const std::vector<Box>& boxes, LabelKind kind, LabelDigits digits = LabelDigits::kFixed);
// Gives `box` the outline of `points` (normalised, not closed) and makes the box its bounds, as a YOLO-seg line
// reads back; or returns why not: make_outline's reasons, or an outline narrower or lower than kMinBoxSide. Label
// files, COCO imports and the segmentation demo all outline a box through it.
std::string set_outline(std::vector<Eigen::Vector2d> points, Box* box);

// Writes labels_text(boxes, kind, digits) to `path`, atomically.
void write_labels(const std::string& path, const std::vector<Box>& boxes, LabelKind kind,
                  LabelDigits digits = LabelDigits::kFixed);

}  // namespace ipd
