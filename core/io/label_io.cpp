#include "core/io/label_io.h"

#include <fmt/format.h>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string_view>

#include "core/geometry/confidence_threshold.h"
#include "core/util/atomic_file.h"
#include "core/util/contained_file.h"
#include "core/util/number_text.h"

namespace fs = std::filesystem;

namespace ipd {

std::string LabelError::to_string() const {
  if (line > 0) return fmt::format("{}:{}: {}", file, line, message);
  if (more > 0) return fmt::format("{}: {} more malformed line(s) not listed", file, more);
  return fmt::format("{}: {}", file, message);
}

namespace {

const char* const kColumnNames[] = {"class", "cx", "cy", "w", "h", "conf"};

// Whitespace-separated fields of one line (up to a '#' comment), into `out` (its strings reused: an outline line
// of hundreds of numbers allocates nothing once the first such line has been read).
void split_fields(std::string_view line, std::vector<std::string>* out, size_t* count) {
  *count = 0;
  const size_t hash = line.find('#');
  if (hash != std::string_view::npos) line = line.substr(0, hash);
  size_t k = 0;
  auto space = [](char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f'; };
  while (k < line.size()) {
    while (k < line.size() && space(line[k])) ++k;
    const size_t start = k;
    while (k < line.size() && !space(line[k])) ++k;
    if (k > start) {
      if (*count == out->size()) out->emplace_back();
      (*out)[*count].assign(line.data() + start, k - start);
      ++*count;
    }
  }
}

// Untrusted text in a message: never more than 40 characters of it, control bytes shown as \xHH.
std::string shorten(const std::string& s) { return quoted_for_message(s); }

std::string parse_class(const std::string& c, Box* box) {
  if (c.empty() || c.find_first_not_of("0123456789") != std::string::npos || c.size() > 9) {
    return fmt::format("expected a non-negative integer class in column 1, found '{}'", shorten(c));
  }
  box->cls = std::atoi(c.c_str());
  return {};
}

// A number of column `column` (1-based) named `name`, finite and (unless it is a confidence) in [0, 1].
std::string parse_number(const std::string& field, size_t column, const std::string& name, bool normalised,
                         const LabelParseOptions& opt, double* out) {
  // The whole field is the number: a NUL or any other byte after it is an error, never cut off.
  double x = NAN;
  if (!parse_decimal(field, &x) && !is_non_finite_word(field))
    return fmt::format("expected a number for {} in column {}, found '{}'", name, column, shorten(field));
  if (!std::isfinite(x))
    return fmt::format("expected a finite number for {} in column {}, found '{}'", name, column, shorten(field));
  if (normalised && (x < -opt.range_tolerance || x > 1.0 + opt.range_tolerance))
    return fmt::format("expected {} in [0, 1]{}, found {}", name, name == "conf" ? "" : " (normalised)",
                       shorten(field));
  *out = x;
  return {};
}

// An outline line, YOLO-seg's `class x1 y1 ... xn yn` (then `conf` for a prediction): the box is the outline's
// bounds. `n` fields, at least 7 (a triangle).
std::string parse_outline(const std::vector<std::string>& f, size_t n, const LabelParseOptions& opt, Box* box) {
  const bool prediction = opt.kind == LabelKind::kPrediction;
  const size_t coords = n - 1 - (prediction ? 1 : 0);
  if (coords % 2 != 0) {
    return prediction ? fmt::format(
                            "expected an outline with a confidence last (class x1 y1 ... xn yn conf), found "
                            "{} columns: an odd number of coordinates, or no confidence",
                            n)
                      : fmt::format(
                            "expected an outline (class x1 y1 ... xn yn), found {} columns: an odd number "
                            "of coordinates",
                            n);
  }
  if (std::string why = parse_class(f[0], box); !why.empty()) return why;
  std::vector<Eigen::Vector2d> points(coords / 2);
  for (size_t k = 0; k < coords; ++k) {
    const std::string name = fmt::format("{}{}", k % 2 == 0 ? 'x' : 'y', k / 2 + 1);
    if (std::string why = parse_number(f[k + 1], k + 2, name, true, opt, &points[k / 2][k % 2]); !why.empty())
      return why;
  }
  if (prediction) {
    if (std::string why = parse_number(f[n - 1], n, "conf", true, opt, &box->conf); !why.empty()) return why;
  }
  return set_outline(std::move(points), box);
}

}  // namespace

std::string set_outline(std::vector<Eigen::Vector2d> points, Box* box) {
  OutlineRef outline = OutlineRef::make();
  if (std::string why = make_outline(std::move(points), outline.fill()); !why.empty()) return why;
  if (outline->x1 - outline->x0 < kMinBoxSide || outline->y1 - outline->y0 < kMinBoxSide)
    return fmt::format("expected an outline at least {:g} wide and high (a millionth of the picture)", kMinBoxSide);
  box->cx = 0.5 * (outline->x0 + outline->x1);
  box->cy = 0.5 * (outline->y0 + outline->y1);
  box->w = outline->x1 - outline->x0;
  box->h = outline->y1 - outline->y0;
  box->outline = std::move(outline);
  return {};
}

namespace {

// Parses a line's `n` fields into a box (or an outline and its bounds) or returns why not.
std::string parse_box(const std::vector<std::string>& f, size_t n, const LabelParseOptions& opt, Box* box) {
  const size_t want = opt.kind == LabelKind::kPrediction ? 6 : 5;
  if (n >= want + 2) return parse_outline(f, n, opt, box);
  if (n != want) {
    return fmt::format("expected {} columns ({}), found {}", want,
                       want == 6 ? "class cx cy w h conf" : "class cx cy w h", n);
  }
  if (std::string why = parse_class(f[0], box); !why.empty()) return why;
  double v[6] = {0, 0, 0, 0, 0, 1};
  // Every column is checked to be a number before any range: "expected a number for conf" names the column a
  // reader must fix before "cx out of range" would.
  for (size_t k = 1; k < want; ++k) {
    if (std::string why = parse_number(f[k], k + 1, kColumnNames[k], false, opt, &v[k]); !why.empty()) return why;
  }
  for (size_t k = 1; k < want; ++k) {
    if (v[k] < -opt.range_tolerance || v[k] > 1.0 + opt.range_tolerance) {
      return fmt::format("expected {} in [0, 1]{}, found {}", kColumnNames[k], k == 5 ? "" : " (normalised)",
                         shorten(f[k]));
    }
  }
  // Not just > 0: a box of 1e-300 has an area of 0 in doubles, so even its own copy would not overlap it.
  if (v[3] < kMinBoxSide)
    return fmt::format("expected w >= {:g} (a millionth of the picture), found {}", kMinBoxSide, shorten(f[3]));
  if (v[4] < kMinBoxSide)
    return fmt::format("expected h >= {:g} (a millionth of the picture), found {}", kMinBoxSide, shorten(f[4]));
  box->cx = v[1];
  box->cy = v[2];
  box->w = v[3];
  box->h = v[4];
  box->conf = v[5];
  return {};
}

}  // namespace

std::string LabelParseOptions::validate() const {
  if (!(range_tolerance >= 0 && range_tolerance < 1))
    return fmt::format("range_tolerance must be in [0, 1), got {}", range_tolerance);
  return {};
}

void LabelParseOptions::check() const {
  if (const std::string problem = validate(); !problem.empty())
    throw std::invalid_argument("label parse options: " + problem);
}

LabelParser::LabelParser(const std::string& file_name, const LabelParseOptions& options) : options_(options) {
  options_.check();
  out_.path = file_name;
  out_.exists = true;
}

void LabelParser::feed(std::string_view piece) {
  while (!piece.empty()) {
    const size_t eol = piece.find('\n');
    if (eol == std::string_view::npos) {
      partial_.append(piece);
      return;
    }
    if (partial_.empty()) {
      line(piece.substr(0, eol));
    } else {
      partial_.append(piece.substr(0, eol));
      line(partial_);
      partial_.clear();
    }
    piece.remove_prefix(eol + 1);
  }
}

void LabelParser::line(std::string_view text) {
  // A UTF-8 byte order mark (Windows editors) starts the first line.
  if (line_no_ == 0 && text.substr(0, 3) == "\xEF\xBB\xBF") text.remove_prefix(3);
  ++line_no_;
  size_t field_count = 0;
  split_fields(text, &fields_, &field_count);
  if (field_count == 0) return;
  Box b;
  const std::string why = parse_box(fields_, field_count, options_, &b);
  if (!why.empty()) {
    if (static_cast<int>(out_.errors.size()) < kMaxListedErrors)
      out_.errors.push_back({out_.path, line_no_, why});
    else
      ++unlisted_;
    return;
  }
  // Past the per-file limit the file is refused whole: later boxes are only counted, so a 16 MB file of short
  // lines holds 20,001 boxes in memory, not a million.
  if (++boxes_ > kMaxBoxesPerFile + 1) return;
  out_.boxes.push_back(b);
  out_.line_of_box.push_back(line_no_);
}

LabelFile LabelParser::finish() {
  if (!partial_.empty()) line(partial_);  // the last line, without its newline
  partial_.clear();
  if (unlisted_ > 0) out_.errors.push_back({out_.path, 0, "", unlisted_});
  if (boxes_ > kMaxBoxesPerFile)
    out_.errors.push_back({out_.path, 0,
                           fmt::format("{} boxes, more than the {} per image this tool handles (docs/study-format.md)",
                                       boxes_, kMaxBoxesPerFile)});
  return std::move(out_);
}

LabelFile parse_labels(const std::string& text, const std::string& file_name, const LabelParseOptions& options) {
  LabelParser p(file_name, options);
  p.feed(text);
  return p.finish();
}

LabelFile read_labels(const std::string& path, const LabelParseOptions& options) {
  try {
    if (file_kind(path) == FileKind::kMissing) {  // a dangling link or no access is an error, not "missing"
      LabelFile missing;
      missing.path = path;
      return missing;
    }
    return parse_labels(read_file(path, kMaxLabelFileBytes), path, options);
  } catch (const IoError& e) {
    LabelFile bad;
    bad.path = path;
    bad.exists = true;
    // IoError's text already starts with the path.
    bad.errors.push_back({path, 0, std::string(e.what()).substr(path.size() + 2)});
    return bad;
  }
}

LabelFile read_labels_beneath(const std::string& root, const std::string& relative, const LabelParseOptions& options) {
  const std::string path = (std::filesystem::path(root) / relative).string();
  try {
    // Parsed as it is read: memory for a line and the boxes, not for the file.
    LabelParser parser(path, options);
    if (!read_file_beneath_in_chunks(root, relative, kMaxLabelFileBytes,
                                     [&](std::string_view piece) { parser.feed(piece); })) {
      LabelFile missing;
      missing.path = path;
      return missing;
    }
    return parser.finish();
  } catch (const IoError& e) {
    LabelFile bad;
    bad.path = path;
    bad.exists = true;
    // The message starts with the path it is about: this file, or a folder on its way.
    const std::string what = e.what();
    const bool this_file = what.rfind(path + ": ", 0) == 0;
    bad.errors.push_back({path, 0, this_file ? what.substr(path.size() + 2) : what});
    return bad;
  }
}

void keep_class(LabelFile* file, int cls) {
  if (cls < 0) return;
  size_t k = 0;
  for (size_t i = 0; i < file->boxes.size(); ++i) {
    if (file->boxes[i].cls != cls) continue;
    file->boxes[k] = file->boxes[i];
    file->line_of_box[k] = file->line_of_box[i];
    ++k;
  }
  file->boxes.resize(k);
  file->line_of_box.resize(k);
}

void keep_confident(LabelFile* file, double threshold) {
  size_t k = 0;
  for (size_t i = 0; i < file->boxes.size(); ++i) {
    if (!kept_at_threshold(file->boxes[i], threshold)) continue;
    file->boxes[k] = file->boxes[i];
    file->line_of_box[k] = file->line_of_box[i];
    ++k;
  }
  file->boxes.resize(k);
  file->line_of_box.resize(k);
}

std::string labels_text(const std::vector<Box>& boxes, LabelKind kind, LabelDigits digits) {
  std::string text;
  for (const auto& b : boxes) {
    if (b.outline) {  // YOLO-seg: the outline's points stand for the box (its bounds)
      text += fmt::format("{}", b.cls);
      for (const Eigen::Vector2d& p : b.outline->points) {
        if (digits == LabelDigits::kExact)
          text += fmt::format(" {} {}", p.x(), p.y());
        else
          text += fmt::format(" {:.6f} {:.6f}", p.x(), p.y());
      }
      if (kind == LabelKind::kPrediction)
        text += digits == LabelDigits::kExact ? fmt::format(" {}", b.conf) : fmt::format(" {:.4f}", b.conf);
      text += '\n';
      continue;
    }
    if (digits == LabelDigits::kExact) {
      // fmt's "{}" is the shortest decimal that reads back as the same double.
      text += fmt::format("{} {} {} {} {}", b.cls, b.cx, b.cy, b.w, b.h);
      if (kind == LabelKind::kPrediction) text += fmt::format(" {}", b.conf);
    } else {
      text += fmt::format("{} {:.6f} {:.6f} {:.6f} {:.6f}", b.cls, b.cx, b.cy, b.w, b.h);
      if (kind == LabelKind::kPrediction) text += fmt::format(" {:.4f}", b.conf);
    }
    text += '\n';
  }
  return text;
}

void write_labels(const std::string& path, const std::vector<Box>& boxes, LabelKind kind, LabelDigits digits) {
  write_file_atomically(path, labels_text(boxes, kind, digits));
}

}  // namespace ipd
