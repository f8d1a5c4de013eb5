// Fuzzes `ipd import yolo`'s source readers: the input is a data.yaml, optionally followed by a line
// "----list----" and a list of pictures the yaml may name as `train: train.txt`, in a dataset folder that has
// images/train/s1.png, labels/train/s1.txt, obj_train_data/ and a names file. A source it can't read is a
// StudyError naming a file of the dataset; anything else escaping, a crash or a hang is a bug.
#include <algorithm>
#include <filesystem>
#include <string>

#include "core/study/yolo_source.h"
#include "core/util/errors.h"
#include "tests/fuzz/fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  // `path:` moves the dataset's root wherever the yaml says (the user's own choice: `path: /` would list the
  // machine); the fuzzer keeps the root in its scratch folder.
  if (text.find("path") != std::string::npos) return 0;
  const std::string separator = "\n----list----\n";
  const size_t cut = text.find(separator);
  const std::filesystem::path dir = ipd_fuzz::scratch_dir() / "ds";
  std::error_code ec;
  std::filesystem::remove_all(dir, ec);
  const std::string yaml = text.substr(0, cut);
  ipd_fuzz::write_bytes(dir / "data.yaml", reinterpret_cast<const uint8_t*>(yaml.data()), yaml.size());
  const std::string list = cut == std::string::npos ? "images/train/s1.png\n" : text.substr(cut + separator.size());
  ipd_fuzz::write_bytes(dir / "train.txt", reinterpret_cast<const uint8_t*>(list.data()), list.size());
  const std::string box = "0 0.5 0.5 0.1 0.1\n", picture = "not decoded";
  ipd_fuzz::write_bytes(dir / "labels/train/s1.txt", reinterpret_cast<const uint8_t*>(box.data()), box.size());
  ipd_fuzz::write_bytes(dir / "images/train/s1.png", reinterpret_cast<const uint8_t*>(picture.data()), picture.size());
  ipd_fuzz::write_bytes(dir / "obj.names", reinterpret_cast<const uint8_t*>(yaml.data()),
                        std::min<size_t>(yaml.size(), 200));
  for (const char* split : {"", "train", "val"}) {
    try {
      const ipd::YoloSource s = ipd::find_yolo_source((dir / "data.yaml").string(), split);
      for (const ipd::SourceScene& x : s.scenes)
        if (x.stem.empty()) ipd_fuzz::fail("a scene without a name", x.label + x.picture);
    } catch (const ipd::StudyError& e) {
      // Messages name the dataset's files (the yaml, a list, a folder below it) or the split asked for.
      ipd_fuzz::check_message(e.what(), dir.string());
    }
  }
  // The same folder as a CVAT export: obj.names (the yaml's first bytes) and train.txt.
  std::filesystem::remove(dir / "data.yaml", ec);
  std::filesystem::create_directories(dir / "obj_train_data", ec);
  try {
    (void)ipd::find_yolo_source(dir.string(), "");
  } catch (const ipd::StudyError& e) {
    ipd_fuzz::check_message(e.what(), dir.string());
  }
  return 0;
}
