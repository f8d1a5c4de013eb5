// `ipd --version` names the build a number came from: CMake's project VERSION, the .deb's version, the
// version caches key on.
#include <gtest/gtest.h>

#include <regex>
#include <string>

#include "core/util/version.h"
#include "tests/support/test_support.h"

namespace {

TEST(Version, IsTheProjectVersionAsMajorMinorPatch) {
  EXPECT_STREQ(ipd::version(), IPD_PROJECT_VERSION);
  EXPECT_TRUE(std::regex_match(std::string(ipd::version()), std::regex("[0-9]+\\.[0-9]+\\.[0-9]+"))) << ipd::version();
}

TEST(Cli, VersionPrintsIpdAndTheProjectVersion) {
  const auto r = ipd::test::run_ipd("--version");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.out, std::string("ipd ") + IPD_PROJECT_VERSION + "\n");
  EXPECT_EQ(r.err, "");
}

}  // namespace
