// The Open dialog's path field (app/studio/study_folder.h): what it opens and what it says about the rest.
#include "app/studio/study_folder.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>

#include "tests/support/test_support.h"

namespace ipd::studio {
namespace {

TEST(StudyFolder, APathThatIsNoStudySaysWhy) {
  test::TempDir d;
  test::write_text(d / "notes.txt", "x");
  test::write_text(d / "yaml/study.yaml", "domains: []\n");
  test::write_text(d / "layout/real/labels/s1.txt", "");
  std::filesystem::create_directories(d / "empty/real");
  EXPECT_EQ(open_path_problem(d / "yaml"), "");
  EXPECT_EQ(open_path_problem(d / "layout"), "");
  EXPECT_EQ(open_path_problem(d / "missing"), d / "missing" + ": no such folder");
  EXPECT_EQ(open_path_problem(d / "notes.txt"), d / "notes.txt" + ": is a file, not a folder");
  EXPECT_EQ(open_path_problem(d / "empty"), d / "empty" + ": not a study (no study.yaml or <domain>/labels/ in it)");
  EXPECT_EQ(open_path_problem(""), "type or paste the path of a study folder");
}

TEST(StudyFolder, APastedPathLosesItsQuotesAndSpacesAndTildeIsHome) {
  const char* home = std::getenv("HOME");
  ASSERT_TRUE(home && *home);
  EXPECT_EQ(expand_typed_path("  '/data/my study'  "), "/data/my study");
  EXPECT_EQ(expand_typed_path("\"/data/x\"\n"), "/data/x");
  EXPECT_EQ(expand_typed_path("~/studies/a"), std::string(home) + "/studies/a");
  EXPECT_EQ(expand_typed_path("~"), std::string(home));
  EXPECT_EQ(expand_typed_path("a~/b"), "a~/b");  // only a leading tilde
  EXPECT_EQ(expand_typed_path("   "), "");
}

}  // namespace
}  // namespace ipd::studio
