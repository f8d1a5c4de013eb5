// Names that become file names (study_names.h) are checked when a study is opened: study.yaml can't declare
// a model `../../x` (it would become the default model and part of export file names), and a domain, model
// or scene whose name can't be a file name part is refused naming where it came from.
#include <gtest/gtest.h>

#include <fmt/format.h>
#include <filesystem>

#include "core/study/fixed_pairs.h"
#include "core/study/study.h"
#include "core/study/study_names.h"
#include "tests/support/test_support.h"

namespace fs = std::filesystem;

namespace ipd {
namespace {

void minimal_study(const test::TempDir& d) {
  test::write_text(d / "real/labels/s0.txt", "0 0.5 0.5 0.1 0.1\n");
  test::write_text(d / "synth/labels/s0.txt", "0 0.5 0.5 0.1 0.1\n");
}

TEST(StudyNames, WhatCanBePartOfAFileName) {
  EXPECT_EQ(file_name_problem("det-real_v2.1", 120), "");
  EXPECT_EQ(file_name_problem("..x", 120), "");
  EXPECT_EQ(file_name_problem("", 120), "is empty");
  EXPECT_EQ(file_name_problem("..", 120), "is '..', which names a folder, not a file");
  EXPECT_EQ(file_name_problem("../../x", 120), "contains a path separator '/'");
  EXPECT_EQ(file_name_problem("a\\b", 120), "contains a path separator '\\'");
  EXPECT_EQ(file_name_problem(std::string("a\0b", 3), 120), "contains a control character (byte 0x00)");
  EXPECT_EQ(file_name_problem("a\nb", 120), "contains a control character (byte 0x0a)");
  EXPECT_EQ(file_name_problem(std::string(121, 'm'), 120),
            "is 121 bytes long; at most 120 fit in the file names it becomes part of");
  EXPECT_EQ(file_name_problem(std::string(120, 'm'), 120), "");
  EXPECT_EQ(printable_name("a\nb\x7f"), "a\\x0ab\\x7f");
}

TEST(StudyNames, StudyYamlModelThatIsAPathIsRefusedWithFileAndLine) {
  test::TempDir d;
  minimal_study(d);
  test::write_text(d / "study.yaml",
                   "rock_class: 0\nmodels:\n  det: {trained_on: real}\n  ../../x: {trained_on: real}\n");
  EXPECT_EQ(test::open_study_error(d.path()),
            d / "study.yaml" + ":4: model name '../../x' contains a path separator '/'");
  test::write_text(d / "study.yaml", "models:\n  \"..\": {}\n");
  EXPECT_EQ(test::open_study_error(d.path()),
            d / "study.yaml" + ":2: model name '..' is '..', which names a folder, not a file");
  test::write_text(d / "study.yaml", "models:\n  \"a\\x07b\": {}\n");
  EXPECT_EQ(test::open_study_error(d.path()),
            d / "study.yaml" + ":2: model name 'a\\x07b' contains a control character (byte 0x07)");
}

TEST(StudyNames, DomainModelAndSceneNamesFromFoldersAreChecked) {
  test::TempDir d;
  minimal_study(d);
  // Two 200-character domains would make pairs/<A>__<B>/ longer than a file name can be.
  const std::string long_domain(200, 'd');
  test::write_text(d / long_domain + "/labels/s0.txt", "0 0.5 0.5 0.1 0.1\n");
  EXPECT_EQ(test::open_study_error(d.path()),
            d / long_domain + ": domain name '" + long_domain.substr(0, 60) + "..." +
                "' is 200 bytes long; at most 120 fit in the file names it becomes part of");
  fs::remove_all(d / long_domain);

  fs::create_directories(d / "real/predictions/det\nx");
  EXPECT_EQ(test::open_study_error(d.path()),
            d / "real/predictions/det\\x0ax" + ": model name 'det\\x0ax' contains a control character (byte 0x0a)");
  fs::remove_all(d / "real/predictions");

  const std::string long_stem(251, 's');  // "<stem>.txt" fits, "<stem>.json" (its pairs file) would not
  test::write_text(d / "synth/labels/" + long_stem + ".txt", "0 0.5 0.5 0.1 0.1\n");
  EXPECT_EQ(test::open_study_error(d.path()),
            d / "synth/labels/" + long_stem + ".txt: scene name '" + long_stem.substr(0, 60) + "..." +
                "' is 251 bytes long; at most 250 fit in the file names it becomes part of");
  fs::remove(d / "synth/labels/" + long_stem + ".txt");
  EXPECT_EQ(test::open_study_error(d.path()), "no error");
}

TEST(StudyNames, PairsFilesLargerThanTheCapAreRefusedUnread) {
  test::TempDir d;
  minimal_study(d);
  test::write_text(d / "pairs/real__synth/s0.json", std::string(kMaxPairsFileBytes + 1, ' '));
  const Study study = open_study(d.path());
  try {
    read_fixed_pairs(study, "real", "synth", "s0", {test::box(0.5, 0.5, 0.1, 0.1)}, {test::box(0.5, 0.5, 0.1, 0.1)});
    FAIL() << "read";
  } catch (const StudyError& e) {
    EXPECT_EQ(std::string(e.what()),
              d / "pairs/real__synth/s0.json" + ": is 8.1 MB, larger than the 8 MB limit for this kind of file");
  }
}

}  // namespace
}  // namespace ipd
