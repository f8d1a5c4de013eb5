// Provenance on figures: the note of core/report/provenance.h under the figure when something was edited by
// hand, and the fingerprint always in the file's metadata (PDF Subject, SVG <desc>, PNG text chunk).
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <tuple>

#include "core/report/provenance.h"
#include "core/session/session.h"
#include "tests/support/pdf_text.h"
#include "tests/support/test_support.h"
#include "ui/canvas/png_text.h"
#include "ui/figures/figure_export.h"
#include "ui/figures/figure_input.h"
#include "ui/figures/figure_provenance.h"

namespace ipd {
namespace {

// As test_provenance.cpp: real rock 0 paired by hand with synth rock 1, real rock 1 left out.
void write_hand_pairs_figure_provenance(const test::TempDir& d) {
  test::write_text(d / "pairs/real__synth/s1.json", R"({"pairs": [[0, 1]], "excluded_a": [1],)"
                                                    R"( "rocks_a": [[0, 0.2, 0.2, 0.1, 0.1], [1, 0.6, 0.6, 0.1, 0.1]],)"
                                                    R"( "rocks_b": [[1, 0.2, 0.2, 0.1, 0.1]]})");
}

std::string read_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

const char* const kEdited = "Label files d189a61c07b5; hand pairs in 1 scene (1 pair set by hand, 1 rock excluded).";
const char* const kAutomatic = "Label files d189a61c07b5; no hand pairs (every pair from registration).";

// Every kind of `ipd figure` prints the note under the figure once a pair is set by hand; below every other
// text (it never covers a label) and at a printable size.
TEST(FigureProvenance, EditedStudyShowsTheNoteUnderEveryKind) {
  test::TempDir d;
  test::write_two_rock_study(d);
  write_hand_pairs_figure_provenance(d);
  for (const std::string kind : {"pairs", "registration", "table", "distribution", "breakdown", "gallery"}) {
    SCOPED_TRACE(kind);
    const std::string out = d / (kind + ".pdf");
    const auto r = test::run_ipd("figure " + kind + " " + d.path() + " --out " + out +
                                 (kind == "pairs" || kind == "registration" ? "" : " --no-cache"));
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const test::PdfText t = test::pdf_text(out);
    EXPECT_NE(t.all().find(kEdited), std::string::npos) << t.all();
    double note_top = 1e9, others_bottom = 0;
    for (const test::Word& w : t.words) {
      if (w.text == "d189a61c07b5;") note_top = std::min(note_top, w.y0);
    }
    for (const test::Word& w : t.words)
      if (w.y1 < note_top - 0.5) others_bottom = std::max(others_bottom, w.y1);
    EXPECT_GT(note_top, others_bottom);
    EXPECT_TRUE(test::overlapping(t).empty());
    const auto info = test::run_command("pdfinfo '" + out + "'");
    const size_t subject = info.out.find("Subject:");
    ASSERT_NE(subject, std::string::npos) << info.out;
    EXPECT_EQ(info.out.substr(subject, info.out.find('\n', subject) - subject).find(kEdited) != std::string::npos, true)
        << info.out;
  }
}

// A scene figure carries its scene's review marks, as the table's note does: scene s1 reviewed, its one
// pair checked as correct.
TEST(FigureProvenance, SceneFiguresCarryTheScenesReviewMarks) {
  test::TempDir d;
  test::write_two_rock_study(d);
  write_hand_pairs_figure_provenance(d);
  test::write_text(d / "review/real__synth.json",
                   R"({"reviewed": ["s1"], "checked": [)"
                   R"({"scene": "s1", "rock_a": [0.2, 0.2, 0.1, 0.1], "rock_b": [0.2, 0.2, 0.1, 0.1]}]})");
  for (const std::string kind : {"pairs", "registration"}) {
    SCOPED_TRACE(kind);
    const std::string out = d / (kind + ".pdf");
    const auto r = test::run_ipd("figure " + kind + " " + d.path() + " --out " + out);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(test::pdf_text(out).all().find("Label files d189a61c07b5; hand pairs in 1 scene (1 pair set by hand, 1 "
                                             "rock excluded); 1 scene reviewed, 1 pair checked as correct."),
              std::string::npos)
        << test::pdf_text(out).all();
  }
}

// A scene whose hand pairs are set aside as stale (a stored rock left its label file) is drawn with
// registration's pairs; its figure says so, from the command line and from the studio alike.
TEST(FigureProvenance, ASceneWithStaleHandPairsSaysTheyWereNotUsed) {
  test::TempDir d;
  test::write_two_rock_study(d);
  write_hand_pairs_figure_provenance(d);
  test::write_text(d / "synth/labels/s1.txt", "0 0.6 0.6 0.1 0.1\n0 0.3 0.2 0.1 0.1\n");  // synth rock 2 moved
  const std::string out = d / "pairs.pdf";
  const auto r = test::run_ipd("figure pairs " + d.path() + " --skip-bad-lines --out " + out);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(test::pdf_words(out).find("stale hand pairs not used in 1 scene (registration counts there)."),
            std::string::npos)
      << test::pdf_words(out);
  const Session s = Session::open(d.path());
  EXPECT_TRUE(ui::scene_input_from_session(s, 0).pairs_stale);
}

// Nothing edited: no note on the page, the fingerprint in the metadata of PDF, SVG and PNG alike.
TEST(FigureProvenance, AutomaticStudyKeepsTheFingerprintInTheMetadataOnly) {
  test::TempDir d;
  test::write_two_rock_study(d);
  auto r = test::run_ipd("figure table " + d.path() + " --no-cache --out " + (d / "t.pdf"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(test::pdf_words(d / "t.pdf").find("Label files"), std::string::npos);
  EXPECT_NE(test::run_command("pdfinfo '" + (d / "t.pdf") + "'").out.find(kAutomatic), std::string::npos);
  r = test::run_ipd("figure table " + d.path() + " --no-cache --out " + (d / "t.svg"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(read_bytes(d / "t.svg").find(std::string("<desc>") + kAutomatic + "</desc>"), std::string::npos);
  r = test::run_ipd("figure table " + d.path() + " --no-cache --out " + (d / "t.png"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(ui::png_text(read_bytes(d / "t.png"), "Description"), kAutomatic);
  // The chunk is valid PNG: ImageMagick reads it back.
  const auto id = test::run_command("identify -verbose '" + (d / "t.png") + "'");
  EXPECT_NE(id.out.find(std::string("Description: ") + kAutomatic), std::string::npos) << id.out << id.err;
}

// A breakdown of synth vs other reported real vs synth's hand pairs (the whole table's), while
// `ipd breakdown` of that cell said "no hand pairs": a figure counts the hand pairs of what it draws, from the
// command line and from the studio alike.
TEST(FigureProvenance, ACellsFigureCountsTheHandPairsOfItsCellOnly) {
  test::TempDir d;
  test::write_two_rock_study(d);
  test::write_text(d / "other/labels/s1.txt", "0 0.6 0.6 0.1 0.1\n0 0.2 0.2 0.1 0.1\n");
  test::write_text(d / "other/predictions/det/s1.txt", "0 0.25 0.2 0.1 0.1 0.8\n");
  write_hand_pairs_figure_provenance(d);
  const std::string fingerprint = "Label files " + label_set_fingerprint(open_study(d.path())) + "; ";
  const std::string none = fingerprint + "no hand pairs (every pair from registration).";
  const std::string edited = fingerprint + "hand pairs in 1 scene (1 pair set by hand, 1 rock excluded).";
  // (The gallery takes its cell from --domains, which limits the table to that pair as well.)
  for (const auto& [a, b, note] : {std::make_tuple("synth", "other", none), std::make_tuple("real", "synth", edited)}) {
    const std::string out = d / ("breakdown-" + std::string(a) + ".svg");
    const auto r = test::run_ipd("figure breakdown " + d.path() + " --bootstrap 0 --no-cache --a " + a + " --b " + b +
                                 " --out " + out);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(read_bytes(out).find("<desc>" + note + "</desc>"), std::string::npos) << a << " " << b;
  }
  Session s = Session::open(d.path());
  ASSERT_TRUE(s.select_domains("synth", "other"));
  ui::ExportRequest req;
  req.kind = "breakdown";
  req.path = d / "studio.svg";
  EXPECT_EQ(ui::export_figure(s, req), "exported " + req.path);
  EXPECT_NE(read_bytes(req.path).find("<desc>" + none + "</desc>"), std::string::npos);
}

// add_provenance on its own: the page grows by the note, which sits below the old bottom margin.
TEST(FigureProvenance, TheNoteGrowsThePageBelowTheFigure) {
  const ui::FontMetrics metrics(ui::default_font_file());
  ui::DisplayList fig(metrics);
  fig.text({4, 4}, ui::Anchor::kTopLeft, {8, ui::rgb(0, 0, 0), false}, "figure");
  fig.width_pt = 252, fig.height_pt = 20;
  ui::add_provenance(fig, scene_provenance(false, 3, 0, "0123456789ab"), {});
  EXPECT_EQ(fig.height_pt, 20);
  EXPECT_EQ(fig.description, "Label files 0123456789ab; no hand pairs (every pair from registration).");
  ui::add_provenance(fig, scene_provenance(true, 3, 0, "0123456789ab"), {});
  EXPECT_GT(fig.height_pt, 20);
  const auto texts = fig.texts();
  ASSERT_GE(texts.size(), 2u);
  std::string note;  // wrapped to the page's width
  for (size_t k = 1; k < texts.size(); ++k) {
    note += (k > 1 ? " " : "") + texts[k].text;
    EXPECT_GE(texts[k].box.y0, 16);  // below the old content's bottom margin
    EXPECT_GE(texts[k].size_pt, 7);
    EXPECT_LE(texts[k].box.x1, 248);
  }
  EXPECT_EQ(note, "Label files 0123456789ab; hand pairs in 1 scene (3 pairs set by hand, 0 rocks excluded).");
}

// The text chunk itself: inserted after IHDR with a correct CRC (identify above), read back by keyword.
TEST(FigureProvenance, PngTextChunkRoundTrips) {
  EXPECT_THROW(ui::png_with_text("not a png", "Description", "x"), std::invalid_argument);
}

}  // namespace
}  // namespace ipd
