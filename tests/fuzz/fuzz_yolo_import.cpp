// Fuzzes `ipd import yolo` end to end on a label file: the input is one dataset's label file (labels/s1.txt, with
// a second, valid one beside it), imported with and without --skip-bad-lines and with --names. An import writes
// the domain whole or not at all: written exactly when it reports no error it could not skip, every error names
// a file of the dataset, and what it writes reads back without the lines it skipped.
#include <filesystem>
#include <string>

#include "core/io/label_io.h"
#include "core/study/yolo_import.h"
#include "core/util/atomic_file.h"
#include "core/util/errors.h"
#include "tests/fuzz/fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::filesystem::path dir = ipd_fuzz::scratch_dir() / "yolo";
  std::error_code ec;
  std::filesystem::remove_all(dir, ec);
  ipd_fuzz::write_bytes(dir / "ds/labels/s1.txt", data, size);
  const std::string box = "0 0.5 0.5 0.1 0.1\n0 0.2 0.2 0.1 0.1\n";
  ipd_fuzz::write_bytes(dir / "ds/labels/s2.txt", reinterpret_cast<const uint8_t*>(box.data()), box.size());
  for (int variant = 0; variant < 3; ++variant) {
    std::filesystem::remove_all(dir / "study", ec);
    ipd::YoloImportOptions o;
    o.source = (dir / "ds").string();
    o.out_dir = (dir / "study/real").string();
    o.skip_bad_lines = variant >= 1;
    if (variant == 2) o.names = {"rock"};
    try {
      const ipd::YoloImportReport r = ipd::import_yolo(o);
      for (const ipd::LabelError& e : r.errors) ipd_fuzz::check_message(e.to_string(), (dir / "ds").string());
      const bool there = std::filesystem::exists(dir / "study/real", ec);
      if (r.written != there) ipd_fuzz::fail("the report and the study disagree on what was written", o.source);
      if (r.written && !o.skip_bad_lines && !r.errors.empty())
        ipd_fuzz::fail("written although lines were bad", r.errors.front().to_string());
      if (!r.written) continue;
      // What was written reads back clean: the skipped lines are comments now.
      const ipd::LabelFile f = ipd::read_labels((dir / "study/real/labels/s1.txt").string(), {});
      if (!f.errors.empty() && !f.errors.front().unusable_file())
        ipd_fuzz::fail("an imported label file has malformed lines", f.errors.front().to_string());
    } catch (const ipd::StudyError& e) {
      ipd_fuzz::check_message(e.what(), dir.string());
      if (std::filesystem::exists(dir / "study/real", ec)) ipd_fuzz::fail("written although it stopped", e.what());
    } catch (const ipd::IoError& e) {
      ipd_fuzz::check_message(e.what(), dir.string());
    }
  }
  return 0;
}
