// Fuzzes `ipd import coco`: the input is the COCO annotations JSON, optionally followed by a line
// "----results----" and a detection-results JSON. Entry problems go to the report (each naming its file);
// structural ones are StudyError/IoError naming the file; anything else escaping is a bug.
#include "core/study/coco_import.h"
#include "core/study/study.h"
#include "core/util/atomic_file.h"
#include "tests/fuzz/fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  const std::string separator = "\n----results----\n";
  const size_t cut = text.find(separator);
  const std::filesystem::path dir = ipd_fuzz::scratch_dir() / "coco";
  std::error_code ec;
  std::filesystem::remove_all(dir, ec);
  ipd::CocoImportOptions o;
  o.annotations = (dir / "instances.json").string();
  o.out_dir = (dir / "out" / "real").string();
  const std::string gt = text.substr(0, cut);
  ipd_fuzz::write_bytes(o.annotations, reinterpret_cast<const uint8_t*>(gt.data()), gt.size());
  if (cut != std::string::npos) {
    o.results = (dir / "results.json").string();
    const std::string res = text.substr(cut + separator.size());
    ipd_fuzz::write_bytes(o.results, reinterpret_cast<const uint8_t*>(res.data()), res.size());
  }
  try {
    const ipd::CocoImportReport r = ipd::import_coco(o);
    for (const ipd::LabelError& e : r.errors) {
      if (e.file != o.annotations && e.file != o.results)
        ipd_fuzz::fail("a report error names another file", e.to_string());
      ipd_fuzz::check_message(e.to_string(), e.file);
    }
    for (const std::string& c : r.collisions) ipd_fuzz::check_message(c, o.annotations);
    if (r.written != (r.errors.empty() && r.collisions.empty()))
      ipd_fuzz::fail("written although entries were bad or names collide (or not written when fine)", o.annotations);
  } catch (const ipd::StudyError& e) {
    const std::string m = e.what();
    ipd_fuzz::check_message(m, m.find(o.annotations) != std::string::npos ? o.annotations : o.results);
  } catch (const ipd::IoError& e) {
    const std::string m = e.what();
    ipd_fuzz::check_message(m, m.find(o.annotations) != std::string::npos ? o.annotations : o.results);
  }
  return 0;
}
