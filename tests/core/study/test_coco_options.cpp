// The COCO import options name the path that is missing before any file is read.
#include <gtest/gtest.h>

#include <stdexcept>

#include "core/study/coco_import.h"

namespace ipd {
namespace {

TEST(CocoImportOptions, NameTheMissingPath) {
  CocoImportOptions o;
  EXPECT_EQ(o.validate(), "annotations must name the COCO instances file, got an empty path");
  o.annotations = "instances.json";
  EXPECT_EQ(o.validate(), "out_dir must name the domain directory to fill, got an empty path");
  o.out_dir = "study/real";
  EXPECT_EQ(o.validate(), "");  // no images_dir: labels only, no pictures linked
  o.results = "results.json";
  o.model = "";
  EXPECT_EQ(o.validate(), "model must name the prediction set when results are given, got \"\"");
  try {
    import_coco(o);
    FAIL() << "import_coco accepted results without a model name";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "COCO import options: model must name the prediction set when results are given, got \"\"");
  }
}

}  // namespace
}  // namespace ipd
