// No predictions is not a perfect renderer: when neither domain has a prediction left after the threshold,
// a cell has no number (and says why) in the table, its formats, compare and the studio's Session; one side
// without predictions is a number and a warning.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "core/report/table_format.h"
#include "core/session/session.h"
#include "core/stats/study_statistics.h"
#include "tests/support/pdf_text.h"
#include "tests/support/test_support.h"
#include "ui/figures/figure_table.h"

namespace ipd {
namespace {

// Two rocks per side (listed in the other order in synth). det's confidences: real 0.9 (rock 0, exact) and
// 0.4 (rock 1, IoU 1/3); synth 0.8 (synth rock 1 = real rock 0, IoU 1/3).
void write_study_no_predictions(const test::TempDir& d, const std::string& yaml) {
  test::write_text(d / "real/labels/s1.txt", "0 0.2 0.2 0.1 0.1\n0 0.6 0.6 0.1 0.1\n");
  test::write_text(d / "synth/labels/s1.txt", "0 0.6 0.6 0.1 0.1\n0 0.2 0.2 0.1 0.1\n");
  test::write_text(d / "real/predictions/det/s1.txt", "0 0.2 0.2 0.1 0.1 0.9\n0 0.65 0.6 0.1 0.1 0.4\n");
  test::write_text(d / "synth/predictions/det/s1.txt", "0 0.25 0.2 0.1 0.1 0.8\n");
  test::write_text(d / "study.yaml", yaml + "image_size: [1000, 1000]\n");
}

CrossTable table_of_no_predictions(const std::string& root) {
  return compute_cross_table(load_labels(open_study(root)), {});
}

TEST(NoPredictions, NeitherSideLeftIsNotANumber) {
  test::TempDir d;
  write_study_no_predictions(d, "conf_threshold: 0.95\n");
  CrossTable t = table_of_no_predictions(d.path());
  ASSERT_EQ(t.cells.size(), 1u);
  const TableCell& c = t.cells[0];
  EXPECT_TRUE(std::isnan(c.ipd));  // not 0.0000: every rock's value is 0 on both sides
  EXPECT_EQ(c.no_value_reason, "no predictions at or above 0.95 in real and synth");
  EXPECT_EQ(c.pairs, 2);  // the pairs are still there, only the number is not
  BootstrapOptions b;
  b.resamples = 100;
  add_confidence_intervals(&t, b, 1);
  EXPECT_TRUE(std::isnan(t.cells[0].ci_low));  // no [0.000, 0.000] either
  EXPECT_TRUE(t.warnings.empty());

  EXPECT_EQ(format_table(t, TableFormat::kText),
            "train \\ eval (IPD, lower is better)  |real - synth|\n"
            "det                                  –¹\n"
            "¹ no predictions at or above 0.95 in real and synth\n");
  const std::string csv = format_table(t, TableFormat::kCsv);
  EXPECT_EQ(csv.substr(csv.find('\n') + 1),
            "det,,real,synth,,2,0,0,1,true,,,,no predictions at or above 0.95 in real and synth\n");
  const std::string json = format_table(t, TableFormat::kJson);
  EXPECT_NE(json.find("\"ipd\": null"), std::string::npos) << json;
  EXPECT_NE(json.find("\"reason\": \"no predictions at or above 0.95 in real and synth\""), std::string::npos) << json;
  // The one-column layout (rows as letters, legend below) and the wide one both mark the cell and say why.
  const std::string latex = format_table(t, TableFormat::kLatex);
  EXPECT_NE(latex.find("M1 & --$^{1}$ \\\\"), std::string::npos) << latex;
  EXPECT_NE(latex.find("\\par}\n\\par{\\footnotesize $^{1}$ no predictions at or above 0.95 in real and synth}\n"),
            std::string::npos)
      << latex;
  TableFormatOptions wide;
  wide.latex_wide = true;
  const std::string latex_wide = format_table(t, TableFormat::kLatex, wide);
  EXPECT_NE(latex_wide.find("det & --$^{1}$ \\\\"), std::string::npos) << latex_wide;
  // Below the table and its legend, as in the one-column layout.
  EXPECT_NE(
      latex_wide.find("training domain.\\par}\n\\par{\\footnotesize $^{1}$ no predictions at or above 0.95 in real and "
                      "synth}\n"),
      std::string::npos)
      << latex_wide;
  // The table figure marks the cell and says why in its note.
  const ui::TableFigure fig = ui::table_figure_of(t);
  EXPECT_EQ(fig.rows.at(0).at(1), "\u2013\u00b9");
  EXPECT_NE(fig.note.find("\u2013\u00b9: not a number, no predictions at or above 0.95 in real and synth."),
            std::string::npos)
      << fig.note;
  const std::string md = format_table(t, TableFormat::kMarkdown);
  EXPECT_NE(md.find("| det | –¹ |"), std::string::npos) << md;
  EXPECT_NE(md.find("\n¹ no predictions at or above 0.95 in real and synth\n"), std::string::npos) << md;
}

TEST(NoPredictions, CompareRefusesACellWithoutANumber) {
  test::TempDir d;
  write_study_no_predictions(d, "conf_threshold: 0.95\n");
  test::write_text(d / "other/labels/s1.txt", "0 0.2 0.2 0.1 0.1\n0 0.6 0.6 0.1 0.1\n");
  test::write_text(d / "other/predictions/det/s1.txt", "0 0.2 0.2 0.1 0.1 0.99\n");
  const CrossTable t = table_of_no_predictions(d.path());
  try {
    compare_renderers(t, "det", "real", "synth", "other", {});
    FAIL() << "compared two empty prediction sets";
  } catch (const StudyError& e) {
    EXPECT_STREQ(e.what(),
                 "model 'det': IPD(real, synth) is not a number: no predictions at or above 0.95 in real and synth");
  }
  // Nor is it broken down by rock size (every bin would read 0).
  try {
    breakdown_cell(load_labels(open_study(d.path())), *t.cell("det", "real", "synth"), {});
    FAIL() << "broke down two empty prediction sets";
  } catch (const StudyError& e) {
    EXPECT_STREQ(e.what(),
                 "model 'det': IPD(real, synth) is not a number: no predictions at or above 0.95 in real and synth");
  }
}

TEST(NoPredictions, OneSideWithoutPredictionsIsANumberAndAWarning) {
  test::TempDir d;
  write_study_no_predictions(d, "conf_threshold: 0.85\n");
  // Only real's 0.9 is left: real rock 0 -> 1, real rock 1 -> 0, synth 0 and 0: (|1 - 0| + |0 - 0|) / 2.
  const CrossTable t = table_of_no_predictions(d.path());
  EXPECT_NEAR(t.cells[0].ipd, 0.5, 1e-12);
  EXPECT_EQ(t.cells[0].no_value_reason, "");
  ASSERT_EQ(t.warnings.size(), 1u);
  EXPECT_EQ(t.warnings[0],
            "model 'det' has no predictions at or above 0.85 in 'synth' (its scenes compared with 'real'): "
            "every rock there counts as missed, as a detector that found nothing");
}

TEST(NoPredictions, PredictionsThatMissEveryRockAreANumber) {
  test::TempDir d;
  write_study_no_predictions(d, "");
  // Far from every rock: each performance value is 0, and 0 is the measured IPD (the detector misses alike).
  test::write_text(d / "real/predictions/det/s1.txt", "0 0.9 0.9 0.05 0.05 0.9\n");
  test::write_text(d / "synth/predictions/det/s1.txt", "0 0.9 0.1 0.05 0.05 0.9\n");
  const CrossTable t = table_of_no_predictions(d.path());
  EXPECT_EQ(t.cells[0].ipd, 0.0);
  EXPECT_EQ(t.cells[0].no_value_reason, "");
  EXPECT_TRUE(t.warnings.empty());
}

TEST(NoPredictions, TheSessionSaysWhyItsCellHasNoNumber) {
  test::TempDir d;
  write_study_no_predictions(d, "");
  Session s(load_labels(open_study(d.path())));
  EXPECT_NEAR(s.cell().ipd, 0.5, 1e-12);  // the tiny study worked by hand (test_ipd.cpp)
  s.set_conf_threshold(0.95);             // the slider: nothing is left on either side
  EXPECT_TRUE(std::isnan(s.cell().ipd));
  EXPECT_EQ(s.cell().no_value_reason, "no predictions at or above 0.95 in real and synth");
  EXPECT_EQ(s.summary(0).no_value_reason, "no predictions at or above 0.95 in real and synth");
  EXPECT_TRUE(std::isnan(s.summary(0).ipd));
  ASSERT_EQ(s.problems().size(), 1u);  // the Problems window says why the cell has no number
  EXPECT_EQ(s.problems()[0].to_string(),
            "model 'det': IPD(real, synth) is not a number: no predictions at or above 0.95 in real and synth");
  s.set_conf_threshold(0.85);
  EXPECT_NEAR(s.cell().ipd, 0.5, 1e-12);
  ASSERT_EQ(s.problems().size(), 1u);
  EXPECT_EQ(s.problems()[0].to_string(),
            "model 'det' has no predictions at or above 0.85 in 'synth' (its scenes compared "
            "with 'real'): every rock there counts as missed, as a detector that found nothing");
  EXPECT_EQ(s.summary(0).no_value_reason, "");
}

// The Problems window lists the cells the table shows: a cell without the model's training domain is dashed in
// every table, so its missing number is no problem to fix.
TEST(NoPredictions, TheSessionListsOnlyCellsTheTableShows) {
  test::TempDir d;
  write_study_no_predictions(d, "models: {det: {trained_on: real}}\n");
  test::write_text(d / "other/labels/s1.txt", "0 0.6 0.6 0.1 0.1\n0 0.2 0.2 0.1 0.1\n");
  test::write_text(d / "other/predictions/det/s1.txt", "0 0.25 0.2 0.1 0.1 0.8\n");
  Session s(load_labels(open_study(d.path())));
  s.set_conf_threshold(0.95);
  std::vector<std::string> cells;
  for (const Problem& p : s.problems()) cells.push_back(p.domain + " " + p.other_domain);
  EXPECT_EQ(cells, (std::vector<std::string>{"real other", "real synth"}));  // not "other synth"
}

}  // namespace
}  // namespace ipd

namespace ipd {
namespace {
// Figures never draw two empty prediction sets as a perfect match: the scene figure's title says there is
// no number and why, and the study figures of such a cell are refused, as ipd compare is.
TEST(NoPredictions, FiguresSayThereIsNoNumber) {
  test::TempDir d;
  ASSERT_EQ(test::run_ipd("demo " + d / "s" + " --labels-only --scenes 2 --rocks 8").exit_code, 0);
  auto r = test::run_ipd("figure pairs " + d / "s" + " --scene scene_00001 --conf 0.999 --out " + d / "p.pdf");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string words = test::pdf_words(d / "p.pdf");
  EXPECT_NE(words.find("IPD not a number (no predictions at or above 0.999 in real and principled)"), std::string::npos)
      << words;
  // A study with no detector at all: no model to name, and no number either.
  test::write_text(d / "bare/real/labels/s1.txt", "0 0.2 0.2 0.1 0.1\n0 0.6 0.6 0.1 0.1\n");
  test::write_text(d / "bare/synth/labels/s1.txt", "0 0.6 0.6 0.1 0.1\n0 0.2 0.2 0.1 0.1\n");
  test::write_text(d / "bare/study.yaml", "image_size: [1000, 1000]\n");
  r = test::run_ipd("figure pairs " + d / "bare --out " + d / "bare.pdf");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(test::pdf_words(d / "bare.pdf").find("model none, scene IPD not a number (the study has no predictions)"),
            std::string::npos)
      << test::pdf_words(d / "bare.pdf");
  for (const char* kind : {"distribution", "compare"}) {
    r = test::run_ipd(std::string("figure ") + kind + " " + d / "s" + " --conf 0.999 --out " + d / "f.pdf");
    EXPECT_EQ(r.exit_code, 1) << kind;
    EXPECT_NE(
        r.err.find("': IPD(real, principled) is not a number: no predictions at or above 0.999 in real and principled"),
        std::string::npos)
        << kind << ": " << r.err;
  }
}
}  // namespace
}  // namespace ipd

namespace ipd {
namespace {
// A model without a predictions folder for one domain: ipd compare names that domain, not all three.
TEST(NoPredictions, CompareNamesTheDomainWithoutPredictions) {
  test::TempDir d;
  ASSERT_EQ(test::run_ipd("demo " + d / "s" + " --labels-only --scenes 2 --rocks 8").exit_code, 0);
  std::filesystem::remove_all(d / "s/hapke/predictions/det-real");
  const auto r = test::run_ipd("compare " + d / "s" + " --model det-real --ref real --a principled --b hapke");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("model 'det-real' has no predictions for hapke\n"), std::string::npos) << r.err;
  // The comparison itself (the studio's compare panel) names the same one domain.
  const CrossTable t = compute_cross_table(load_labels(open_study(d / "s")), {});
  try {
    compare_renderers(t, "det-real", "real", "principled", "hapke", {});
    FAIL() << "compared";
  } catch (const StudyError& e) {
    EXPECT_EQ(std::string(e.what()),
              "model 'det-real': IPD(real, hapke) is not a number: no predictions of det-real for hapke");
  }
}

// A model without a predictions folder for one domain: its cells there are not a number, marked and
// footnoted under ipd table (never a bare "n/a" left unexplained).
TEST(NoPredictions, ACellOfAModelWithoutPredictionsForADomainIsFootnoted) {
  test::TempDir d;
  ASSERT_EQ(test::run_ipd("demo " + d / "s" + " --labels-only --scenes 2 --rocks 8").exit_code, 0);
  std::filesystem::remove_all(d / "s/hapke/predictions/det-real");
  const auto r = test::run_ipd("table " + d / "s" + " --bootstrap 0");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.out.find("n/a"), std::string::npos) << r.out;
  const size_t row = r.out.find("\ndet-real (real)");
  ASSERT_NE(row, std::string::npos) << r.out;
  const std::string line = r.out.substr(row + 1, r.out.find('\n', row + 1) - row - 1);
  EXPECT_NE(line.find("–¹"), std::string::npos) << line;
  EXPECT_NE(r.out.find("\n¹ no predictions of det-real for hapke\n"), std::string::npos) << r.out;
}
}  // namespace
}  // namespace ipd
