// YOLOv5 ONNX inference with known outputs (tiny models written by make_onnx_model.py with Debian's
// python3-onnx), letterbox un-mapping on a 1936 x 1216 picture, thresholds, NMS, classes; COCO import.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <opencv2/imgcodecs.hpp>

#include "core/detect/yolo.h"
#include "core/study/coco_import.h"
#include "core/study/study.h"
#include "core/util/atomic_file.h"
#include "tests/support/test_support.h"

namespace fs = std::filesystem;

namespace ipd {
namespace {

bool have_python_onnx() { return std::system("/usr/bin/python3 -c 'import onnx' >/dev/null 2>&1") == 0; }

std::string make_model(const test::TempDir& d, const std::string& name, const std::string& layout,
                       const std::string& rows, int imgsz = 640) {
  const std::string path = d / name;
  const std::string cmd = std::string("/usr/bin/python3 ") + IPD_TESTS_DIR + "/support/make_onnx_model.py " + path +
                          " " + std::to_string(imgsz) + " " + layout + " '" + rows + "'";
  EXPECT_EQ(std::system(cmd.c_str()), 0) << cmd;
  return path;
}

#define REQUIRE_ONNX() \
  if (!have_python_onnx()) GTEST_SKIP() << "python3-onnx is not installed (./run.sh installs it); skipping"

TEST(Letterbox, MatchesYolov5OnANonSquarePicture) {
  const Letterbox lb = letterbox_for(1936, 1216, 640);
  EXPECT_NEAR(lb.scale, 640.0 / 1936, 1e-12);
  EXPECT_EQ(lb.width, 640);
  EXPECT_EQ(lb.height, 402);  // 1216 * 0.330578 = 401.98
  EXPECT_EQ(lb.left, 0);
  EXPECT_EQ(lb.top, 119);  // round((640 - 402) / 2 - 0.1)
  const Letterbox tall = letterbox_for(480, 640, 640);
  EXPECT_EQ(tall.left, 80);
  EXPECT_EQ(tall.top, 0);
  const cv::Mat img = apply_letterbox(cv::Mat(1216, 1936, CV_8UC3, cv::Scalar(0, 0, 0)), lb, 640);
  EXPECT_EQ(img.at<cv::Vec3b>(10, 320), cv::Vec3b(114, 114, 114));  // padding
  EXPECT_EQ(img.at<cv::Vec3b>(320, 320), cv::Vec3b(0, 0, 0));       // picture
}

TEST(Yolo, DecodesThresholdsNmsAndClassesThroughTheLetterbox) {
  REQUIRE_ONNX();
  test::TempDir d;
  // Rows in letterbox pixels: cx cy w h obj cls0 cls1.
  const std::string model = make_model(d, "v5.onnx", "v5",
                                       "[[320, 320, 100, 50, 0.9, 0.8, 0.1],"   // kept: class 0, conf 0.72
                                       " [322, 321, 100, 50, 0.9, 0.7, 0.1],"   // same class, IoU ~0.95: suppressed
                                       " [322, 321, 100, 50, 0.9, 0.1, 0.6],"   // class 1 at the same place: kept
                                       " [100, 200, 40, 40, 0.2, 0.9, 0.1],"    // objectness below 0.25: dropped
                                       " [500, 300, 40, 40, 0.9, 0.2, 0.1]]");  // 0.9 * 0.2 = 0.18: dropped
  YoloDetector det(model, {});
  EXPECT_EQ(det.head(), YoloHead::kV5);
  EXPECT_EQ(det.classes(), 2);
  const std::vector<Box> boxes = det.detect(cv::Mat(1216, 1936, CV_8UC3, cv::Scalar(50, 60, 70)));
  ASSERT_EQ(boxes.size(), 2u);
  // x: (270 .. 370) / (640/1936) = 816.75 .. 1119.25; y: (295 .. 345 - 119) / (640/1936) = 532.4 .. 683.65.
  const double s = 640.0 / 1936;
  EXPECT_EQ(boxes[0].cls, 0);
  EXPECT_NEAR(boxes[0].conf, 0.72, 1e-6);
  EXPECT_NEAR(boxes[0].cx, (270 / s + 370 / s) / 2 / 1936, 1e-6);
  EXPECT_NEAR(boxes[0].cy, ((295 - 119) / s + (345 - 119) / s) / 2 / 1216, 1e-6);
  EXPECT_NEAR(boxes[0].w, 100 / s / 1936, 1e-6);
  EXPECT_NEAR(boxes[0].h, 50 / s / 1216, 1e-6);
  EXPECT_EQ(boxes[1].cls, 1);
  EXPECT_NEAR(boxes[1].conf, 0.54, 1e-6);
  // Class filter and a higher threshold.
  YoloOptions only1;
  only1.classes = {1};
  EXPECT_EQ(YoloDetector(model, only1).detect(cv::Mat(1216, 1936, CV_8UC3)).size(), 1u);
  YoloOptions strict;
  strict.conf = 0.8;
  EXPECT_TRUE(YoloDetector(model, strict).detect(cv::Mat(1216, 1936, CV_8UC3)).empty());
}

TEST(Yolo, Yolov8HeadIsRecognisedAndDecoded) {
  REQUIRE_ONNX();
  test::TempDir d;
  const std::string model =
      make_model(d, "v8.onnx", "v8", "[[320, 320, 64, 64, 0.1, 0.9, 0.2], [50, 50, 10, 10, 0.1, 0.1, 0.1]]");
  YoloDetector det(model, {});
  EXPECT_EQ(det.head(), YoloHead::kV8);
  EXPECT_EQ(det.classes(), 3);
  const auto boxes = det.detect(cv::Mat(640, 640, CV_8UC3));
  ASSERT_EQ(boxes.size(), 1u);
  EXPECT_EQ(boxes[0].cls, 1);
  EXPECT_NEAR(boxes[0].conf, 0.9, 1e-6);
  EXPECT_NEAR(boxes[0].cx, 0.5, 1e-6);
  EXPECT_NEAR(boxes[0].w, 0.1, 1e-6);
}

TEST(Yolo, BadModelsAreRefusedByName) {
  REQUIRE_ONNX();
  test::TempDir d;
  try {
    YoloDetector(d / "none.onnx", {});
    FAIL();
  } catch (const ModelError& e) {
    EXPECT_EQ(std::string(e.what()), d / "none.onnx" + ": no such model file");
  }
  test::write_text(d / "junk.onnx", "not a model");
  EXPECT_THROW(YoloDetector(d / "junk.onnx", {}), ModelError);
  // A head with 5 columns: no class scores, so neither [1, N, 5+nc] with nc >= 1 nor [1, 4+nc, N].
  const std::string odd = make_model(d, "odd.onnx", "v5", "[[1, 2, 3, 4, 5], [1, 2, 3, 4, 5]]");
  try {
    YoloDetector(odd, {});
    FAIL();
  } catch (const ModelError& e) {
    EXPECT_EQ(std::string(e.what()),
              odd + ": output [1, 25200, 5] is not a YOLO head (expected YOLOv5 [1, N, 5+nc] or YOLOv8 [1, 4+nc, N])");
  }
}

TEST(Yolo, CliFillsEveryDomainOfAStudyAndWritesEmptyFiles) {
  REQUIRE_ONNX();
  test::TempDir d;
  const std::string model = make_model(d, "m.onnx", "v5", "[[320, 320, 100, 50, 0.9, 0.8], [10, 10, 5, 5, 0.1, 0.1]]");
  for (const std::string dom : {"real", "synth"}) {
    test::write_text(d / ("study/" + dom + "/labels/a.txt"), "0 0.5 0.5 0.1 0.1\n");
    fs::create_directories(d / ("study/" + dom + "/images"));
    cv::imwrite(d / ("study/" + dom + "/images/a.png"), cv::Mat(1216, 1936, CV_8UC3, cv::Scalar(9, 9, 9)));
  }
  auto r = test::run_ipd("detect " + d / "study" + " --onnx " + model + " --model yolo");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const std::string dom : {"real", "synth"}) {
    const LabelFile f = read_labels(d / ("study/" + dom + "/predictions/yolo/a.txt"), {LabelKind::kPrediction});
    ASSERT_TRUE(f.exists);
    ASSERT_EQ(f.boxes.size(), 1u);
    EXPECT_NEAR(f.boxes[0].cx, 0.5, 1e-4);
  }
  // Nothing above the threshold: an empty file, not a missing one.
  r = test::run_ipd("detect " + d / "study/real/images" + " --onnx " + model + " --conf 0.99 --out " + d / "empty");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(fs::exists(d / "empty/a.txt"));
  EXPECT_EQ(fs::file_size(d / "empty/a.txt"), 0u);
  // The classical detector needs no model.
  r = test::run_ipd("detect " + d / "study/real/images" + " --detector classical --out " + d / "classical");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  r = test::run_ipd("detect " + d / "study/real/images" + " --out " + d / "x");
  EXPECT_EQ(r.exit_code, 2);  // no --onnx
}

// A study is untrusted: `real/predictions` linked to a folder elsewhere must not make `ipd detect STUDY
// --model` write there. Refused as the study is read, before anything is written, in every domain; a model name
// must be a file name.
TEST(Detect, AStudysLinkedPredictionsFolderIsNotWrittenThrough) {
  test::TempDir d;
  for (const std::string dom : {"real", "synth"}) {
    test::write_text(d / ("study/" + dom + "/labels/a.txt"), "0 0.5 0.5 0.1 0.1\n");
    fs::create_directories(d / ("study/" + dom + "/images"));
    cv::imwrite(d / ("study/" + dom + "/images/a.png"), cv::Mat(200, 300, CV_8UC3, cv::Scalar(9, 9, 9)));
  }
  fs::create_directories(d / "elsewhere");
  fs::create_directory_symlink(d / "elsewhere", d / "study/real/predictions");
  auto r = test::run_ipd("detect " + d / "study" + " --detector classical --model classical");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_EQ(r.err, "error: " + d / "study/real/predictions" +
                       ": is a symbolic link; reading through it is refused (links inside a study are never "
                       "followed)\n");
  EXPECT_FALSE(fs::exists(d / "elsewhere/classical"));
  EXPECT_FALSE(fs::exists(d / "study/synth/predictions/classical/a.txt"));  // all domains or none
  // Without the link both domains are filled.
  fs::remove(d / "study/real/predictions");
  r = test::run_ipd("detect " + d / "study" + " --detector classical --model classical");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(fs::exists(d / "study/real/predictions/classical/a.txt"));
  EXPECT_TRUE(fs::exists(d / "study/synth/predictions/classical/a.txt"));
  r = test::run_ipd("detect " + d / "study" + " --detector classical --model ../up");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--model"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(d / "study/real/up"));
}

// A detector run into a folder of label files replaced them without a word: GT labels by predictions
// (pictures mode, --out STUDY/real/labels), or a model's predictions by a second run that kept the first run's
// files of pictures it did not see, mixing two runs. Refused, nothing written; --replace replaces the set whole.
TEST(Detect, AFolderThatHoldsLabelFilesIsReplacedOnlyWhenAskedAndThenWhole) {
  test::TempDir d;
  for (const std::string dom : {"real", "synth"}) {
    test::write_text(d / ("study/" + dom + "/labels/a.txt"), "0 0.5 0.5 0.1 0.1\n");
    fs::create_directories(d / ("study/" + dom + "/images"));
    cv::imwrite(d / ("study/" + dom + "/images/a.png"), cv::Mat(200, 300, CV_8UC3, cv::Scalar(9, 9, 9)));
  }
  const std::string mix =
      "the predictions of two runs would mix, so nothing is written (--replace replaces the whole set: the .txt "
      "files this run does not write are removed)\n";
  test::write_text(d / "pred/a.txt", "0 0.5 0.5 0.1 0.1 0.9\n");
  auto r = test::run_ipd("detect " + d / "study/real/images --detector classical --out " + d / "pred");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_EQ(r.err, "error: " + d / "pred" + ": already holds 1 label file (e.g. a.txt)\n" + mix);
  EXPECT_EQ(read_file(d / "pred/a.txt"), "0 0.5 0.5 0.1 0.1 0.9\n");
  // Beside images/ it is ground truth: refused even with --replace (the GT would be gone).
  r = test::run_ipd("detect " + d / "study/real/images --detector classical --replace --out " +
                    d / "study/real/labels");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_EQ(r.err, "error: " + d / "study/real/labels" +
                       ": is a domain's ground-truth labels; detections written there would replace them, so nothing "
                       "is written (a study's predictions: ipd detect STUDY --model NAME)\n");
  EXPECT_EQ(read_file(d / "study/real/labels/a.txt"), "0 0.5 0.5 0.1 0.1\n");

  const std::string run = "detect " + d / "study" + " --detector classical --model classical";
  ASSERT_EQ(test::run_ipd(run).exit_code, 0);
  test::write_text(d / "study/real/predictions/classical/gone.txt", "0 0.5 0.5 0.1 0.1 0.9\n");
  test::write_text(d / "study/synth/predictions/classical/notes.md", "mine");
  r = test::run_ipd(run);
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_EQ(r.err, "error: " + d / "study/real/predictions/classical" + ": already holds 2 label files (e.g. a.txt)\n" +
                       d / "study/synth/predictions/classical" + ": already holds 1 label file (e.g. a.txt)\n" + mix);
  EXPECT_TRUE(fs::exists(d / "study/real/predictions/classical/gone.txt"));
  r = test::run_ipd(run + " --replace");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.out, "1 label file of the earlier run removed\n2 pictures, predictions written\n");
  EXPECT_FALSE(fs::exists(d / "study/real/predictions/classical/gone.txt"));
  EXPECT_TRUE(fs::exists(d / "study/real/predictions/classical/a.txt"));
  EXPECT_EQ(read_file(d / "study/synth/predictions/classical/notes.md"), "mine");  // not a label file
}

// A picture that is a FIFO got no predictions and no word ("17 pictures, predictions written"): its scene then
// read as "nothing detected". An error naming it, and nothing written.
TEST(Detect, APictureThatIsNotARegularFileIsAnError) {
  test::TempDir d;
  fs::create_directories(d / "pics");
  cv::imwrite(d / "pics/a.png", cv::Mat(60, 80, CV_8UC3, cv::Scalar(9, 9, 9)));
  ASSERT_EQ(::mkfifo((d / "pics/b.png").c_str(), 0600), 0);
  const auto r = test::run_ipd("detect " + d / "pics" + " --detector classical --out " + d / "pred");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_EQ(r.err, "error: " + d / "pics/b.png" + ": is a FIFO, expected a regular file\n");
  EXPECT_FALSE(fs::exists(d / "pred/a.txt"));
}

TEST(CocoImport, GroundTruthAndResultsToTheStudyLayout) {
  test::TempDir d;
  test::write_text(d / "ann.json", R"({
    "images": [{"id": 1, "file_name": "a.png", "width": 200, "height": 100},
               {"id": 2, "file_name": "b.png", "width": 200, "height": 100}],
    "categories": [{"id": 7, "name": "shadow"}, {"id": 3, "name": "rock"}],
    "annotations": [{"image_id": 1, "category_id": 3, "bbox": [50, 25, 20, 10]},
                    {"image_id": 1, "category_id": 7, "bbox": [0, 0, 200, 100]}]})");
  test::write_text(d / "res.json", R"([{"image_id": 1, "category_id": 3, "bbox": [52, 25, 20, 10], "score": 0.8}])");
  test::write_text(d / "pics/a.png", "");
  CocoImportOptions o;
  o.annotations = d / "ann.json";
  o.results = d / "res.json";
  o.images_dir = d / "pics";
  o.out_dir = d / "study/real";
  const CocoImportReport r = import_coco(o);
  ASSERT_TRUE(r.errors.empty()) << r.errors[0].to_string();
  // The class is the category id, whatever else the file lists; unused numbers have no name.
  EXPECT_EQ(r.classes, (std::vector<std::string>{"", "", "", "rock", "", "", "", "shadow"}));
  EXPECT_EQ(r.categories, 2);
  EXPECT_EQ(r.linked_images, 1);
  const LabelFile a = read_labels(d / "study/real/labels/a.txt", {});
  ASSERT_EQ(a.boxes.size(), 2u);
  EXPECT_EQ(a.boxes[0].cls, 3);
  EXPECT_DOUBLE_EQ(a.boxes[0].cx, 0.3);  // (50 + 10) / 200
  EXPECT_DOUBLE_EQ(a.boxes[0].cy, 0.3);  // (25 + 5) / 100
  EXPECT_DOUBLE_EQ(a.boxes[0].w, 0.1);
  EXPECT_EQ(a.boxes[1].cls, 7);
  EXPECT_TRUE(fs::exists(d / "study/real/labels/b.txt"));  // an image without rocks
  const LabelFile p = read_labels(d / "study/real/predictions/coco-results/a.txt", {LabelKind::kPrediction});
  ASSERT_EQ(p.boxes.size(), 1u);
  EXPECT_DOUBLE_EQ(p.boxes[0].conf, 0.8);
  // A hard link (here) or a copy, never a symbolic link: a study's links are not followed when it is read.
  EXPECT_FALSE(fs::is_symlink(d / "study/real/images/a.png"));
  EXPECT_TRUE(fs::equivalent(d / "study/real/images/a.png", d / "pics/a.png"));
}

TEST(CocoImport, EveryBadEntryIsReportedAndNothingWritten) {
  test::TempDir d;
  test::write_text(d / "ann.json", R"({
    "images": [{"id": 1, "file_name": "a.png", "width": 200, "height": 100}],
    "categories": [{"id": 3, "name": "rock"}],
    "annotations": [{"image_id": 1, "category_id": 3, "bbox": [50, 25, 0, 10]},
                    {"image_id": 9, "category_id": 3, "bbox": [1, 1, 2, 2]},
                    {"image_id": 1, "category_id": 4, "bbox": [1, 1, 2, 2]},
                    {"image_id": 1, "category_id": 3, "bbox": [190, 25, 30, 10]}]})");
  CocoImportOptions o;
  o.annotations = d / "ann.json";
  o.out_dir = d / "out";
  const CocoImportReport r = import_coco(o);
  ASSERT_EQ(r.errors.size(), 4u);
  EXPECT_EQ(r.errors[0].to_string(),
            d / "ann.json" + ": annotations[0]: expected bbox with w > 0 and h > 0, found [50,25,0,10]");
  EXPECT_EQ(r.errors[1].to_string(), d / "ann.json" + ": annotations[1]: image_id 9 is not among the images");
  EXPECT_EQ(r.errors[2].to_string(), d / "ann.json" + ": annotations[2]: category_id 4 is not among the categories");
  EXPECT_EQ(r.errors[3].to_string(),
            d / "ann.json" + ": annotations[3]: expected bbox inside the 200x100 image, found [190,25,30,10]");
  EXPECT_FALSE(r.written);
  EXPECT_FALSE(fs::exists(d / "out"));
  o.skip_bad_entries = true;
  EXPECT_TRUE(import_coco(o).written);
  test::write_text(d / "broken.json", "{\"images\": [");
  o.annotations = d / "broken.json";
  EXPECT_THROW(import_coco(o), StudyError);
}

}  // namespace
}  // namespace ipd
