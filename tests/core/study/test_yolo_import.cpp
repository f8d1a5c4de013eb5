// `ipd import yolo` and `ipd import predictions`: each tool's layout, built here as the tool writes it, imports
// with one command into a study whose `ipd table` cells are byte-identical to those of the same data laid out
// by hand; bad input is refused naming the file (and line), with nothing written.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>
#include <string>
#include <vector>

#include "core/study/yolo_source.h"
#include "core/util/atomic_file.h"
#include "tests/support/test_support.h"

namespace fs = std::filesystem;

namespace ipd {
namespace {

const std::vector<std::string> kStems = {"s1", "s2", "s3"};
const std::vector<std::string> kDomains = {"real", "synth"};
const char* const kStudyYaml = "models: {det: {trained_on: real}}\nimage_size: [64, 48]\n";

std::string lines(const std::vector<Box>& boxes, bool conf) {
  std::string out;
  for (const Box& b : boxes)
    out += conf ? fmt::format("0 {:.6f} {:.6f} {:.6f} {:.6f} {:.4f}\n", b.cx, b.cy, b.w, b.h, b.conf)
                : fmt::format("0 {:.6f} {:.6f} {:.6f} {:.6f}\n", b.cx, b.cy, b.w, b.h);
  return out;
}

// Scene k of a domain: seven rocks, the synthetic ones moved a little; the detector finds some, offset.
std::string gt_of(const std::string& domain, size_t k) {
  return lines(test::seven_rocks(0.01 * static_cast<double>(k) + (domain == "synth" ? 0.004 : 0)), false);
}
std::string predictions_of(const std::string& domain, size_t k) {
  std::vector<Box> rocks = test::seven_rocks(0.01 * static_cast<double>(k) + (domain == "synth" ? 0.012 : 0.003));
  rocks.resize(5 - k);
  for (size_t j = 0; j < rocks.size(); ++j) rocks[j].conf = 0.3 + 0.1 * static_cast<double>(j);
  return lines(rocks, true);
}

void picture(const std::string& path) {
  fs::create_directories(fs::path(path).parent_path());
  ASSERT_TRUE(cv::imwrite(path, cv::Mat(48, 64, CV_8UC3, cv::Scalar(40, 80, 120))));
}

// The study laid out by hand (docs/study-format.md).
void write_flat_study(const std::string& root) {
  for (const std::string& d : kDomains) {
    test::write_text(root + "/" + d + "/labels/classes.txt", "rock\n");
    for (size_t k = 0; k < kStems.size(); ++k) {
      test::write_text(root + "/" + d + "/labels/" + kStems[k] + ".txt", gt_of(d, k));
      test::write_text(root + "/" + d + "/predictions/det/" + kStems[k] + ".txt", predictions_of(d, k));
      picture(root + "/" + d + "/images/" + kStems[k] + ".png");
    }
  }
  test::write_text(root + "/study.yaml", kStudyYaml);
}

// `ipd table --format json`'s cells, as text.
std::string table_cells(const std::string& study) {
  const auto r = test::run_ipd("table " + study + " --format json --bootstrap 200");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out, nullptr, false);
  if (!j.is_object() || !j.contains("cells") || j["cells"].empty()) return "no table: " + r.out + r.err;
  // A number measured from rock pairs, not two empty tables alike.
  const nlohmann::json& first = j["cells"][0];
  EXPECT_TRUE(first["ipd"].is_number()) << first.dump();
  EXPECT_GT(first["pairs"].get<int>(), 10) << first.dump();
  return j["cells"].dump();
}

// A YOLO run over the domain's pictures as the detector saw them named (`names[k]` for scene k), with the
// scene whose detector found nothing left without a file, as YOLOv5 leaves it.
std::string write_run(const std::string& dir, const std::string& domain, const std::vector<std::string>& names) {
  for (size_t k = 0; k < kStems.size(); ++k)
    test::write_text(dir + "/labels/" + names[k] + ".txt", predictions_of(domain, k));
  test::write_text(dir + "/labels/../results.csv", "not a label file\n");
  return dir;
}

struct Imported {
  std::string study;
  std::vector<std::string> outputs;
};

// Imports each domain's source and run into `study` with the documented commands.
void import_all(const std::string& study, const std::map<std::string, std::string>& sources,
                const std::map<std::string, std::string>& runs) {
  for (const std::string& d : kDomains) {
    auto r = test::run_ipd("import yolo " + sources.at(d) + " --out " + study + "/" + d);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    r = test::run_ipd("import predictions " + runs.at(d) + " --out " + study + "/" + d + " --model det");
    ASSERT_EQ(r.exit_code, 0) << r.err;
  }
  test::write_text(study + "/study.yaml", kStudyYaml);
}

TEST(YoloImport, AnUltralyticsDataYamlWithSplitsGivesTheHandBuiltStudysCells) {
  test::TempDir t;
  write_flat_study(t / "flat");
  std::map<std::string, std::string> sources, runs;
  for (const std::string& d : kDomains) {
    const std::string ds = t / ("datasets/" + d);
    // names as a mapping; `path:` relative to the yaml's folder; s3 in val.
    test::write_text(ds + "/data.yaml", "path: .\ntrain: images/train\nval: images/val\nnames:\n  0: rock\n");
    for (size_t k = 0; k < kStems.size(); ++k) {
      const std::string split = k < 2 ? "train" : "val";
      test::write_text(ds + "/labels/" + split + "/" + kStems[k] + ".txt", gt_of(d, k));
      picture(ds + "/images/" + split + "/" + kStems[k] + ".png");
    }
    sources[d] = ds + "/data.yaml";
    runs[d] = write_run(t / ("runs/detect/exp-" + d), d, kStems);
  }
  import_all(t / "study", sources, runs);
  EXPECT_EQ(read_file(t / "study/real/labels/classes.txt"), "rock\n");
  EXPECT_EQ(read_file(t / "study/real/labels/s3.txt"), gt_of("real", 2));
  EXPECT_EQ(table_cells(t / "study"), table_cells(t / "flat"));
}

TEST(YoloImport, ACvatYolo11ExportGivesTheHandBuiltStudysCells) {
  test::TempDir t;
  write_flat_study(t / "flat");
  std::map<std::string, std::string> sources, runs;
  for (const std::string& d : kDomains) {
    const std::string ds = t / ("cvat-" + d);
    test::write_text(ds + "/obj.names", "rock\n");
    test::write_text(ds + "/obj.data",
                     "classes = 1\ntrain = data/train.txt\nnames = data/obj.names\nbackup = backup/\n");
    std::string list;
    for (size_t k = 0; k < kStems.size(); ++k) {
      test::write_text(ds + "/obj_train_data/" + kStems[k] + ".txt", gt_of(d, k));
      picture(ds + "/obj_train_data/" + kStems[k] + ".png");
      list += "data/obj_train_data/" + kStems[k] + ".png\n";
    }
    test::write_text(ds + "/train.txt", list);
    sources[d] = ds;
    runs[d] = write_run(t / ("runs/detect/exp-" + d), d, kStems) + "/labels";  // its labels/ folder
  }
  import_all(t / "study", sources, runs);
  EXPECT_EQ(table_cells(t / "study"), table_cells(t / "flat"));
}

TEST(YoloImport, ALabelStudioExportHasItsUploadPrefixesMappedBack) {
  test::TempDir t;
  write_flat_study(t / "flat");
  std::map<std::string, std::string> sources, runs;
  const std::vector<std::string> prefixes = {"1a2b3c4d-", "0f9e8d7c-", "a0b1c2d3-"};
  for (const std::string& d : kDomains) {
    const std::string ds = t / ("label-studio-" + d);
    test::write_text(ds + "/classes.txt", "rock\n");
    test::write_text(ds + "/notes.json", "{\"categories\": [{\"id\": 0, \"name\": \"rock\"}], \"info\": {}}\n");
    std::vector<std::string> names;
    for (size_t k = 0; k < kStems.size(); ++k) {
      names.push_back(prefixes[k] + kStems[k]);
      test::write_text(ds + "/labels/" + names.back() + ".txt", gt_of(d, k));
      picture(ds + "/images/" + names.back() + ".png");
    }
    sources[d] = ds;
    runs[d] = write_run(t / ("runs/detect/exp-" + d), d, names);
  }
  import_all(t / "study", sources, runs);
  EXPECT_TRUE(fs::exists(t / "study/synth/images/s2.png"));
  const auto j = nlohmann::json::parse(read_file(t / "study/real/import.json"));
  EXPECT_EQ(j["renamed"]["s1"], "labels/1a2b3c4d-s1.txt");
  EXPECT_EQ(table_cells(t / "study"), table_cells(t / "flat"));
}

const std::string kHashA = "0123456789abcdef0123456789abcdef", kHashB = "fedcba9876543210fedcba9876543210";

TEST(YoloImport, ARoboflowYolov5ExportHasItsNamesMappedBackAndItsSplitsMerged) {
  test::TempDir t;
  write_flat_study(t / "flat");
  std::map<std::string, std::string> sources, runs;
  for (const std::string& d : kDomains) {
    const std::string ds = t / ("roboflow-" + d);
    test::write_text(ds + "/data.yaml",
                     "train: ../train/images\nval: ../valid/images\ntest: ../test/images\n\nnc: 1\nnames: ['rock']\n\n"
                     "roboflow:\n  workspace: lab\n  project: rocks\n  version: 3\n  license: CC BY 4.0\n"
                     "  url: https://universe.roboflow.com/lab/rocks/dataset/3\n");
    const std::vector<std::string> splits = {"train", "valid", "test"};
    std::vector<std::string> names;
    for (size_t k = 0; k < kStems.size(); ++k) {
      names.push_back(kStems[k] + "_png.rf." + kHashA);
      test::write_text(ds + "/" + splits[k] + "/labels/" + names.back() + ".txt", gt_of(d, k));
      picture(ds + "/" + splits[k] + "/images/" + names.back() + ".jpg");
    }
    sources[d] = ds;
    runs[d] = write_run(t / ("runs/detect/exp-" + d), d, names);
  }
  import_all(t / "study", sources, runs);
  EXPECT_TRUE(fs::exists(t / "study/real/images/s3.jpg"));
  EXPECT_EQ(table_cells(t / "study"), table_cells(t / "flat"));
}

// Roboflow's folder is valid/, its data.yaml's key val: --split valid and --split val both take that split.
TEST(YoloImport, TheValidationSplitIsChosenByEitherOfItsNames) {
  for (const std::string word : {"valid", "val"}) {
    test::TempDir t;
    const std::string ds = t / "roboflow";
    test::write_text(ds + "/data.yaml", "train: ../train/images\nval: ../valid/images\nnames: ['rock']\n");
    const std::vector<std::string> splits = {"train", "valid", "train"};
    for (size_t k = 0; k < kStems.size(); ++k) {
      const std::string name = kStems[k] + "_png.rf." + kHashA;
      test::write_text(ds + "/" + splits[k] + "/labels/" + name + ".txt", gt_of("real", k));
      picture(ds + "/" + splits[k] + "/images/" + name + ".jpg");
    }
    const auto r = test::run_ipd("import yolo " + ds + "/data.yaml --out " + (t / "study/real") + " --split " + word);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_TRUE(fs::exists(t / ("study/real/labels/" + kStems[1] + ".txt"))) << word;
    EXPECT_FALSE(fs::exists(t / ("study/real/labels/" + kStems[0] + ".txt"))) << word;
  }
}

TEST(YoloImport, ManglingRulesGiveBackTheNameAndNothingElse) {
  EXPECT_EQ(scene_stem("0001_jpg.rf." + kHashA, false), "0001");
  EXPECT_EQ(scene_stem("a_b_jpeg.rf." + kHashA, false), "a_b");
  EXPECT_EQ(scene_stem("0001_txt.rf." + kHashA, false), "0001_txt.rf." + kHashA);  // not a picture extension
  EXPECT_EQ(scene_stem("0001_jpg.rf." + kHashA.substr(1), false), "0001_jpg.rf." + kHashA.substr(1));  // 31 digits
  EXPECT_EQ(scene_stem("1a2b3c4d-0001", true), "0001");
  EXPECT_EQ(scene_stem("1a2b3c4d-0001", false), "1a2b3c4d-0001");
  EXPECT_EQ(scene_stem("1A2B3C4D-0001", true), "1A2B3C4D-0001");  // Label Studio's ids are lower case
  EXPECT_FALSE(has_upload_prefix("1a2b3c4d-"));
}

// A name that merely starts like an upload id keeps it unless every name of the export has one: the prefix is
// Label Studio's only when it marks every upload.
TEST(YoloImport, AnUploadPrefixIsLeftOutOnlyWhenEveryNameHasOne) {
  test::TempDir t;
  test::write_text(t / "ls/classes.txt", "rock\n");
  test::write_text(t / "ls/labels/deadbeef-s1.txt", "0 0.5 0.5 0.1 0.1\n");
  test::write_text(t / "ls/labels/s2.txt", "0 0.5 0.5 0.1 0.1\n");
  const auto r = test::run_ipd("import yolo " + t / "ls" + " --out " + t / "study/real");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(fs::exists(t / "study/real/labels/deadbeef-s1.txt"));
  EXPECT_TRUE(fs::exists(t / "study/real/labels/s2.txt"));
}

// A second model's COCO results join a domain imported from COCO without touching (or re-importing) its GT.
TEST(PredictionImport, ASecondModelsCocoResultsJoinTheDomainAndLeaveItsGroundTruth) {
  test::TempDir t;
  test::write_text(t / "gt.json",
                   "{\"images\": [{\"id\": 7, \"file_name\": \"s1.png\", \"width\": 100, \"height\": 100},"
                   " {\"id\": 8, \"file_name\": \"s2.png\", \"width\": 100, \"height\": 100}],"
                   " \"categories\": [{\"id\": 0, \"name\": \"rock\"}],"
                   " \"annotations\": [{\"image_id\": 7, \"category_id\": 0, \"bbox\": [40, 40, 20, 20]}]}");
  test::write_text(t / "a.json", "[{\"image_id\": 7, \"category_id\": 0, \"bbox\": [40, 40, 20, 20], \"score\": 0.9}]");
  test::write_text(t / "b.json", "[{\"image_id\": 7, \"category_id\": 0, \"bbox\": [42, 40, 20, 20], \"score\": 0.8}]");
  auto r = test::run_ipd("import coco " + t / "gt.json" + " --images " + t.path() + " --out " + t / "study/real" +
                         " --results " + t / "a.json" + " --model a");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string gt_before = read_file(t / "study/real/labels/s1.txt");
  r = test::run_ipd("import predictions " + t / "b.json" + " --gt " + t / "gt.json" + " --out " + t / "study/real" +
                    " --model b");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.out, "COCO results " + t / "b.json" +
                       ": 2 files, 1 detections; 0 scenes without a file written empty (no detections) -> " +
                       t / "study/real" + "/predictions/b\n");
  EXPECT_EQ(read_file(t / "study/real/predictions/b/s1.txt"), "0 0.52 0.5 0.2 0.2 0.8\n");
  EXPECT_EQ(read_file(t / "study/real/predictions/b/s2.txt"), "");
  EXPECT_EQ(read_file(t / "study/real/labels/s1.txt"), gt_before);
  EXPECT_EQ(read_file(t / "study/real/predictions/a/s1.txt"), "0 0.5 0.5 0.2 0.2 0.9\n");
  r = test::run_ipd("import predictions " + t / "b.json" + " --out " + t / "study/real" + " --model c");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("give --gt with the COCO annotations file"), std::string::npos) << r.err;
}

TEST(PredictionImport, ARunWithoutConfidencesIsRefusedWithTheCommandsThatWriteThem) {
  test::TempDir t;
  test::write_text(t / "study/real/labels/s1.txt", "0 0.5 0.5 0.1 0.1\n");
  test::write_text(t / "study/real/labels/s2.txt", "0 0.2 0.2 0.1 0.1\n");
  test::write_text(t / "runs/detect/predict/labels/s1.txt", "0 0.5 0.5 0.1 0.1\n0 0.7 0.7 0.1 0.1\n");
  auto r =
      test::run_ipd("import predictions " + t / "runs/detect/predict" + " --out " + t / "study/real" + " --model yolo");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_EQ(r.err, "error: " + t / "runs/detect/predict/labels" +
                       ": the run wrote no confidences (5 columns: class cx cy w h); IPD and AP rank detections by "
                       "them. Run the detector again with them: yolov5 `python detect.py --save-txt --save-conf ...` "
                       "or Ultralytics `yolo predict save_txt=True save_conf=True ...`; or give --no-conf to read "
                       "every box with confidence 1 (import.json then says so)\n");
  EXPECT_FALSE(fs::exists(t / "study/real/predictions"));
  r = test::run_ipd("import predictions " + t / "runs/detect/predict" + " --out " + t / "study/real" +
                    " --model yolo --no-conf");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(read_file(t / "study/real/predictions/yolo/s1.txt"), "0 0.5 0.5 0.1 0.1 1\n0 0.7 0.7 0.1 0.1 1\n");
  EXPECT_EQ(read_file(t / "study/real/predictions/yolo/s2.txt"), "");  // no file from the run: no detections
  const auto j = nlohmann::json::parse(read_file(t / "study/real/predictions/yolo/import.json"));
  EXPECT_EQ(j["confidence"], "none in the run's files: every box read with confidence 1 (--no-conf)");
  EXPECT_EQ(j["no_detections"], nlohmann::json::array({"s2"}));
}

// A run that found nothing anywhere has only empty files: that is no detections, not a run without confidences.
TEST(PredictionImport, ARunOfEmptyFilesIsNoDetectionsNotARunWithoutConfidences) {
  test::TempDir t;
  test::write_text(t / "study/real/labels/s1.txt", "0 0.5 0.5 0.1 0.1\n");
  test::write_text(t / "run/labels/s1.txt", "");
  const auto r = test::run_ipd("import predictions " + t / "run" + " --out " + t / "study/real" + " --model m");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(read_file(t / "study/real/predictions/m/s1.txt"), "");
}

TEST(PredictionImport, AFolderOfRunsIsRefusedNamingTheRunsInIt) {
  test::TempDir t;
  test::write_text(t / "study/real/labels/s1.txt", "0 0.5 0.5 0.1 0.1\n");
  test::write_text(t / "runs/detect/exp/labels/s1.txt", "0 0.5 0.5 0.1 0.1 0.9\n");
  test::write_text(t / "runs/detect/exp2/labels/s1.txt", "0 0.5 0.5 0.1 0.1 0.8\n");
  const auto r = test::run_ipd("import predictions " + t / "runs/detect" + " --out " + t / "study/real" + " --model m");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_EQ(r.err, "error: " + t / "runs/detect" +
                       ": holds the run folders exp/, exp2/, not a run's files; name the "
                       "run, e.g. " +
                       t / "runs/detect/exp" + "\n");
  EXPECT_FALSE(fs::exists(t / "study/real/predictions"));
}

// Nothing is written, and nothing is left beside --out, when the source is refused.
void expect_nothing_written(const test::TempDir& t) {
  EXPECT_FALSE(fs::exists(t / "study/real"));
  if (fs::exists(t / "study"))
    for (const auto& e : fs::directory_iterator(t / "study")) ADD_FAILURE() << "left behind: " << e.path();
}

std::string import_error(const test::TempDir& t, const std::string& src) {
  const auto r = test::run_ipd("import yolo " + src + " --out " + t / "study/real");
  EXPECT_EQ(r.exit_code, 1);
  expect_nothing_written(t);
  return r.err;
}

TEST(YoloImportBadInput, ATruncatedDataYamlIsRefusedWithItsLine) {
  test::TempDir t;
  test::write_text(t / "ds/labels/train/s1.txt", "0 0.5 0.5 0.1 0.1\n");
  test::write_text(t / "ds/data.yaml", "train: images/train\nnames: [rock, sh");
  EXPECT_EQ(import_error(t, t / "ds/data.yaml"),
            "error: " + t / "ds/data.yaml" +
                ":2: not YAML: end of sequence flow not found; expected a dataset's data.yaml (path, train, val, "
                "names)\n");
  test::write_text(t / "ds/data.yaml", "train: images/train\nval: images/tr");
  EXPECT_EQ(import_error(t, t / "ds/data.yaml"),
            "error: " + t / "ds/data.yaml" +
                ": no names; expected the class names (names: [rock, shadow] or names: {0: rock}); a data.yaml cut "
                "short ends before them\n");
}

TEST(YoloImportBadInput, ASplitFolderThatIsNotThereIsRefusedWithItsLine) {
  test::TempDir t;
  test::write_text(t / "ds/labels/train/s1.txt", "0 0.5 0.5 0.1 0.1\n");
  picture(t / "ds/images/train/s1.png");
  test::write_text(t / "ds/data.yaml", "path: .\ntrain: images/train\nval: images/val\nnames: [rock]\n");
  EXPECT_EQ(import_error(t, t / "ds/data.yaml"), "error: " + t / "ds/data.yaml" + ":3: val: " + t / "ds/images/val" +
                                                     " is not there; expected the split's folder of pictures\n");
}

// A label moved into a sub-folder of its split no longer pairs with its picture: said by name, nothing written.
TEST(YoloImportBadInput, ALabelFileWithoutItsPictureIsRefusedNamingWhereThePictureWouldBe) {
  test::TempDir t;
  picture(t / "ds/images/train/s1.png");
  picture(t / "ds/images/train/s2.png");
  test::write_text(t / "ds/labels/train/s1.txt", "0 0.5 0.5 0.1 0.1\n");
  test::write_text(t / "ds/labels/train/extra/s2.txt", "0 0.5 0.5 0.1 0.1\n");
  test::write_text(t / "ds/data.yaml", "path: .\ntrain: images/train\nnames: [rock]\n");
  EXPECT_EQ(import_error(t, t / "ds/data.yaml"),
            "error: " + t / "ds/labels/train/extra/s2.txt" + ": no picture for this label file at " +
                t / "ds/images/train/extra/s2" + ".* (labels and pictures pair by their path below " +
                t / "ds/labels/train" + " and " + t / "ds/images/train" +
                "); move it beside its picture's path, or remove it\n");
}

TEST(YoloImportBadInput, TwoFilesThatBecomeOneSceneAreRefusedNamingBoth) {
  test::TempDir t;
  test::write_text(t / "rf/data.yaml", "train: ../train/images\nnames: ['rock']\n");
  test::write_text(t / "rf/train/labels/s1_jpg.rf." + kHashA + ".txt", "0 0.5 0.5 0.1 0.1\n");
  test::write_text(t / "rf/train/labels/s1_jpg.rf." + kHashB + ".txt", "0 0.4 0.5 0.1 0.1\n");
  fs::create_directories(t / "rf/train/images");
  EXPECT_EQ(import_error(t, t / "rf"), "error: " + t / ("rf/train/labels/s1_jpg.rf." + kHashA + ".txt") + " and " +
                                           t / ("rf/train/labels/s1_jpg.rf." + kHashB + ".txt") +
                                           " would both be scene 's1' of the study; rename one (or import one split "
                                           "with --split)\n");
}

TEST(YoloImportBadInput, ALinkInTheSourceIsRefusedNotFollowed) {
  test::TempDir t;
  test::write_text(t / "outside.txt", "0 0.5 0.5 0.1 0.1\n");
  test::write_text(t / "ls/classes.txt", "rock\n");
  test::write_text(t / "ls/labels/s1.txt", "0 0.5 0.5 0.1 0.1\n");
  fs::create_symlink(t / "outside.txt", t / "ls/labels/s2.txt");
  EXPECT_EQ(import_error(t, t / "ls"), "error: " + t / "ls/labels/s2.txt" +
                                           ": is a symbolic link; links in an import's source are never followed "
                                           "(one could lead out of it), so nothing is imported; copy the file it "
                                           "points to in its place\n");
}

TEST(YoloImportBadInput, AMalformedLineOrAnUnnamedClassIsRefusedWithItsLine) {
  test::TempDir t;
  test::write_text(t / "ls/classes.txt", "rock\n");
  test::write_text(t / "ls/labels/s1.txt", "0 0.5 0.5 0.1 0.1\n1 0.2 0.2 0.1 0.1\n");
  test::write_text(t / "ls/labels/s2.txt", "0 0.5 0.5 0.1\n");
  const std::string err = import_error(t, t / "ls");
  EXPECT_EQ(
      err,
      t / "ls/labels/s1.txt" + ":2: class 1 is not among the classes " + t / "ls/classes.txt" +
          " names (1 of them); expected a named class number\n" + t / "ls/labels/s2.txt" +
          ":1: expected 5 columns (class cx cy w h), found 4\n"
          "error: 2 problems in the source's label files; nothing written (--skip-bad-lines writes malformed lines as "
          "comments)\n");
}

TEST(YoloImportBadInput, AClassNameTheStudyGivesAnotherNumberIsRefusedNamingBothFiles) {
  test::TempDir t;
  test::write_text(t / "study/synth/labels/classes.txt", "shadow\nrock\n");
  test::write_text(t / "study/synth/labels/s1.txt", "1 0.5 0.5 0.1 0.1\n");
  test::write_text(t / "ls/classes.txt", "rock\n");
  test::write_text(t / "ls/labels/s1.txt", "0 0.5 0.5 0.1 0.1\n");
  const auto r = test::run_ipd("import yolo " + t / "ls" + " --out " + t / "study/real");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_EQ(r.err, "error: " + t / "ls/classes.txt" + ": class 0 is \"rock\" here but \"shadow\" in " +
                       t / "study/synth/labels/classes.txt" +
                       "; a class number must be the same class in every domain of a study (rock_class picks one "
                       "number for all), so nothing is written\n");
  EXPECT_FALSE(fs::exists(t / "study/real"));
}

TEST(YoloImportBadInput, AClassNameStudyYamlDoesNotListIsRefusedNamingBothFiles) {
  test::TempDir t;
  test::write_text(t / "study/study.yaml", "classes: [rock, shadow]\n");
  test::write_text(t / "ls/classes.txt", "rock\nboulder\n");
  test::write_text(t / "ls/labels/s1.txt", "1 0.5 0.5 0.1 0.1\n");
  const auto r = test::run_ipd("import yolo " + t / "ls" + " --out " + t / "study/real");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_EQ(r.err, "error: " + t / "ls/classes.txt" + ": class 1 \"boulder\" is not among the study's classes in " +
                       t / "study/study.yaml" +
                       "; a class must have one name in every label set (rename it, or add it to study.yaml's "
                       "classes), so nothing is written\n");
  EXPECT_FALSE(fs::exists(t / "study/real"));
}

}  // namespace
}  // namespace ipd
