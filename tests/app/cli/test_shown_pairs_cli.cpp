// Each command registers the domain pairs its output reads and no other: on the 3-domain demo a comparison
// needs (ref, a) and (ref, b), a breakdown of one model the pairs with its training domain, a gallery one pair.
// Counted as the registrations the parsed-study cache keeps after the command, from an empty cache.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "core/ipd/study_cache.h"
#include "tests/support/test_support.h"

namespace fs = std::filesystem;

namespace ipd {
namespace {

constexpr int kScenes = 4;

std::string file_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// Registrations kept after `ipd ARGS` ran on the study in `d` with no cache before it.
int registrations_after(const test::TempDir& d, const std::string& args) {
  fs::remove_all(d / ".ipd-cache");
  const auto r = test::run_ipd(args);
  EXPECT_EQ(r.exit_code, 0) << args << "\n" << r.err;
  const StudyCache cache(parsed_study_cache_path(d.path()), d.path());
  EXPECT_EQ(cache.stats().state, "loaded") << args;
  return cache.stats().registrations_stored;
}

TEST(ShownPairsCli, EachCommandRegistersOnlyTheDomainPairsItReads) {
  test::TempDir d, out;
  ASSERT_EQ(test::run_ipd("demo " + d.path() + " --labels-only --scenes " + std::to_string(kScenes)).exit_code, 0);
  const std::string s = " " + d.path();
  const std::string svg = " --out " + (out / "figure.svg");
  // Every domain pair: 3.
  EXPECT_EQ(registrations_after(d, "export rocks" + s), 3 * kScenes);
  EXPECT_EQ(registrations_after(d, "breakdown" + s + " --model det-real --all-cells"), 3 * kScenes);
  // (real, principled) and (real, hapke): never (principled, hapke).
  EXPECT_EQ(registrations_after(d, "compare" + s + " --ref real --a principled --b hapke"), 2 * kScenes);
  EXPECT_EQ(registrations_after(d, "breakdown" + s + " --model det-real"), 2 * kScenes);
  EXPECT_EQ(registrations_after(d, "table" + s + " --model det-real"), 2 * kScenes);
  EXPECT_EQ(registrations_after(d, "figure table" + s + " --model det-real" + svg), 2 * kScenes);
  EXPECT_EQ(registrations_after(d, "figure compare" + s + " --ref real --a principled --b hapke" + svg), 2 * kScenes);
  // One pair.
  EXPECT_EQ(registrations_after(d, "figure breakdown" + s + " --a principled --b hapke" + svg), kScenes);
  EXPECT_EQ(registrations_after(d, "figure gallery" + s + " --domains hapke,real" + svg), kScenes);
}

}  // namespace
}  // namespace ipd

namespace ipd {
namespace {
// A gallery of (hapke, real) is the gallery of (real, hapke): the same pictures left and right, scored with the
// model trained on the left one (det-real), whichever order --domains names them in.
TEST(ShownPairsCli, AGallerysDomainOrderChangesNeitherItsLayoutNorItsModel) {
  test::TempDir d, out;
  ASSERT_EQ(test::run_ipd("demo " + d.path() + " --labels-only --scenes 3").exit_code, 0);
  const auto a = test::run_ipd("figure gallery " + d.path() + " --domains real,hapke --out " + (out / "a.svg"));
  const auto b = test::run_ipd("figure gallery " + d.path() + " --domains hapke,real --out " + (out / "b.svg"));
  ASSERT_EQ(a.exit_code, 0) << a.err;
  ASSERT_EQ(b.exit_code, 0) << b.err;
  const std::string svg = file_text(out / "a.svg");
  EXPECT_NE(svg.find("det-real"), std::string::npos);
  EXPECT_EQ(svg, file_text(out / "b.svg"));
}
}  // namespace
}  // namespace ipd
