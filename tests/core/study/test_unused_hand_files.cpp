// Hand-made files nothing reads (a renamed domain's pairs folder or review file, a pairs file of a scene that is
// gone) are said, so hand pairs and review marks never vanish from the numbers without a word.
#include "core/study/unused_hand_files.h"

#include <gtest/gtest.h>

#include "tests/support/test_support.h"

namespace ipd {
namespace {

std::vector<std::string> texts(const std::vector<Problem>& problems) {
  std::vector<std::string> out;
  for (const auto& p : problems) out.push_back(p.to_string());
  return out;
}

TEST(UnusedHandFiles, RenamedDomainsAndGoneScenesAreSaid) {
  test::TempDir d;
  test::write_review_study(d);                                             // domains real and synth, scenes s1 and s2
  test::write_text(d / "pairs/real__synth/s1.json", "{\"pairs\": []}\n");  // used
  test::write_text(d / "pairs/real__synth/s9.json", "{\"pairs\": []}\n");  // no scene s9
  test::write_text(d / "pairs/real__synth-v1/s1.json", "{\"pairs\": []}\n");  // synth was synth-v1
  test::write_text(d / "pairs/notes/x.json", "{}\n");
  test::write_text(d / "review/real__synth.json", "{\"reviewed\": [], \"checked\": []}\n");
  test::write_text(d / "review/real__synth-v1.json", "{\"reviewed\": [], \"checked\": []}\n");
  EXPECT_EQ(
      texts(unused_hand_files(open_study(d.path()))),
      (std::vector<std::string>{
          d / "pairs/notes" + ": is not named <A>__<B> after two domains: its hand pairs are not used",
          d / "pairs/real__synth/s9.json" + ": no scene 's9' in both 'real' and 'synth': its hand pairs are not used",
          d / "pairs/real__synth-v1" +
              ": names no domain pair of this study (domains: real, synth): its hand pairs are not used",
          d / "review/real__synth-v1.json" +
              ": names no domain pair of this study (domains: real, synth): its review marks are not used"}));
}

TEST(UnusedHandFiles, AStudyWhoseFilesAreAllReadHasNone) {
  test::TempDir d;
  test::write_review_study(d);
  test::write_text(d / "pairs/synth__real/s2.json", "{\"pairs\": []}\n");  // the other name order is read too
  EXPECT_TRUE(unused_hand_files(open_study(d.path())).empty());
}

}  // namespace
}  // namespace ipd
