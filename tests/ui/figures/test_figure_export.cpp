// The GUI's "Export figure…" for the study-wide kinds: the function the studio's worker calls
// (ui::export_figure on the session) and `ipd figure KIND` on the same study state (threshold, hand edits,
// domains, model) give the same PDF text.
#include <gtest/gtest.h>

#include <filesystem>

#include "ui/figures/figure_export.h"
#include "core/session/session.h"
#include "tests/support/pdf_text.h"
#include "tests/support/stats_study.h"
#include "tests/support/test_support.h"

namespace fs = std::filesystem;

namespace ipd {
namespace {

struct Case {
  std::string kind, by, cli;  // cli: the `ipd figure` arguments that describe the same view
};

TEST(FigureExport, GuiAndCliGiveTheSameStudyFigures) {
  test::TempDir d;
  test::write_stats_study(d.path(), test::StatsStudyVariant::kDistinct);
  // The view: real vs hapke, threshold 0.5 (the detections are 0.30-0.95 confident), and one scene's pairs
  // edited by hand (saved where `ipd figure` reads them).
  Session s = Session::open(d.path());
  s.select_domains("real", "hapke");
  s.set_conf_threshold(0.5);
  run_save_job(s.apply(0, Edit::unpair(Side::kA, 0)));
  ASSERT_TRUE(fs::exists(d / "pairs/real__hapke/s00.json"));
  const std::string view = " --conf 0.5 --model det";
  const std::vector<Case> cases = {
      {"table", "size", "table --ci 0.95"},
      {"compare", "size", "compare"},
      {"distribution", "size", "distribution"},
      {"breakdown", "size", "breakdown --by size --a real --b hapke"},
      {"breakdown", "region", "breakdown --by region --a real --b hapke"},
      {"breakdown", "confidence", "breakdown --by confidence --a real --b hapke"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.kind + " " + c.by);
    ui::ExportRequest request;
    request.kind = c.kind;
    request.options.ci = true;
    request.options.by = c.by;
    request.path = d / ("gui_" + c.kind + c.by + ".pdf");
    EXPECT_EQ(ui::export_figure(s, request), "exported " + request.path);
    const std::string cli_pdf = d / ("cli_" + c.kind + c.by + ".pdf");
    const auto r = test::run_ipd("figure " + c.cli + " " + d.path() + view + " --out " + cli_pdf);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const std::string gui = test::pdf_words(request.path), cli = test::pdf_words(cli_pdf);
    EXPECT_GT(gui.size(), 100u) << gui;
    EXPECT_EQ(gui, cli);
    if (c.kind == "breakdown") {
      EXPECT_NE(gui.find("IPD(real, hapke) of det (real) by"), std::string::npos) << gui;
    }
  }
  // The threshold is part of the view: without it the table and the confidence bins are other figures.
  ASSERT_EQ(test::run_ipd("figure table --ci 0.95 " + d.path() + " --out " + d / "all.pdf").exit_code, 0);
  EXPECT_NE(test::pdf_words(d / "all.pdf"), test::pdf_words(d / "gui_tablesize.pdf"));
  ASSERT_EQ(test::run_ipd("figure breakdown --by confidence --a real --b hapke " + d.path() + " --out " + d / "allc.pdf").exit_code, 0);
  EXPECT_NE(test::pdf_words(d / "allc.pdf"), test::pdf_words(d / "gui_breakdownconfidence.pdf"));
}

TEST(FigureExport, CompareUsesTheDomainsOfTheComparePanel) {
  test::TempDir d;
  test::write_stats_study(d.path(), test::StatsStudyVariant::kDistinct);
  const Session s = Session::open(d.path());
  ui::ExportRequest request;
  request.kind = "compare";
  request.ref = "real", request.a = "hapke", request.b = "principled";
  request.path = d / "gui.pdf";
  EXPECT_EQ(ui::export_figure(s, request), "exported " + request.path);
  const auto r = test::run_ipd("figure compare " + d.path() + " --a hapke --b principled --out " + d / "cli.pdf");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string gui = test::pdf_words(d / "gui.pdf");
  EXPECT_EQ(gui, test::pdf_words(d / "cli.pdf"));
  EXPECT_NE(gui.find("IPD(real, hapke) \u2212 IPD(real, principled)"), std::string::npos) << gui;
}

TEST(FigureExport, UnknownKindIsReported) {
  test::TempDir d;
  test::write_stats_study(d.path(), test::StatsStudyVariant::kDistinct);
  const Session s = Session::open(d.path());
  ui::ExportRequest request;
  request.kind = "histogram";
  request.path = d / "x.pdf";
  EXPECT_EQ(ui::export_figure(s, request), "export failed: unknown figure kind 'histogram'");
  EXPECT_FALSE(fs::exists(d / "x.pdf"));
}

}  // namespace
}  // namespace ipd
