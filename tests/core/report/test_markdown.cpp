// Markdown tables: a `|` in a model or domain name ended its cell and shifted the row one column.
#include <gtest/gtest.h>

#include "core/ipd/ipd.h"
#include "core/report/markdown.h"
#include "core/report/table_format.h"
#include "tests/support/test_support.h"

namespace ipd {
namespace {

TEST(Markdown, APipeInACellIsEscapedAndABackslashDoubled) {
  EXPECT_EQ(markdown_cell("det-real"), "det-real");
  EXPECT_EQ(markdown_cell("det|real"), "det\\|real");
  EXPECT_EQ(markdown_cell("a\\|b"), "a\\\\\\|b");
  EXPECT_EQ(markdown_cell(""), "");
}

// The study of TableRules (IPD 0.5, worked by hand there) with a model "d|et" and a domain "sy|nth": every
// row keeps two cells.
TEST(Markdown, ModelAndDomainNamesWithAPipeStayInTheirColumn) {
  test::TempDir d;
  test::write_text(d / "real/labels/s1.txt", "0 0.2 0.2 0.1 0.1\n0 0.6 0.6 0.1 0.1\n");
  test::write_text(d / "sy|nth/labels/s1.txt", "0 0.6 0.6 0.1 0.1\n0 0.2 0.2 0.1 0.1\n");
  test::write_text(d / "real/predictions/d|et/s1.txt", "0 0.2 0.2 0.1 0.1 0.9\n0 0.65 0.6 0.1 0.1 0.4\n");
  test::write_text(d / "sy|nth/predictions/d|et/s1.txt", "0 0.25 0.2 0.1 0.1 0.8\n");
  test::write_text(d / "study.yaml", "domains: [real, \"sy|nth\"]\nmodels: {\"d|et\": {trained_on: real}}\n");
  const CrossTable t = compute_cross_table(load_labels(open_study(d.path())), {});
  const std::string md = format_table(t, TableFormat::kMarkdown);
  EXPECT_EQ(md.substr(0, md.find("\n\n")),
            "| Train \\ Eval | \\|real - sy\\|nth\\| |\n"
            "|---|---:|\n"
            "| d\\|et (real) | **0.5000** |")
      << md;
}

}  // namespace
}  // namespace ipd
