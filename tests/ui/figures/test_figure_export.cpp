// The GUI's "Export figure…" for the study-wide kinds: the function the studio's worker calls
// (ui::export_figure on the session) and `ipd figure KIND` on the same study state (threshold, hand edits,
// domains, model) give the same PDF text.
#include <gtest/gtest.h>

#include <filesystem>

#include "core/session/session.h"
#include "tests/support/pdf_text.h"
#include "tests/support/stats_study.h"
#include "tests/support/test_support.h"
#include "ui/figures/figure_export.h"
#include "ui/gui/export_dialog.h"

namespace fs = std::filesystem;

namespace ipd {
namespace {

struct CaseFigureExport {
  std::string kind, by, cli;     // cli: the `ipd figure` arguments that describe the same view
  std::string after_study = {};  // more of them after STUDY (--domains takes every word up to the next option)
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
  const std::vector<CaseFigureExport> cases = {
      {"table", "size", "table --ci 0.95"},
      {"compare", "size", "compare"},
      {"distribution", "size", "distribution"},
      {"breakdown", "size", "breakdown --by size --a real --b hapke"},
      {"breakdown", "region", "breakdown --by region --a real --b hapke"},
      {"breakdown", "confidence", "breakdown --by confidence --a real --b hapke"},
      {"gallery", "size", "gallery", "--domains real,hapke"},
  };
  for (const CaseFigureExport& c : cases) {
    SCOPED_TRACE(c.kind + " " + c.by);
    ui::ExportRequest request;
    request.kind = c.kind;
    request.options.ci = true;
    request.options.by = c.by;
    request.path = d / ("gui_" + c.kind + c.by + ".pdf");
    EXPECT_EQ(ui::export_figure(s, request), "exported " + request.path);
    const std::string cli_pdf = d / ("cli_" + c.kind + c.by + ".pdf");
    const auto r = test::run_ipd("figure " + c.cli + " " + d.path() + " " + c.after_study + view + " --out " + cli_pdf);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const std::string gui = test::pdf_words(request.path), cli = test::pdf_words(cli_pdf);
    EXPECT_GT(gui.size(), 100u) << gui;
    EXPECT_EQ(gui, cli);
    if (c.kind == "breakdown") {
      EXPECT_NE(gui.find("IPD(real, hapke) of det (real) by"), std::string::npos) << gui;
    }
    // The edit shows on every kind, in the GUI's file as in the CLI's.
    EXPECT_NE(gui.find("hand pairs in 1 scene"), std::string::npos) << gui;
  }
  // The threshold is part of the view: without it the table and the confidence bins are other figures.
  ASSERT_EQ(test::run_ipd("figure table --ci 0.95 " + d.path() + " --out " + d / "all.pdf").exit_code, 0);
  EXPECT_NE(test::pdf_words(d / "all.pdf"), test::pdf_words(d / "gui_tablesize.pdf"));
  ASSERT_EQ(
      test::run_ipd("figure breakdown --by confidence --a real --b hapke " + d.path() + " --out " + d / "allc.pdf")
          .exit_code,
      0);
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

// The studio's exports go through write_output_file too: its default folder STUDY/figures takes them, a path
// that is one of the study's inputs (a picture, here) is refused with the reason and the picture kept.
TEST(FigureExport, AnExportOverOneOfTheStudysInputsIsRefused) {
  test::TempDir d;
  test::write_stats_study(d.path(), test::StatsStudyVariant::kDistinct);
  const Session s = Session::open(d.path());
  ui::ExportRequest request;
  request.kind = "compare";
  request.ref = "real", request.a = "hapke", request.b = "principled";
  request.path = d / "real/images/s1.pdf";
  EXPECT_EQ(ui::export_figure(s, request),
            "export failed: " + request.path +
                ": is one of the study's inputs (the pictures of domain 'real', real/images/); an output written "
                "there would replace it, so nothing is written. Outputs go outside study.yaml, pairs/, review/, "
                ".ipd-cache/ and each domain's labels/, images/ and predictions/ (e.g. into STUDY/figures/)");
  EXPECT_FALSE(fs::exists(request.path));
  request.path = d / "figures/compare.pdf";
  fs::create_directories(d / "figures");
  EXPECT_EQ(ui::export_figure(s, request), "exported " + request.path);
}

// The dialog's proposed file names carry what the figure depends on: two views differing only in model or
// threshold propose different names, so one export never overwrites the other.
TEST(FigureExport, DefaultNamesNameModelAndThreshold) {
  ui::ExportViewContext ctx;
  ctx.base_name = "scene_02_real_principled";
  ctx.model = "det-real", ctx.left = "real", ctx.right = "principled";
  ui::ExportDialogState st;
  const auto name = [&](const std::string& kind) {
    EXPECT_TRUE(ui::set_export_kind(st, kind)) << kind;
    return ui::default_figure_name(st, ctx);
  };
  EXPECT_EQ(name("pairs"), "scene_02_real_principled_det-real_pairs");
  EXPECT_EQ(name("registration"), "scene_02_real_principled_registration");  // GT only
  EXPECT_EQ(name("table"), "table");
  EXPECT_EQ(name("distribution"), "distribution_det-real");
  EXPECT_EQ(name("breakdown-region"), "breakdown_region_det-real_real_principled");
  ctx.conf_threshold = 0.4;
  EXPECT_EQ(name("pairs"), "scene_02_real_principled_det-real_conf0.4_pairs");
  EXPECT_EQ(name("table"), "table_conf0.4");
  EXPECT_EQ(name("distribution"), "distribution_det-real_conf0.4");
  EXPECT_EQ(name("breakdown"), "breakdown_size_det-real_real_principled_conf0.4");
  ctx.ref = "real", ctx.a = "principled", ctx.b = "hapke";
  EXPECT_EQ(name("compare"), "compare_real_principled_hapke_conf0.4");
  ctx.model = "det-hapke";
  EXPECT_EQ(name("pairs"), "scene_02_real_principled_det-hapke_conf0.4_pairs");
}

}  // namespace
}  // namespace ipd
