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

// Four domains (six domain pairs) don't fit one column: the tool says so, with a width TeX confirms, and
// points to the wide layout for table*.
TEST(LatexTable, TheToolSaysWhenOnlyTableStarFits) {
  test::TempDir d, tex;
  test::write_small_demo_study(d);
  fs::copy(d / "principled", d / "lambert", fs::copy_options::recursive);
  test::write_text(d / "study.yaml",
                   "domains: [real, principled, hapke, lambert]\nimage_size: [960, 600]\nmodels:\n"
                   "  det-real: {trained_on: real}\n  det-principled: {trained_on: principled}\n"
                   "  det-hapke: {trained_on: hapke}\n");
  const auto r = test::run_ipd("table " + d.path() + " --format latex --ci");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const double stated = stated_width(r.err);
  EXPECT_GT(stated, 252) << r.err;
  EXPECT_NE(r.err.find("more than one IEEE column (252 pt at 10 pt type): only a table* across both columns fits it "
                       "(--latex-wide spells the names out for that)"),
            std::string::npos)
      << r.err;
  if (!have_pdflatex())
    GTEST_SKIP() << "pdflatex not found (Debian: apt-get install texlive-latex-base): the stated width is not checked";
  const Compiled c = compile(tex, r.out);
  EXPECT_NEAR(stated, c.width_pt, 8) << r.out;
  EXPECT_GT(c.width_pt, 252);
}

}  // namespace
}  // namespace ipd
