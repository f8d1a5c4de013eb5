// The LaTeX cross table fits where a paper puts it, at 10 pt type and never by shrinking it: the default
// (compact) layout one IEEE column (252 pt) for up to three domains with intervals, --latex-wide a table*
// across both (516 pt); `ipd table` says when only the wide one fits. Measured by compiling a minimal
// IEEE-like document (10 pt article, 252 pt text width) with pdflatex and reading the tabular's box width.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>

#include "core/demo/demo_study.h"
#include "tests/support/figure_test_study.h"
#include "tests/support/test_support.h"

namespace fs = std::filesystem;

namespace ipd {
namespace {

bool have_pdflatex() { return test::run_command("command -v pdflatex").exit_code == 0; }

struct Compiled {
  double width_pt = -1;  // the tabular's box
  int overfull = 0;      // Overfull \hbox warnings of the whole output set in one 252 pt column
  std::string log;
};

// Compiles `latex` (the output of `ipd table --format latex`) in a 10 pt article with a 252 pt column.
Compiled compile(const test::TempDir& d, const std::string& latex) {
  const size_t a = latex.find("\\begin{tabular}"), b = latex.find("\\end{tabular}");
  if (a == std::string::npos || b == std::string::npos) return {};
  test::write_text(d / "tab.tex", latex.substr(a, b + 13 - a));
  test::write_text(d / "t.tex", latex);
  test::write_text(
      d / "doc.tex",
      "\\documentclass[10pt]{article}\n\\IfFileExists{booktabs.sty}{\\usepackage{booktabs}}{}\n"
      "\\providecommand\\toprule{\\hline}\\providecommand\\midrule{\\hline}\\providecommand\\bottomrule{\\hline}\n"
      "\\ifdefined\\cmidrule\\else\\def\\cmidrule(#1)#2{}\\fi\n\\setlength{\\textwidth}{252pt}\n"
      "\\begin{document}\n\\newsavebox\\tbl\\sbox\\tbl{\\input{tab.tex}}\n\\typeout{TABULAR-WIDTH=\\the\\wd\\tbl}\n"
      "\\begin{table}\\centering\\input{t.tex}\\end{table}\n\\end{document}\n");
  const auto r = test::run_command("cd '" + d.path() + "' && pdflatex -interaction=nonstopmode -halt-on-error doc.tex");
  Compiled c;
  std::ifstream in(d / "doc.log");
  std::stringstream ss;
  ss << in.rdbuf();
  c.log = ss.str();
  EXPECT_EQ(r.exit_code, 0) << c.log;
  std::smatch m;
  if (std::regex_search(c.log, m, std::regex("TABULAR-WIDTH=([0-9.]+)pt"))) c.width_pt = std::stod(m[1]);
  for (size_t p = 0; (p = c.log.find("Overfull \\hbox", p)) != std::string::npos; ++p) ++c.overfull;
  return c;
}

// The estimate `ipd table` states when a table does not fit, from the note on stderr (-1: no note).
double stated_width(const std::string& err) {
  std::smatch m;
  return std::regex_search(err, m, std::regex("the LaTeX table is about ([0-9]+) pt wide")) ? std::stod(m[1]) : -1;
}

TEST(LatexTable, CompactLayoutNamesDomainsByLetterWithALegend) {
  test::TempDir d;
  test::write_small_demo_study(d);
  const auto r = test::run_ipd("table " + d.path() + " --format latex --ci");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(
      r.out.find(
          "Train & \\multicolumn{3}{c|}{$\\downarrow$ IPD} \\\\\n & $|$A$-$B$|$ & $|$A$-$C$|$ & $|$B$-$C$|$ \\\\\n"),
      std::string::npos)
      << r.out;
  // A row (its best value bold) and its intervals on the line below (braced: "[" after \\ would be read as a length).
  EXPECT_TRUE(std::regex_search(
      r.out,
      std::regex(
          R"(\nA & (\\textbf\{)?0\.\d{4}\}? & (\\textbf\{)?0\.\d{4}\}? & -- \\\\\n & \{\[\}0\.\d{3}, 0\.\d{3}\{\]\} & \{\[\}0\.\d{3}, 0\.\d{3}\{\]\} &  \\\\\n)")))
      << r.out;
  EXPECT_NE(
      r.out.find("{\\footnotesize A: real, B: principled, C: hapke. Rows: the detector trained on A (det-real), B "
                 "(det-principled), C (det-hapke). IPD: mean $|$performance-value difference$|$ over matched rock "
                 "pairs, lower is better; bold: the row's best; --: pair not involving the training domain. "
                 "[low, high]: 95\\% scene-bootstrap percentile interval (2,000 resamples of scenes, seed 0).\\par}"),
      std::string::npos)
      << r.out;
  EXPECT_EQ(r.err.find("LaTeX table"), std::string::npos) << r.err;  // it fits: nothing to say
  // The wide layout spells the names out, intervals beside the values.
  const auto wide = test::run_ipd("table " + d.path() + " --format latex --ci --latex-wide");
  ASSERT_EQ(wide.exit_code, 0) << wide.err;
  EXPECT_NE(wide.out.find("$|$real $-$ principled$|$"), std::string::npos) << wide.out;
  EXPECT_TRUE(std::regex_search(
      wide.out, std::regex(R"(det-real \(real\) & (\\textbf\{)?0\.\d{4}\}? \[0\.\d{3}, 0\.\d{3}\] & )")))
      << wide.out;
}

// Three domains: 140 pt too wide before (184 pt with --ci). Now every compact variant fits one column, and the
// stated estimate is within 8 pt of what TeX measures.
TEST(LatexTable, ThreeDomainsWithIntervalsFitOneIeeeColumn) {
  if (!have_pdflatex())
    GTEST_SKIP()
        << "pdflatex not found (Debian: apt-get install texlive-latex-base): the LaTeX table's width is not measured";
  test::TempDir d, tex;
  test::write_small_demo_study(d);
  for (const std::string opts : {"", " --ci", " --booktabs", " --ci --booktabs"}) {
    const auto r = test::run_ipd("table " + d.path() + " --format latex" + opts);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const Compiled c = compile(tex, r.out);
    EXPECT_GT(c.width_pt, 100) << opts;
    EXPECT_LE(c.width_pt, 252) << opts << ": " << r.out;
    EXPECT_EQ(c.overfull, 0) << opts << ": the legend or the table overflows the column\n" << c.log;
  }
  // The wide layout is what needs table*: wider than a column, within both.
  const auto wide = test::run_ipd("table " + d.path() + " --format latex --ci --latex-wide");
  // It says how to read it, as the one-column layout does (it had only % comments).
  EXPECT_NE(wide.out.find("\\par\\smallskip{\\footnotesize IPD: mean $|$performance-value difference$|$ over "
                          "matched rock pairs, lower is better; bold: the row's best; --: pair not involving the "
                          "training domain."),
            std::string::npos)
      << wide.out;
  const Compiled c = compile(tex, wide.out);
  EXPECT_GT(c.width_pt, 252);
  EXPECT_LE(c.width_pt, 516);
  EXPECT_EQ(stated_width(wide.err), -1) << wide.err;
}

// Two domains with --ci: 11 pt too wide before.
TEST(LatexTable, TwoDomainsWithIntervalsFitOneIeeeColumn) {
  if (!have_pdflatex())
    GTEST_SKIP()
        << "pdflatex not found (Debian: apt-get install texlive-latex-base): the LaTeX table's width is not measured";
  test::TempDir d, tex;
  test::write_small_demo_study(d);
  // Only real and principled, and their two detectors.
  test::write_text(d / "study.yaml",
                   "domains: [real, principled]\nimage_size: [960, 600]\nmodels:\n"
                   "  det-real: {trained_on: real}\n  det-principled: {trained_on: principled}\n");
  fs::remove_all(d / "hapke");
  for (const std::string dom : {"real", "principled"}) fs::remove_all(d / (dom + "/predictions/det-hapke"));
  const auto r = test::run_ipd("table " + d.path() + " --format latex --ci");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find(" & $|$A$-$B$|$ \\\\\n"), std::string::npos) << r.out;  // one domain pair
  const Compiled c = compile(tex, r.out);
  EXPECT_GT(c.width_pt, 50);
  EXPECT_LE(c.width_pt, 252) << r.out;
}

// The demo's first three scenes with a fourth domain (a copy of principled) and `models` of its detectors.
void write_four_domains(const test::TempDir& d, const std::string& models) {
  test::write_small_demo_study(d);
  fs::copy(d / "principled", d / "lambert", fs::copy_options::recursive);
  test::write_text(d / "study.yaml",
                   "domains: [real, principled, hapke, lambert]\nimage_size: [960, 600]\nmodels:\n" + models);
}
const char* const kThreeModels =
    "  det-real: {trained_on: real}\n  det-principled: {trained_on: principled}\n  det-hapke: {trained_on: hapke}\n";

// Four domains and three detectors: every one of the six pairs holds a number, so only the rows can turn. The
// pairs as rows with intervals need about 254 pt with vertical rules (TeX measures 251.5: the estimate errs
// wide) and 240 without: the tool names --booktabs, which TeX confirms fits, and never a layout that does not.
TEST(LatexTable, FourDomainsAndThreeDetectorsNameTheOptionThatFits) {
  test::TempDir d, tex;
  write_four_domains(d, kThreeModels);
  const auto r = test::run_ipd("table " + d.path() + " --format latex --ci");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("note: the LaTeX table is about 254 pt wide, more than one IEEE column (252 pt at 10 pt "
                       "type): --booktabs fits it in one (no vertical rules: about 240 pt)\n"),
            std::string::npos)
      << r.err;
  EXPECT_NE(r.out.find("\\begin{tabular}{|l|c|c|c|}"), std::string::npos) << r.out;  // pairs as rows
  const auto bt = test::run_ipd("table " + d.path() + " --format latex --ci --booktabs");
  ASSERT_EQ(bt.exit_code, 0) << bt.err;
  EXPECT_EQ(stated_width(bt.err), -1) << bt.err;  // fits: nothing said
  const auto wide = test::run_ipd("table " + d.path() + " --format latex --ci --latex-wide");
  EXPECT_NE(wide.err.find("note: the LaTeX table is about 776 pt wide, more than both IEEE columns (516 pt): drop "
                          "--latex-wide and add --booktabs: the compact layout then fits one column (about 240 pt)\n"),
            std::string::npos)
      << wide.err;
  if (!have_pdflatex())
    GTEST_SKIP() << "pdflatex not found (Debian: apt-get install texlive-latex-base): the stated width is not checked";
  EXPECT_NEAR(compile(tex, r.out).width_pt, 254, 8);
  const Compiled c = compile(tex, bt.out);
  EXPECT_LE(c.width_pt, 252) << bt.out;
  EXPECT_NEAR(c.width_pt, 240, 8);
}

// Four domains and two detectors (real, principled): the pair lambert - hapke holds no number and is left out
// (said in the legend); the other five as columns need about 388 pt, so they become rows (one column per
// detector, about 184 pt), and the tool says why. --latex-wide (about 671 pt) is told to drop the flag, since
// the compact layout fits one column: advice that holds for every layout.
TEST(LatexTable, FourDomainsAndTwoDetectorsTurnThePairsIntoRows) {
  test::TempDir d, tex;
  write_four_domains(d, "  det-real: {trained_on: real}\n  det-principled: {trained_on: principled}\n");
  for (const std::string dom : {"real", "principled", "hapke", "lambert"})
    fs::remove_all(d / (dom + "/predictions/det-hapke"));
  const auto r = test::run_ipd("table " + d.path() + " --format latex --ci");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("note: the domain pairs are the LaTeX table's rows (about 184 pt wide): as columns they would "
                       "take about 388 pt, more than one IEEE column (252 pt at 10 pt type)\n"),
            std::string::npos)
      << r.err;
  EXPECT_NE(r.out.find("Eval & \\multicolumn{2}{c|}{$\\downarrow$ IPD, train} \\\\\n & A & B \\\\\n"),
            std::string::npos)
      << r.out;
  for (const std::string pair : {"A$-$B", "A$-$C", "A$-$D", "B$-$C", "B$-$D"})
    EXPECT_NE(r.out.find("$|$" + pair + "$|$ & "), std::string::npos) << pair << "\n" << r.out;
  EXPECT_EQ(r.out.find("C$-$D"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("Columns: the detector trained on A (det-real), B (det-principled). Rows: domain pairs."),
            std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find("Not shown: 1 domain pair without any row's training domain (every cell --)."),
            std::string::npos)
      << r.out;
  const auto wide = test::run_ipd("table " + d.path() + " --format latex --ci --latex-wide");
  EXPECT_NE(wide.err.find("note: the LaTeX table is about 671 pt wide, more than both IEEE columns (516 pt): drop "
                          "--latex-wide: the compact layout fits one column (about 184 pt)\n"),
            std::string::npos)
      << wide.err;
  if (!have_pdflatex())
    GTEST_SKIP() << "pdflatex not found (Debian: apt-get install texlive-latex-base): the widths are not measured";
  const Compiled c = compile(tex, r.out);
  EXPECT_NEAR(c.width_pt, 184, 8);
  EXPECT_EQ(c.overfull, 0) << c.log;
}

// Four domains and one detector: three of the six pairs are "--" in every row and left out; the other three
// fit one column as columns, and nothing is said.
TEST(LatexTable, FourDomainsAndOneDetectorShowOnlyItsPairs) {
  test::TempDir d, tex;
  write_four_domains(d, kThreeModels);
  const auto r = test::run_ipd("table " + d.path() + " --format latex --ci --model det-real");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(stated_width(r.err), -1) << r.err;
  EXPECT_EQ(r.err.find("IEEE"), std::string::npos) << r.err;
  EXPECT_NE(r.out.find(" & $|$A$-$B$|$ & $|$A$-$C$|$ & $|$A$-$D$|$ \\\\\n"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("Not shown: 3 domain pairs without any row's training domain (every cell --)."),
            std::string::npos)
      << r.out;
  if (!have_pdflatex())
    GTEST_SKIP() << "pdflatex not found (Debian: apt-get install texlive-latex-base): the width is not measured";
  EXPECT_LE(compile(tex, r.out).width_pt, 252) << r.out;
}

// `ipd rank --format latex` fits one column on the demo's nine renderer settings with intervals: settings by
// their parameter (ambient), best first, intervals on a second line; --latex-wide keeps names and parameters on
// one line for a table*.
TEST(LatexTable, RankingFitsOneIeeeColumn) {
  test::TempDir d, tex;
  ASSERT_EQ(test::run_ipd("demo " + d.path() + "/v9 --variants 9").exit_code, 0);
  const std::string st = d.path() + "/v9";
  const auto r = test::run_ipd("rank " + st + " --ref real --model det-real --format latex --ci");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err.find("IEEE"), std::string::npos) << r.err;
  EXPECT_NE(r.out.find("ambient & IPD & $\\Delta$IPD & $p$ Holm & \\\\\n"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("0.375 & \\textbf{"), std::string::npos) << r.out;  // the true best, first
  EXPECT_NE(r.out.find("Best first; settings by their parameters (ambient-038, "), std::string::npos) << r.out;
  const auto wide = test::run_ipd("rank " + st + " --ref real --model det-real --format latex --ci --latex-wide");
  ASSERT_EQ(wide.exit_code, 0) << wide.err;
  EXPECT_NE(wide.out.find("1 & ambient-038 & ambient=0.375 & "), std::string::npos) << wide.out;
  if (!have_pdflatex())
    GTEST_SKIP() << "pdflatex not found (Debian: apt-get install texlive-latex-base): the width is not measured";
  const Compiled c = compile(tex, r.out);
  EXPECT_GT(c.width_pt, 150);
  EXPECT_LE(c.width_pt, 252) << r.out;
}

}  // namespace
}  // namespace ipd
