// Fuzzes `ipd import predictions` end to end: the input's first byte picks the source, the rest is its file.
// Even: a YOLO run's label file (exp/labels/s1.txt, a valid s2.txt beside it), imported with and without
// --no-conf; odd: COCO results JSON against a fixed COCO annotations file (--gt). The domain's ground truth is
// never touched; the prediction set is written whole exactly when the import says so, or not at all; every
// error names a file of the run.
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "core/study/prediction_import.h"
#include "core/util/errors.h"
#include "tests/fuzz/fuzz_support.h"

namespace {

std::string file_text(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void put(const std::filesystem::path& p, const std::string& text) {
  ipd_fuzz::write_bytes(p, reinterpret_cast<const uint8_t*>(text.data()), text.size());
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size == 0) return 0;
  const bool coco = data[0] % 2 == 1;
  const std::filesystem::path dir = ipd_fuzz::scratch_dir() / "predictions";
  std::error_code ec;
  std::filesystem::remove_all(dir, ec);
  const std::string gt_text = "0 0.5 0.5 0.1 0.1\n";
  put(dir / "study/real/labels/s1.txt", gt_text);
  put(dir / "study/real/labels/s2.txt", gt_text);
  ipd::PredictionImportOptions o;
  o.out_dir = (dir / "study/real").string();
  o.model = "det";
  if (coco) {
    o.source = (dir / "results.json").string();
    o.gt = (dir / "instances.json").string();
    ipd_fuzz::write_bytes(o.source, data + 1, size - 1);
    put(o.gt, R"({"images": [{"id": 1, "file_name": "s1.jpg", "width": 100, "height": 50},)"
              R"( {"id": 2, "file_name": "s2.jpg", "width": 100, "height": 50}],)"
              R"( "categories": [{"id": 1, "name": "rock"}], "annotations": []})");
  } else {
    o.source = (dir / "exp").string();
    ipd_fuzz::write_bytes(dir / "exp/labels/s1.txt", data + 1, size - 1);
    put(dir / "exp/labels/s2.txt", "0 0.5 0.5 0.1 0.1 0.9\n");
  }
  const std::filesystem::path set = dir / "study/real/predictions/det";
  for (int variant = 0; variant < (coco ? 2 : 3); ++variant) {
    std::filesystem::remove_all(set.parent_path(), ec);
    o.no_conf = !coco && variant == 1;
    o.skip_bad_entries = coco && variant == 1;
    try {
      const ipd::PredictionImportReport r = ipd::import_predictions(o);
      for (const ipd::LabelError& e : r.errors) ipd_fuzz::check_message(e.to_string(), dir.string());
      if (r.written != std::filesystem::exists(set, ec))
        ipd_fuzz::fail("the report and the study disagree on what was written", o.source);
      if (r.written && !r.errors.empty() && !o.skip_bad_entries)
        ipd_fuzz::fail("written although entries were bad", r.errors.front().to_string());
      if (r.written && (!std::filesystem::exists(set / "s1.txt", ec) || !std::filesystem::exists(set / "s2.txt", ec)))
        ipd_fuzz::fail("a written set lacks a scene's file (an empty one means no detections)", o.source);
    } catch (const ipd::StudyError& e) {
      ipd_fuzz::check_message(e.what(), dir.string());
      if (std::filesystem::exists(set, ec)) ipd_fuzz::fail("written although it stopped", e.what());
    } catch (const ipd::IoError& e) {
      ipd_fuzz::check_message(e.what(), dir.string());
    }
    for (const char* s : {"s1.txt", "s2.txt"})
      if (file_text(dir / "study/real/labels" / s) != gt_text) ipd_fuzz::fail("the ground truth was changed", s);
  }
  return 0;
}
