// Output files a user names (figures, tables, exports): below a study they are never written through a link
// the study holds, since the study may come from someone else; elsewhere they are the user's own paths.
#include <gtest/gtest.h>

#include <filesystem>

#include "core/util/atomic_file.h"
#include "core/util/contained_file.h"
#include "tests/support/test_support.h"

namespace fs = std::filesystem;

namespace ipd {
namespace {

std::string error_of_output_files(const std::function<void()>& f) {
  try {
    f();
  } catch (const IoError& e) {
    return e.what();
  }
  return "";
}

TEST(OutputFiles, BelowAStudyALinkedFolderOrFileIsRefusedAndNothingOutsideChanges) {
  test::TempDir d;
  const std::string study = d / "study", outside = d / "outside";
  fs::create_directories(study);
  fs::create_directories(outside);
  test::write_text(outside + "/victim.svg", "precious");
  // The studio's default export folder, planted as a link out of the study.
  fs::create_directory_symlink(outside, study + "/figures");
  EXPECT_EQ(error_of_output_files([&] { write_output_file(study, study + "/figures/scene_01.svg", "figure"); }),
            fs::canonical(study).string() +
                "/figures: is a symbolic link; saving through it is refused (links inside a study are never followed)");
  EXPECT_FALSE(fs::exists(outside + "/scene_01.svg"));
  // The file itself a link, in a real folder.
  fs::remove(study + "/figures");
  fs::create_directories(study + "/figures");
  fs::create_symlink(outside + "/victim.svg", study + "/figures/victim.svg");
  EXPECT_NE(error_of_output_files([&] { write_output_file(study, study + "/figures/victim.svg", "figure"); }), "");
  EXPECT_EQ(read_file(outside + "/victim.svg"), "precious");
  // A path that only passes through ".." inside the study is still below it.
  EXPECT_NE(
      error_of_output_files([&] { write_output_file(study, study + "/figures/../figures/victim.svg", "figure"); }), "");
  EXPECT_EQ(read_file(outside + "/victim.svg"), "precious");
  // A plain file below the study is written.
  write_output_file(study, study + "/figures/new.svg", "figure");
  EXPECT_EQ(read_file(study + "/figures/new.svg"), "figure");
}

// A scene name of 250 bytes (the longest a study takes) makes a pairs file name of 255, the file system's
// limit: its temp name (name.tmp-PID-N) is cut so the save still works (it failed: "File name too long").
TEST(OutputFiles, TheLongestNameAStudyTakesIsStillSaved) {
  test::TempDir d;
  const std::string name = std::string(250, 's') + ".json";
  write_file_beneath(d.path(), "pairs/real__synth/" + name, "{}\n");
  EXPECT_EQ(read_file(d / ("pairs/real__synth/" + name)), "{}\n");
  write_file_atomically(d / name, "{}\n");
  EXPECT_EQ(read_file(d / name), "{}\n");
  EXPECT_EQ(temp_name_for(name).rfind(std::string(200, 's') + ".tmp-", 0), 0u);
  EXPECT_EQ(std::distance(fs::directory_iterator(d.path()), fs::directory_iterator()), 2);  // no temp left
}

TEST(OutputFiles, ElsewhereTheUsersPathIsWrittenAsGiven) {
  test::TempDir d;
  fs::create_directories(d / "study");
  fs::create_directories(d / "mine");
  // The user's own link, outside the study: followed, as any --out is.
  fs::create_symlink(d / "mine/real.txt", d / "mine/link.txt");
  write_output_file(d / "study", d / "mine/link.txt", "table");
  EXPECT_EQ(read_file(d / "mine/real.txt"), "table");
  // A sibling whose name starts like the study's is not below it.
  EXPECT_EQ(path_below(d / "study", d / "study2/x.txt"), std::nullopt);
  EXPECT_EQ(path_below(d / "study", d / "study"), std::nullopt);
  EXPECT_EQ(path_below(d / "study", d / "study/figures/x.pdf"), std::optional<std::string>("figures/x.pdf"));
}

}  // namespace
}  // namespace ipd
