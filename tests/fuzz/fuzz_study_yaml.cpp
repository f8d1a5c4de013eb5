// Fuzzes study.yaml parsing: every problem must be a StudyError naming the file; anything else that
// escapes (a yaml-cpp exception, a crash) is a bug.
#include "core/study/study.h"
#include "tests/fuzz/fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  const std::string name = "fuzz/study.yaml";
  try {
    const ipd::StudyConfig c = ipd::parse_study_config(text, name);
    if (c.conf_threshold < 0 || c.conf_threshold > 1 || c.rock_class < -1 || c.image_width < 0 || c.image_height < 0)
      ipd_fuzz::fail("parse_study_config accepted an out-of-range setting", text.substr(0, 200));
  } catch (const ipd::StudyError& e) {
    ipd_fuzz::check_message(e.what(), name);
  }
  return 0;
}
