// Which cells of the cross table are shown: the paper dashes a cell whose pair of domains leaves out the
// model's training domain; a model without one has every cell shown.
#include <gtest/gtest.h>

#include "core/ipd/ipd.h"
#include "core/report/table_format.h"
#include "tests/support/test_support.h"

namespace ipd {
namespace {

// Two rocks a side, listed in opposite orders; det finds real's rocks with IoU 1 and 1/3, synth's with 1/3
// and 0: IPD (|1 - 1/3| + |1/3 - 0|) / 2 = 0.5 (as Ipd.TinyStudyWorkedByHand). "other" is synth's layout with
// its rock at (0.2, 0.2) found exactly: against real (|1 - 1| + |1/3 - 0|) / 2 = 1/6.
void write_study_table_rules(const test::TempDir& d, const std::string& yaml) {
  test::write_text(d / "real/labels/s1.txt", "0 0.2 0.2 0.1 0.1\n0 0.6 0.6 0.1 0.1\n");
  test::write_text(d / "synth/labels/s1.txt", "0 0.6 0.6 0.1 0.1\n0 0.2 0.2 0.1 0.1\n");
  test::write_text(d / "other/labels/s1.txt", "0 0.6 0.6 0.1 0.1\n0 0.2 0.2 0.1 0.1\n");
  test::write_text(d / "real/predictions/det/s1.txt", "0 0.2 0.2 0.1 0.1 0.9\n0 0.65 0.6 0.1 0.1 0.4\n");
  test::write_text(d / "synth/predictions/det/s1.txt", "0 0.25 0.2 0.1 0.1 0.8\n");
  test::write_text(d / "other/predictions/det/s1.txt", "0 0.2 0.2 0.1 0.1 0.8\n");
  test::write_text(d / "study.yaml", yaml);
}

const TableCell& cell(const CrossTable& t, const std::string& a, const std::string& b) {
  const TableCell* c = t.cell("det", a, b);
  EXPECT_NE(c, nullptr) << a << " vs " << b;
  return *c;
}

TEST(TableRules, AModelWithoutATrainingDomainHasEveryCellShown) {
  test::TempDir d;
  write_study_table_rules(d, "domains: [real, synth, other]\n");
  const CrossTable t = compute_cross_table(load_labels(open_study(d.path())), {});
  for (const auto& [a, b] : t.columns) EXPECT_TRUE(cell(t, a, b).involves_training_domain) << a << " vs " << b;
  EXPECT_NEAR(cell(t, "real", "synth").ipd, 0.5, 1e-12);
  const std::string text = format_table(t, TableFormat::kText);
  EXPECT_EQ(text.find("–"), std::string::npos) << text;
}

// Trained on real: real vs synth and real vs other are shown, synth vs other is dashed ("–" in text).
TEST(TableRules, ACellWithoutTheTrainingDomainIsDashed) {
  test::TempDir d;
  write_study_table_rules(d, "domains: [real, synth, other]\nmodels: {det: {trained_on: real}}\n");
  const CrossTable t = compute_cross_table(load_labels(open_study(d.path())), {});
  EXPECT_TRUE(cell(t, "real", "synth").involves_training_domain);
  EXPECT_TRUE(cell(t, "real", "other").involves_training_domain);
  EXPECT_FALSE(cell(t, "synth", "other").involves_training_domain);
  const std::string text = format_table(t, TableFormat::kText);
  EXPECT_NE(text.find("–"), std::string::npos) << text;
}

// The row's best shown value, its lowest IPD, is bold in Markdown and LaTeX, as in the paper.
TEST(TableRules, TheRowsLowestIpdIsBold) {
  test::TempDir d;
  write_study_table_rules(d, "domains: [real, synth, other]\nmodels: {det: {trained_on: real}}\n");
  const CrossTable t = compute_cross_table(load_labels(open_study(d.path())), {});
  EXPECT_NEAR(cell(t, "real", "synth").ipd, 0.5, 1e-12);
  EXPECT_NEAR(cell(t, "real", "other").ipd, 1.0 / 6, 1e-12);
  const std::string md = format_table(t, TableFormat::kMarkdown);
  EXPECT_NE(md.find("**0.1667**"), std::string::npos) << md;
  EXPECT_EQ(md.find("**0.5000**"), std::string::npos) << md;
  const std::string latex = format_table(t, TableFormat::kLatex);
  EXPECT_NE(latex.find("\\textbf{0.1667}"), std::string::npos) << latex;
}

// A table that prints "–" where no chosen model trained never registers those domain pairs: trained on real,
// synth vs other is dashed, so 2 of the 3 domain pairs (one scene each) are registered; the shown cells keep
// their values and the text is the same as when every pair is registered.
TEST(TableRules, OnlyTheShownDomainPairsAreRegistered) {
  test::TempDir d;
  write_study_table_rules(d, "domains: [real, synth, other]\nmodels: {det: {trained_on: real}}\n");
  const StudyLabels labels = load_labels(open_study(d.path()));
  const CrossTable all = compute_cross_table(labels, {});
  EXPECT_EQ(all.registrations, 3);
  TableOptions o;
  o.shown_cells_only = true;
  const CrossTable shown = compute_cross_table(labels, o);
  EXPECT_EQ(shown.registrations, 2);
  EXPECT_NEAR(cell(shown, "real", "synth").ipd, 0.5, 1e-12);
  EXPECT_NEAR(cell(shown, "real", "other").ipd, 1.0 / 6, 1e-12);
  EXPECT_EQ(cell(shown, "synth", "other").scenes, 0);
  EXPECT_EQ(format_table(shown, TableFormat::kText), format_table(all, TableFormat::kText));
  // A model without a training domain shows every cell: every pair is registered.
  test::write_text(d / "study.yaml", "domains: [real, synth, other]\n");
  EXPECT_EQ(compute_cross_table(load_labels(open_study(d.path())), o).registrations, 3);
}

}  // namespace
}  // namespace ipd
