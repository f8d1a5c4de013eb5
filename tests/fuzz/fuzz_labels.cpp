// Fuzzes the YOLO label parser (ground truth and predictions), in memory and through a file.
#include <cmath>

#include "core/io/label_io.h"
#include "tests/fuzz/fuzz_support.h"

namespace {

void check(const ipd::LabelFile& f, const std::string& name, size_t lines, const ipd::LabelParseOptions& opt) {
  using ipd_fuzz::fail;
  if (f.boxes.size() != f.line_of_box.size()) fail("boxes and line_of_box differ in size", name);
  if (f.boxes.size() + f.errors.size() > lines + 1) fail("more boxes and errors than lines", name);
  int previous = 0;
  for (size_t k = 0; k < f.boxes.size(); ++k) {
    const ipd::Box& b = f.boxes[k];
    if (f.line_of_box[k] <= previous || f.line_of_box[k] > static_cast<int>(lines)) fail("box line out of order", name);
    previous = f.line_of_box[k];
    const double tol = opt.range_tolerance;
    for (double v : {b.cx, b.cy, b.w, b.h, b.conf})
      if (!std::isfinite(v) || v < -tol || v > 1 + tol) fail("a kept box has a value outside [0, 1]", name);
    if (!(b.w > 0 && b.h > 0) || b.cls < 0) fail("a kept box has w <= 0, h <= 0 or a negative class", name);
  }
  for (const ipd::LabelError& e : f.errors) {
    if (e.file != name || e.line < 0 || e.line > static_cast<int>(lines))
      fail("error with a wrong file or line", e.to_string());
    ipd_fuzz::check_message(e.to_string(), name);
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  size_t lines = 1;
  for (char c : text) lines += c == '\n';
  const std::string name = "fuzz/labels.txt";
  for (ipd::LabelKind kind : {ipd::LabelKind::kGroundTruth, ipd::LabelKind::kPrediction}) {
    ipd::LabelParseOptions opt;
    opt.kind = kind;
    ipd::LabelFile f = ipd::parse_labels(text, name, opt);
    check(f, name, lines, opt);
    ipd::keep_class(&f, 0);
    ipd::keep_confident(&f, 0.5);
    if (f.boxes.size() != f.line_of_box.size()) ipd_fuzz::fail("keep_* broke line_of_box", name);
  }
  // The file path (read_labels) as `ipd table` uses it.
  const std::string path = (ipd_fuzz::scratch_dir() / "labels.txt").string();
  ipd_fuzz::write_bytes(path, data, size);
  ipd::LabelParseOptions opt;
  check(ipd::read_labels(path, opt), path, lines, opt);
  return 0;
}
