// COCO imports that could lose or change labels: images whose label files would collide, boxes too small for a
// label file, skipped entries, a category id given twice. Each is an error or a warning naming the file.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>

#include "core/study/coco_import.h"
#include "core/util/errors.h"
#include "tests/support/test_support.h"

namespace ipd {
namespace {

namespace fs = std::filesystem;

std::string slurp(const std::string& path) {
  std::ifstream in(path);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

CocoImportOptions coco_options(const test::TempDir& d) {
  CocoImportOptions o;
  o.annotations = d / "ann.json";
  o.out_dir = d / "study/real";
  return o;
}

std::string coco(const std::string& images, const std::string& categories = "[{\"id\": 3, \"name\": \"rock\"}]") {
  return "{\"images\": " + images + ", \"categories\": " + categories +
         ", \"annotations\": [{\"image_id\": 1, \"category_id\": 3, \"bbox\": [10, 10, 20, 20]},"
         " {\"image_id\": 2, \"category_id\": 3, \"bbox\": [50, 50, 20, 20]}]}";
}

// cam1/0001.png and cam2/0001.png both wrote labels/0001.txt (the second won), and an image named
// classes.png lost its labels to the class names; exit 0 both times.
TEST(InputChecks, CocoImagesWhoseLabelsWouldCollideAreRefusedByName) {
  test::TempDir d;
  test::write_text(d / "ann.json",
                   coco("[{\"id\": 1, \"file_name\": \"cam1/0001.png\", \"width\": 100, \"height\": 100},"
                        " {\"id\": 2, \"file_name\": \"cam2/0001.png\", \"width\": 100, \"height\": 100}]"));
  const std::string collision = d / "ann.json" +
                                ": images[0] \"cam1/0001.png\" and images[1] \"cam2/0001.png\" would both write "
                                "labels/0001.txt; give the images distinct names (or import each folder into a "
                                "domain of its own)";
  CocoImportReport r = import_coco(coco_options(d));
  EXPECT_EQ(r.collisions, std::vector<std::string>{collision});
  EXPECT_FALSE(r.written);
  EXPECT_FALSE(fs::exists(d / "study"));
  // Never skipped: --skip-bad-lines skips malformed entries, not labels that would land on each other.
  auto skipping = coco_options(d);
  skipping.skip_bad_entries = true;
  EXPECT_FALSE(import_coco(skipping).written);
  const auto cli = test::run_ipd("import coco " + d / "ann.json" + " --images " + d.path() + " --out " +
                                 d / "study/real --skip-bad-lines");
  EXPECT_EQ(cli.exit_code, 1);
  EXPECT_EQ(cli.err, collision + "\nerror: 1 image name collision; nothing written\n");

  test::write_text(d / "ann.json", coco("[{\"id\": 1, \"file_name\": \"classes.png\", \"width\": 100, \"height\": 100},"
                                        " {\"id\": 2, \"file_name\": \"b.png\", \"width\": 100, \"height\": 100}]"));
  r = import_coco(coco_options(d));
  EXPECT_EQ(r.collisions, std::vector<std::string>{d / "ann.json" +
                                                   ": images[0] \"classes.png\" would write labels/classes.txt, which "
                                                   "holds the class names; rename the image"});
  EXPECT_FALSE(r.written);

  // Distinct names import as before.
  test::write_text(d / "ann.json",
                   coco("[{\"id\": 1, \"file_name\": \"cam1/0001.png\", \"width\": 100, \"height\": 100},"
                        " {\"id\": 2, \"file_name\": \"cam2/0002.png\", \"width\": 100, \"height\": 100}]"));
  r = import_coco(coco_options(d));
  EXPECT_TRUE(r.collisions.empty());
  EXPECT_TRUE(r.written);
  EXPECT_EQ(slurp(d / "study/real/labels/0002.txt"), "3 0.6 0.6 0.2 0.2\n");
}

// A box under a millionth of the image a side was written as "0.000000", which ipd then refused in every command:
// the import names the entry instead.
TEST(InputChecks, CocoBoxesTooSmallForALabelFileAreNamed) {
  test::TempDir d;
  test::write_text(d / "ann.json",
                   "{\"images\": [{\"id\": 1, \"file_name\": \"a.png\", \"width\": 200, \"height\": 100}],"
                   " \"categories\": [{\"id\": 3, \"name\": \"rock\"}], \"annotations\": ["
                   "{\"image_id\": 1, \"category_id\": 3, \"bbox\": [50, 25, 0.0001, 10]}]}");
  const auto r =
      test::run_ipd("import coco " + d / "ann.json" + " --images " + d.path() + " --out " + d / "study/real");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_EQ(r.err, d / "ann.json" +
                       ": annotations[0]: expected bbox of at least a millionth of the 200x100 image a side, found "
                       "[50,25,0.0001,10]\nerror: 1 malformed entry; nothing written (--skip-bad-lines skips them)\n");
}

// With --skip-bad-lines the import skipped a bad entry and wrote the rest, then said "nothing written" and
// exited 1: a COCO entry has no line, and a line-less error read as an unreadable file.
TEST(InputChecks, CocoSkippedEntriesAreWarningsAndTheImportSaysItWrote) {
  test::TempDir d;
  test::write_text(d / "ann.json",
                   "{\"images\": [{\"id\": 1, \"file_name\": \"a.png\", \"width\": 200, \"height\": 100}],"
                   " \"categories\": [{\"id\": 3, \"name\": \"rock\"}], \"annotations\": ["
                   "{\"image_id\": 1, \"category_id\": 3, \"bbox\": [50, 25, 0, 10]},"
                   " {\"image_id\": 1, \"category_id\": 3, \"bbox\": [50, 25, 10, 10]}]}");
  const std::string import = "import coco " + d / "ann.json" + " --images " + d.path() + " --out " + d / "study/real";
  const std::string entry = d / "ann.json" + ": annotations[0]: expected bbox with w > 0 and h > 0, found [50,25,0,10]";
  auto r = test::run_ipd(import);
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_EQ(r.err, entry + "\nerror: 1 malformed entry; nothing written (--skip-bad-lines skips them)\n");
  EXPECT_FALSE(fs::exists(d / "study"));
  r = test::run_ipd(import + " --skip-bad-lines");
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_EQ(r.err, "warning: " + entry + "\nwarning: 1 malformed entry skipped (--skip-bad-lines)\n");
  EXPECT_EQ(r.out, "1 images, 1 GT boxes, 0 detections, 1 classes, 0 pictures linked -> " + d / "study/real" + "\n");
  EXPECT_EQ(slurp(d / "study/real/labels/a.txt"), "3 0.275 0.3 0.05 0.1\n");
}

// Categories 3 and 3 (and 7): which name class 3 has would be a guess (numbered by rank they made classes 0,
// 1, 2 with class_of[3] = 1, and `rock_class: 0` dropped every rock).
TEST(InputChecks, CocoDuplicateCategoryIdIsAnError) {
  test::TempDir d;
  test::write_text(
      d / "ann.json",
      coco("[{\"id\": 1, \"file_name\": \"a.png\", \"width\": 100, \"height\": 100}]",
           "[{\"id\": 3, \"name\": \"rock\"}, {\"id\": 7, \"name\": \"shadow\"}, {\"id\": 3, \"name\": \"stone\"}]"));
  try {
    import_coco(coco_options(d));
    ADD_FAILURE() << "accepted";
  } catch (const StudyError& e) {
    EXPECT_EQ(std::string(e.what()), d / "ann.json" +
                                         ": categories[2]: category id 3 appears twice (also categories[0]); every "
                                         "category needs its own id, since YOLO class numbers are the ids");
  }
  EXPECT_FALSE(fs::exists(d / "study"));
}

}  // namespace
}  // namespace ipd
