// study.yaml's `domains:` as a mapping that attaches numbers to a domain (a renderer setting's parameters), in
// the file's order; the list form stays valid; a value that is not a number is refused where it is written.
#include <gtest/gtest.h>

#include "core/study/study.h"
#include "tests/support/test_support.h"

namespace ipd {
namespace {

TEST(DomainParams, MappingKeepsTheFilesOrderAndEachDomainsNumbers) {
  const StudyConfig c = parse_study_config(
      "domains:\n  real: {}\n  hapke-w030: {params: {w: 0.30, b: 0.2}}\n  hapke-w050:\n    params: {w: 5e-1, b: -2}\n"
      "  principled:\n",
      "study.yaml");
  EXPECT_EQ(c.domain_order, (std::vector<std::string>{"real", "hapke-w030", "hapke-w050", "principled"}));
  ASSERT_EQ(c.domain_params.size(), 2u);
  using Params = std::vector<std::pair<std::string, double>>;
  EXPECT_EQ(c.domain_params.at("hapke-w030"), (Params{{"w", 0.30}, {"b", 0.2}}));
  EXPECT_EQ(c.domain_params.at("hapke-w050"), (Params{{"w", 0.5}, {"b", -2.0}}));
}

TEST(DomainParams, ListFormStaysValid) {
  const StudyConfig c = parse_study_config("domains: [real, principled, hapke]\n", "study.yaml");
  EXPECT_EQ(c.domain_order, (std::vector<std::string>{"real", "principled", "hapke"}));
  EXPECT_TRUE(c.domain_params.empty());
}

TEST(DomainParams, BadValuesAreRefusedNamingFileAndLine) {
  EXPECT_EQ(test::study_yaml_error("domains:\n  real: {}\n  hapke:\n    params: {w: abc}\n"),
            "study.yaml:4: domains.hapke.params.w must be a number, got 'abc'");
  EXPECT_EQ(test::study_yaml_error("domains:\n  real: {}\n  hapke: {params: {w: .inf}}\n"),
            "study.yaml:3: domains.hapke.params.w must be a number, got '.inf'");
  EXPECT_EQ(test::study_yaml_error("domains:\n  hapke: {params: {w: 1e999}}\n"),
            "study.yaml:2: domains.hapke.params.w must be a number, got '1e999'");
  EXPECT_EQ(test::study_yaml_error("domains:\n  hapke: {params: {w: [1, 2]}}\n"),
            "study.yaml:2: domains.hapke.params.w must be a number, got a list");
  EXPECT_EQ(test::study_yaml_error("domains:\n  hapke: {params: 0.3}\n"),
            "study.yaml:2: domains.hapke.params must be a mapping of parameter names to numbers (e.g. {w: 0.30, b: "
            "0.2}), got '0.3'");
  EXPECT_EQ(test::study_yaml_error("domains:\n  hapke: {parms: {w: 0.3}}\n"),
            "study.yaml:2: unknown setting 'domains.hapke.parms' (expected params)");
  EXPECT_EQ(test::study_yaml_error("domains: {real: {}, real: {}}\n"),
            "study.yaml:1: domains lists 'real' twice; each domain once, in the order to show");
}

}  // namespace
}  // namespace ipd
