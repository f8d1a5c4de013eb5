// `ipd bench study`: one row per kind of run (no cache, first run writing the caches, warm run reading them)
// with every stage's time and the run's peak memory, without touching the study's own caches.
#include <gtest/gtest.h>

#include <filesystem>
#include <regex>
#include <string>

#include "tests/support/test_support.h"

namespace {

TEST(BenchStudy, PrintsEveryStageOfEachKindOfRunAndLeavesTheStudysCachesAlone) {
  ipd::test::TempDir d;
  ASSERT_EQ(ipd::test::run_ipd("demo " + d / "s" + " --labels-only --scenes 3 --rocks 8").exit_code, 0);
  const auto r = ipd::test::run_ipd("bench study " + d / "s" + " --runs 1 --bootstrap 10 --threads 1");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(
      std::regex_search(r.out, std::regex("\nrun +parse +register +IPD +cache-write +bootstrap +total +peak MiB\n")))
      << r.out;
  const std::string number = " +[0-9]+\\.[0-9]";
  for (const std::string kind : {"no-cache", "first", "warm"})
    EXPECT_TRUE(std::regex_search(r.out, std::regex("\n" + kind + "(" + number + "){6} +[0-9]+\n"))) << kind << r.out;
  EXPECT_TRUE(std::regex_search(r.out, std::regex("first / no-cache: [0-9.]+x; warm / no-cache: [0-9.]+x"))) << r.out;
  EXPECT_FALSE(std::filesystem::exists(d / "s" + "/.ipd-cache"));
}

TEST(BenchStudy, AMissingStudyIsAnErrorNamingIt) {
  ipd::test::TempDir d;
  const auto r = ipd::test::run_ipd("bench study " + d / "none");
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.err.find(d / "none"), std::string::npos) << r.err;
}

}  // namespace
