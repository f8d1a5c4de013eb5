#include "ipd/label_io.h"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fmt/format.h>
#include <sstream>

#include "ipd/atomic_file.h"

namespace fs = std::filesystem;

namespace ipd {

std::string LabelError::to_string() const {
  if (line > 0) return fmt::format("{}:{}: {}", file, line, message);
  return fmt::format("{}: {}", file, message);
}

namespace {

const char* const kColumnNames[] = {"class", "cx", "cy", "w", "h", "conf"};

std::vector<std::string> split_fields(const std::string& line) {
  std::vector<std::string> out;
  std::istringstream ss(line);
  std::string tok;
  while (ss >> tok) out.push_back(tok);
  return out;
}

std::string shorten(const std::string& s) { return s.size() > 40 ? s.substr(0, 37) + "..." : s; }

// Parses a line's fields into a box or returns why not.
std::string parse_box(const std::vector<std::string>& f, const LabelParseOptions& opt, Box* box) {
  const size_t want = opt.kind == LabelKind::kPrediction ? 6 : 5;
  if (f.size() != want) {
    return fmt::format("expected {} columns ({}), found {}", want,
                       want == 6 ? "class cx cy w h conf" : "class cx cy w h", f.size());
  }
  const std::string& c = f[0];
  if (c.empty() || c.find_first_not_of("0123456789") != std::string::npos || c.size() > 9) {
    return fmt::format("expected a non-negative integer class in column 1, found '{}'", shorten(c));
  }
  box->cls = std::atoi(c.c_str());
  double v[6] = {0, 0, 0, 0, 0, 1};
  for (size_t k = 1; k < want; ++k) {
    const char* s = f[k].c_str();
    char* end = nullptr;
    errno = 0;
    const double x = std::strtod(s, &end);
    if (end == s || *end != '\0') {
      return fmt::format("expected a number for {} in column {}, found '{}'", kColumnNames[k], k + 1, shorten(f[k]));
    }
    if (!std::isfinite(x)) {
      return fmt::format("expected a finite number for {} in column {}, found '{}'", kColumnNames[k], k + 1, f[k]);
    }
    v[k] = x;
  }
  for (size_t k = 1; k < want; ++k) {
    if (v[k] < -opt.range_tolerance || v[k] > 1.0 + opt.range_tolerance) {
      return fmt::format("expected {} in [0, 1] (normalised), found {}", kColumnNames[k], f[k]);
    }
  }
  if (v[3] <= 0) return fmt::format("expected w > 0, found {}", f[3]);
  if (v[4] <= 0) return fmt::format("expected h > 0, found {}", f[4]);
  box->cx = v[1];
  box->cy = v[2];
  box->w = v[3];
  box->h = v[4];
  box->conf = v[5];
  return {};
}

}  // namespace

LabelFile parse_labels(const std::string& text, const std::string& file_name, const LabelParseOptions& options) {
  LabelFile out;
  out.path = file_name;
  out.exists = true;
  std::istringstream in(text);
  std::string line;
  int line_no = 0;
  while (std::getline(in, line)) {
    ++line_no;
    const size_t hash = line.find('#');
    if (hash != std::string::npos) line.resize(hash);
    const auto fields = split_fields(line);
    if (fields.empty()) continue;
    Box b;
    const std::string why = parse_box(fields, options, &b);
    if (!why.empty()) {
      out.errors.push_back({file_name, line_no, why});
      continue;
    }
    out.boxes.push_back(b);
    out.line_of_box.push_back(line_no);
  }
  return out;
}

LabelFile read_labels(const std::string& path, const LabelParseOptions& options) {
  std::error_code ec;
  if (!fs::exists(path, ec)) {
    LabelFile missing;
    missing.path = path;
    return missing;
  }
  try {
    return parse_labels(read_file(path), path, options);
  } catch (const IoError& e) {
    LabelFile bad;
    bad.path = path;
    bad.exists = true;
    // IoError's text already starts with the path.
    bad.errors.push_back({path, 0, std::string(e.what()).substr(path.size() + 2)});
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
  if (threshold <= 0) return;
  size_t k = 0;
  for (size_t i = 0; i < file->boxes.size(); ++i) {
    if (file->boxes[i].conf < threshold) continue;
    file->boxes[k] = file->boxes[i];
    file->line_of_box[k] = file->line_of_box[i];
    ++k;
  }
  file->boxes.resize(k);
  file->line_of_box.resize(k);
}

void write_labels(const std::string& path, const std::vector<Box>& boxes, LabelKind kind) {
  std::string text;
  for (const auto& b : boxes) {
    text += fmt::format("{} {:.6f} {:.6f} {:.6f} {:.6f}", b.cls, b.cx, b.cy, b.w, b.h);
    if (kind == LabelKind::kPrediction) text += fmt::format(" {:.4f}", b.conf);
    text += '\n';
  }
  write_file_atomically(path, text);
}

}  // namespace ipd
