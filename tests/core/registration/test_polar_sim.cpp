// The real POLAR-Sim labels from ../shared parse without a single error (skipped when absent).
#include <gtest/gtest.h>

#include <filesystem>

#include "core/io/label_io.h"

namespace fs = std::filesystem;

namespace ipd {
namespace {

TEST(PolarSim, EveryLabelFileParses) {
  const fs::path root = fs::path(IPD_SHARED_DATA) / "labels";
  if (!fs::is_directory(root)) GTEST_SKIP() << "POLAR-Sim labels not found at " << root << "; skipping";
  int files = 0, boxes = 0, rocks = 0;
  for (const auto& e : fs::recursive_directory_iterator(root)) {
    if (e.path().extension() != ".txt" || e.path().filename() == "classes.txt") continue;
    LabelFile f = read_labels(e.path().string(), {});
    ASSERT_TRUE(f.errors.empty()) << f.errors[0].to_string();
    ++files;
    boxes += static_cast<int>(f.boxes.size());
    keep_class(&f, 0);
    rocks += static_cast<int>(f.boxes.size());
  }
  EXPECT_EQ(files, 2446);
  EXPECT_EQ(boxes, 84733);
  EXPECT_GT(rocks, 0);
  EXPECT_LT(rocks, boxes);  // class 1 (shadow) boxes exist and are filtered out
}

}  // namespace
}  // namespace ipd
