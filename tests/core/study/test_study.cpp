// Study layout, configuration errors, the Table I layout and the CLI's contract.
#include <gtest/gtest.h>

#include <regex>
#include <sstream>
#include <vector>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "core/ipd/ipd.h"
#include "core/report/table_format.h"
#include "tests/support/test_support.h"

namespace ipd {
namespace {

// Three domains, one scene, one rock each, three models, each trained on one domain.
void write_three_domain_study(const test::TempDir& d) {
  test::write_text(d / "study.yaml",
                   "domains: [real, principled, hapke]\n"
                   "image_size: [1000, 1000]\n"
                   "models:\n  det-real: {trained_on: real}\n  det-principled: {trained_on: principled}\n"
                   "  det-hapke: {trained_on: hapke}\n");
  for (const std::string dom : {"real", "principled", "hapke"}) {
    test::write_text(d / (dom + "/labels/s.txt"), "0 0.5 0.5 0.2 0.2\n");
    for (const std::string m : {"det-real", "det-principled", "det-hapke"})
      test::write_text(d / (dom + "/predictions/" + m + "/s.txt"),
                       dom == "real" ? "0 0.6 0.5 0.2 0.2 0.9\n" : "0 0.5 0.5 0.2 0.2 0.9\n");
  }
}

TEST(TableLayout, ThreeDomainsLikeThePaper) {
  test::TempDir d;
  write_three_domain_study(d);
  const CrossTable t = compute_cross_table(load_labels(open_study(d.path())), {});
  ASSERT_EQ(t.models.size(), 3u);
  EXPECT_EQ(t.models[0].name, "det-real");
  EXPECT_EQ(t.models[1].name, "det-principled");
  EXPECT_EQ(t.models[2].name, "det-hapke");
  using P = std::pair<std::string, std::string>;
  EXPECT_EQ(t.columns, (std::vector<P>{{"real", "principled"}, {"real", "hapke"}, {"principled", "hapke"}}));
  const bool expected[3][3] = {{true, true, false}, {true, false, true}, {false, true, true}};
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) EXPECT_EQ(t.cells[r * 3 + c].involves_training_domain, expected[r][c]) << r << c;
  // real's only rock scores 1/3, the synthetic ones 1: |1/3 - 1| = 2/3 against real, 0 between synthetics.
  EXPECT_NEAR(t.cell("det-real", "real", "hapke")->ipd, 2.0 / 3, 1e-12);
  EXPECT_NEAR(t.cell("det-hapke", "principled", "hapke")->ipd, 0.0, 1e-12);

  const std::string text = format_table(t, TableFormat::kText);
  EXPECT_NE(text.find("|real - principled|"), std::string::npos) << text;
  EXPECT_NE(text.find("det-real (real)"), std::string::npos);
  TableFormatOptions wide;
  wide.latex_wide = true;
  const std::string latex = format_table(t, TableFormat::kLatex, wide);
  const std::string compact = format_table(t, TableFormat::kLatex);
  EXPECT_NE(compact.find("\nA & \\textbf{0.6667} & \\textbf{0.6667} & -- \\\\\n"), std::string::npos) << compact;
  EXPECT_NE(latex.find("det-real (real) & \\textbf{0.6667} & \\textbf{0.6667} & -- \\\\"), std::string::npos) << latex;
  EXPECT_NE(latex.find("det-hapke (hapke) & -- & 0.6667 & \\textbf{0.0000} \\\\"), std::string::npos) << latex;
  const auto j = nlohmann::json::parse(format_table(t, TableFormat::kJson));
  ASSERT_EQ(j["cells"].size(), 9u);
  EXPECT_EQ(j["cells"][2]["a"], "principled");
  EXPECT_EQ(j["cells"][2]["involves_training_domain"], false);
  EXPECT_EQ(j["cells"][0]["pairs"], 1);
  const std::string csv = format_table(t, TableFormat::kCsv);
  EXPECT_NE(csv.find("det-real,real,real,hapke,0.666667,1,0,0,1,true,,,,\n"), std::string::npos) << csv;
}

TEST(Study, ClearErrorsForUnusableStudies) {
  test::TempDir d;
  try {
    open_study(d / "nope");
    FAIL();
  } catch (const StudyError& e) {
    EXPECT_EQ(std::string(e.what()), d / "nope" + ": no such study directory");
  }
  try {
    open_study(d.path());
    FAIL();
  } catch (const StudyError& e) {
    EXPECT_EQ(std::string(e.what()),
              d.path() + ": no domains found (expected subdirectories like real/labels/ with YOLO label files)");
  }
  test::write_text(d / "real/labels/a.txt", "");
  test::write_text(d / "study.yaml", "rock_class: 0\nconf_treshold: 0.3\n");
  try {
    open_study(d.path());
    FAIL();
  } catch (const StudyError& e) {
    EXPECT_EQ(
        std::string(e.what()),
        d / "study.yaml" +
            ":2: unknown setting 'conf_treshold' (expected rock_class, classes, task, conf_threshold, image_size, "
            "domains, models, registration)");
  }
  test::write_text(d / "study.yaml", "registration: {method: icp}\n");
  EXPECT_THROW(open_study(d.path()), StudyError);
  test::write_text(d / "study.yaml", "image_size: [10]\n");
  EXPECT_THROW(open_study(d.path()), StudyError);
  auto message = [&](const std::string& yaml) {
    test::write_text(d / "study.yaml", yaml);
    try {
      open_study(d.path());
    } catch (const StudyError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_EQ(message("[a, b]: 1\n"), d / "study.yaml" + ":1: expected a setting name, found a list");
  EXPECT_EQ(message("models: {m: [1, 2]}\n"),
            d / "study.yaml" + ":1: models.m must be a mapping like {trained_on: real}");
  EXPECT_EQ(message("rock_class: [0\n"), d / "study.yaml" + ":2: invalid YAML: end of sequence flow not found");
}

// study.yaml comes from whoever sent the study: a setting name, method or value of any length is quoted in a
// message as at most 40 characters (37 and "..."), so a megabyte key can't become a megabyte error.
TEST(Study, MessagesQuoteAtMostFortyCharactersOfTheFile) {
  const std::string long_word(1000, 'r');  // YAML's longest plain key is 1024 characters
  const std::string shown = std::string(37, 'r') + "...";
  EXPECT_EQ(test::study_yaml_error(long_word + ": 1\n"),
            "study.yaml:1: unknown setting '" + shown +
                "' (expected rock_class, classes, task, conf_threshold, image_size, domains, models, registration)");
  EXPECT_EQ(
      test::study_yaml_error("registration: {" + long_word + ": 1}\n"),
      "study.yaml:1: unknown registration setting '" + shown + "' (expected method, seed, trials, gate, budget_ms)");
  EXPECT_EQ(test::study_yaml_error("registration: {method: " + long_word + "}\n"),
            "study.yaml:1: unknown registration method '" + shown + "' (expected consensus, paper or cpd)");
  EXPECT_EQ(test::study_yaml_error("registration: {seed: -" + long_word + "}\n"),
            "study.yaml:1: registration.seed must be a whole number from 0 to 18446744073709551615, got -" +
                std::string(36, 'r') + "...");
  EXPECT_EQ(test::study_yaml_error("registration: {gate: " + long_word + "}\n"),
            "study.yaml:1: registration.gate has the wrong type");
}

// A misspelt model setting or `trained_on: null` left the model without its training domain (every cell of
// its row then read as cross-domain), with no message; both are errors naming the line and what is allowed.
TEST(Study, ModelSettingsAreCheckedAtEveryLevel) {
  EXPECT_EQ(test::study_yaml_error("models:\n  det-real:\n    traind_on: real\n"),
            "study.yaml:3: unknown setting 'models.det-real.traind_on' (expected trained_on)");
  EXPECT_EQ(test::study_yaml_error("models: {det: {trained_on: real, epochs: 30}}\n"),
            "study.yaml:1: unknown setting 'models.det.epochs' (expected trained_on)");
  for (const char* empty : {"null", "~", ""})
    EXPECT_EQ(test::study_yaml_error(std::string("models:\n  det:\n    trained_on: ") + empty + "\n"),
              "study.yaml:3: models.det.trained_on is empty (null); expected the name of the domain the model was "
              "trained on (leave the setting out when it is unknown)")
        << empty;
  EXPECT_EQ(test::study_yaml_error("models: {det: {trained_on: ''}}\n"),
            "study.yaml:1: models.det.trained_on is an empty name; expected the name of the domain the model was "
            "trained on (leave the setting out when it is unknown)");
  EXPECT_EQ(test::study_yaml_error("registration: {method: cpd, sed: 3}\n"),
            "study.yaml:1: unknown registration setting 'sed' (expected method, seed, trials, gate, budget_ms)");
  // An entry without a value (`det-principled:`, a line cut short) would silently drop its training domain.
  EXPECT_EQ(test::study_yaml_error("models:\n  det-real: {trained_on: real}\n  det-principled:\n"),
            "study.yaml:3: models.det-principled has no value; expected its settings like {trained_on: real} ({} "
            "when the training domain is unknown)");
  EXPECT_EQ(test::study_yaml_error("models: {a: , b: {}}\n"),
            "study.yaml:1: models.a has no value; expected its settings like {trained_on: real} ({} when the "
            "training domain is unknown)");
  // What stays allowed: a model with empty settings (training domain unknown) and a quoted domain named null.
  const StudyConfig c = parse_study_config("models: {b: {}, c: {trained_on: 'null'}}\n", "study.yaml");
  EXPECT_EQ(c.trained_on.at("c"), "null");
}

// registration.budget_ms is --budget-ms for every registration of the study: a number of milliseconds > 0; anything
// else is an error naming the line, quoting at most 40 characters of what was written.
TEST(Study, RegistrationBudgetIsANumberOfMillisecondsAboveZero) {
  EXPECT_FALSE(parse_study_config("registration: {method: paper}\n", "study.yaml").registration.time_budget_ms);
  EXPECT_EQ(parse_study_config("registration:\n  budget_ms: 12.5\n", "study.yaml").registration.time_budget_ms, 12.5);
  const std::string expected =
      "study.yaml:2: registration.budget_ms must be a number of milliseconds > 0 (unset: no "
      "time limit), got ";
  EXPECT_EQ(test::study_yaml_error("registration:\n  budget_ms: 0\n"), expected + "0");
  EXPECT_EQ(test::study_yaml_error("registration:\n  budget_ms: -3\n"), expected + "-3");
  EXPECT_EQ(test::study_yaml_error("registration:\n  budget_ms: .nan\n"), expected + ".nan");
  EXPECT_EQ(test::study_yaml_error("registration:\n  budget_ms: .inf\n"), expected + ".inf");
  EXPECT_EQ(test::study_yaml_error("registration:\n  budget_ms: [1]\n"), expected + "a list or map");
  // "budget_ms:" with no value is YAML's null, neither a list nor a map.
  EXPECT_EQ(test::study_yaml_error("registration:\n  budget_ms:\n"), expected + "nothing");
  EXPECT_EQ(test::study_yaml_error("registration: {budget_ms: }\n"),
            "study.yaml:1: registration.budget_ms must be a number of "
            "milliseconds > 0 (unset: no time limit), got nothing");
  EXPECT_EQ(test::study_yaml_error("registration:\n  budget_ms: " + std::string(1000, '9') + "x\n"),
            expected + std::string(37, '9') + "...");
}

// study.yaml's registration.trials is the configured method's budget, as ipd register's --trials: cpd's EM
// iterations, the others' trials; below 1 an error naming the line.
TEST(Study, RegistrationTrialsIsTheMethodsBudget) {
  auto c = parse_study_config("registration:\n  trials: 7\n  method: cpd\n", "study.yaml");
  EXPECT_EQ(c.registration.cpd.iterations, 7);
  EXPECT_EQ(c.registration.consensus.max_hypotheses, 1000);
  EXPECT_EQ(c.registration.paper.samples, 1000);
  c = parse_study_config("registration: {method: paper, trials: 5}\n", "study.yaml");
  EXPECT_EQ(c.registration.paper.samples, 5);
  EXPECT_EQ(c.registration.consensus.max_hypotheses, 1000);
  EXPECT_EQ(c.registration.cpd.iterations, 100);
  c = parse_study_config("registration: {trials: 9}\n", "study.yaml");  // consensus, the default method
  EXPECT_EQ(c.registration.consensus.max_hypotheses, 9);
  EXPECT_EQ(c.registration.paper.samples, 1000);
  try {
    parse_study_config("registration:\n  method: cpd\n  trials: 0\n", "study.yaml");
    FAIL();
  } catch (const StudyError& e) {
    EXPECT_EQ(std::string(e.what()), "study.yaml:3: registration.trials must be at least 1, got 0");
  }
}

TEST(Study, ScenesMatchedByStemAndMissingModelsWarned) {
  test::TempDir d;
  write_three_domain_study(d);
  std::filesystem::remove_all(d / "hapke/predictions/det-real");
  const CrossTable t = compute_cross_table(load_labels(open_study(d.path())), {});
  EXPECT_TRUE(t.cell("det-real", "real", "hapke")->missing_predictions);
  EXPECT_TRUE(std::isnan(t.cell("det-real", "real", "hapke")->ipd));
  ASSERT_EQ(t.warnings.size(), 1u);
  EXPECT_EQ(t.warnings[0].rfind("model 'det-real' has no predictions for domain 'hapke'", 0), 0u) << t.warnings[0];
}

TEST(Cli, ExitCodesAndMessages) {
  test::TempDir d;
  write_three_domain_study(d);
  auto r = test::run_ipd("table " + d.path() + " --format json");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(nlohmann::json::parse(r.out)["cells"].size(), 9u);
  r = test::run_ipd("table " + d.path() + " --format nope");
  EXPECT_EQ(r.exit_code, 2);
  r = test::run_ipd("");
  EXPECT_EQ(r.exit_code, 2);
  r = test::run_ipd("table " + d / "missing");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_EQ(r.err, "error: " + d / "missing" + ": no such study directory\n");
  r = test::run_ipd("table " + d.path() + " --model nobody");
  EXPECT_EQ(r.exit_code, 1);
  // Every malformed line, then exit 1; with --skip-bad-lines a warning and the table.
  test::write_text(d / "real/labels/s.txt", "0 0.5 0.5 0.2\n0 0.5 x 0.2 0.2\n0 0.5 0.5 0.2 0.2\n");
  r = test::run_ipd("table " + d.path() + " --out " + d / "table.txt");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find(d / "real/labels/s.txt" + ":1: expected 5 columns (class cx cy w h), found 4"),
            std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find(d / "real/labels/s.txt" + ":2: expected a number for cy in column 3, found 'x'"),
            std::string::npos)
      << r.err;
  EXPECT_FALSE(std::filesystem::exists(d / "table.txt"));  // no half-written output
  r = test::run_ipd("table " + d.path() + " --skip-bad-lines --out " + d / "table.txt");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(std::filesystem::exists(d / "table.txt"));
}

// r.txt: 4 rocks; s.txt: 3 of them shifted by (0.01, 0.01), listed in another order.
void write_register_pair(const test::TempDir& d) {
  test::write_text(d / "r.txt", "0 0.2 0.2 0.05 0.05\n0 0.7 0.3 0.05 0.05\n0 0.4 0.8 0.05 0.05\n0 0.8 0.8 0.05 0.05\n");
  test::write_text(d / "s.txt", "0 0.81 0.81 0.05 0.05\n0 0.21 0.21 0.05 0.05\n0 0.41 0.81 0.05 0.05\n");
  // r.txt with one box a hair wider: the same centres, but not an identical layout, so it is searched.
  test::write_text(d / "r2.txt",
                   "0 0.2 0.2 0.05 0.05\n0 0.7 0.3 0.05 0.05\n0 0.4 0.8 0.05 0.05\n0 0.8 0.8 0.05 0.051\n");
}

TEST(Cli, RegisterPrintsOneJsonObjectPerLine) {
  test::TempDir d;
  write_register_pair(d);
  test::write_text(d / "list.tsv", d / "r.txt" + "\t" + d / "s.txt" + "\n" + d / "s.txt" + "\t" + d / "r.txt" + "\n");
  auto r = test::run_ipd("register --list " + d / "list.tsv" + " --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::istringstream lines(r.out);
  std::string first, second;
  std::getline(lines, first);
  std::getline(lines, second);
  const auto j = nlohmann::json::parse(first);
  EXPECT_EQ(j["real"], d / "r.txt");
  EXPECT_EQ(j["pairs"], nlohmann::json::parse("[[0,1],[2,2],[3,0]]"));
  EXPECT_EQ(j["affine"].size(), 2u);
  EXPECT_EQ(j["affine"][0].size(), 3u);
  EXPECT_NEAR(j["affine"][0][2].get<double>(), 0.01, 1e-6);
  EXPECT_TRUE(j.contains("trials"));
  EXPECT_TRUE(j.contains("score"));
  EXPECT_EQ(nlohmann::json::parse(second)["real"], d / "s.txt");
  r = test::run_ipd("register " + d / "r.txt");
  EXPECT_EQ(r.exit_code, 2);
  r = test::run_ipd("register " + d / "r.txt " + d / "none.txt");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_EQ(r.err, d / "none.txt" + ": no such label file\n");
}

// A misspelt domain or model is refused with the names the study has, so the fix is one look away.
TEST(Cli, AnUnknownDomainOrModelListsTheStudysOwn) {
  test::TempDir d;
  ASSERT_EQ(test::run_ipd("demo " + d / "s --labels-only --scenes 2 --rocks 8").exit_code, 0);
  auto r = test::run_ipd("figure pairs " + d / "s --a real --b hapkee --out " + d / "p.pdf");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find(d / "s" + ": no domain 'hapkee' in this study (the study's domains: real, principled, hapke)"),
            std::string::npos)
      << r.err;
  r = test::run_ipd("table " + d / "s --model det-rea");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find(d / "s" +
                       ": no model 'det-rea' (no <domain>/predictions/det-rea/ directory and not in study.yaml; the "
                       "study's models: det-real, det-principled, det-hapke)"),
            std::string::npos)
      << r.err;
}

// Under a budget the text report says how long the registration took and how much of it was the final pairing,
// which the budget cannot end; the JSON carries the same two times.
TEST(Cli, ABudgetedRegistrationSaysWhatPartTheFinalPairingTook) {
  test::TempDir d;
  write_register_pair(d);
  auto r = test::run_ipd("register " + d / "r.txt " + d / "s.txt --budget-ms 5000 --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_GT(j["pairing_ms"].get<double>(), 0);
  EXPECT_LE(j["pairing_ms"].get<double>(), j["elapsed_ms"].get<double>());
  r = test::run_ipd("register " + d / "r.txt " + d / "s.txt --budget-ms 5000");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find(" ms of a 5000 ms budget, the final pairing "), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("cannot end it"), std::string::npos) << r.out;  // within the budget: nothing to explain
  r = test::run_ipd("register " + d / "r.txt " + d / "s.txt");
  EXPECT_EQ(r.out.find("time: "), std::string::npos) << r.out;  // no budget, no time line: the output stays the same
}

// --json names each count as the text report does: cpd counts EM iterations (it has no trials or hypotheses),
// paper and consensus count trials and hypotheses; the score carries the measure it is in (a distance or width is
// better lower, a soft inlier count higher), null both where nothing was scored.
TEST(Cli, RegisterJsonNamesItsCountsAsTheTextDoes) {
  test::TempDir d;
  write_register_pair(d);
  auto r = test::run_ipd("register " + d / "r.txt " + d / "s.txt --method cpd --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  auto j = nlohmann::json::parse(r.out);
  std::string keys;
  for (const auto& [key, value] : j.items()) keys += key + " ";
  EXPECT_EQ(
      keys,
      "affine ambiguous confidence elapsed_ms em_iterations inliers method pairing_ms pairs real score score_measure "
      "stop synth work work_budget ");
  EXPECT_EQ(j["em_iterations"], 6);
  EXPECT_EQ(j["score_measure"], "mixture_width");
  r = test::run_ipd("register " + d / "r.txt " + d / "s.txt --method cpd");
  EXPECT_NE(r.out.find("  method cpd: 6 EM iterations, mixture width below 0.00001; stopped: "), std::string::npos)
      << r.out;
  j = nlohmann::json::parse(test::run_ipd("register " + d / "r.txt " + d / "s.txt --method paper --json").out);
  EXPECT_EQ(j["trials"], 1000);
  EXPECT_EQ(j["hypotheses"], 6000);
  EXPECT_EQ(j["score_measure"], "mean_distance");
  EXPECT_FALSE(j.contains("em_iterations"));
  j = nlohmann::json::parse(test::run_ipd("register " + d / "r.txt " + d / "r2.txt --json").out);
  EXPECT_EQ(j["method"], "consensus");
  EXPECT_EQ(j["trials"], 1);
  EXPECT_EQ(j["hypotheses"], 1);
  EXPECT_EQ(j["score_measure"], "soft_inliers");
  EXPECT_NEAR(j["score"].get<double>(), 3.99843, 5e-6);
  EXPECT_FALSE(j.contains("em_iterations"));
  j = nlohmann::json::parse(test::run_ipd("register " + d / "r.txt " + d / "r.txt --json").out);
  EXPECT_TRUE(j["score"].is_null());  // identical layouts: no search, no score
  EXPECT_TRUE(j["score_measure"].is_null());
}

// An ambiguous registration says so after its confidence, the reason's "(e.g. ...)" not nested in another
// parenthesis (it read "confidence 0.186 (AMBIGUOUS: ... as well (e.g. a small overlap or a repetitive
// layout))"). A 3 x 3 block of identical rocks inside a 5 x 5 grid: nine placements fit equally well.
TEST(Cli, RegisterSaysAmbiguousWithoutNestedParentheses) {
  test::TempDir d;
  std::string a, b;
  for (int y = 0; y < 5; ++y)
    for (int x = 0; x < 5; ++x) {
      a += fmt::format("0 {:.2f} {:.2f} 0.04 0.04\n", 0.1 + 0.2 * x, 0.1 + 0.2 * y);
      if (x >= 1 && x <= 3 && y >= 1 && y <= 3)
        b += fmt::format("0 {:.2f} {:.2f} 0.04 0.04\n", 0.11 + 0.2 * x, 0.1 + 0.2 * y);
    }
  test::write_text(d / "a.txt", a);
  test::write_text(d / "b.txt", b);
  const auto r = test::run_ipd("register " + d / "a.txt " + d / "b.txt");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(
      r.out.find("; AMBIGUOUS: another alignment fits as well or almost as well (e.g. a small overlap or a repetitive "
                 "layout)\n"),
      std::string::npos)
      << r.out;
  EXPECT_EQ(r.out.find("))"), std::string::npos) << r.out;
}

// --trials is each method's own search budget, as its help says: cpd's EM iterations (so cpd stops
// where --trials says, not after its own 12), paper's K samples; below 1 it is a usage error, not the default.
TEST(Cli, RegisterTrialsIsEachMethodsBudget) {
  test::TempDir d;
  write_register_pair(d);
  EXPECT_NE(test::run_ipd("register --help")
                .out.find("Search budget: paper: K samples (default 1000); consensus: "
                          "hypothesis cap (default 1000); cpd: EM iterations (default 100)"),
            std::string::npos);
  auto j = nlohmann::json::parse(test::run_ipd("register " + d / "s.txt " + d / "r.txt --method cpd --json").out);
  EXPECT_EQ(j["em_iterations"], 12);  // converges within the default 100
  EXPECT_EQ(j["stop"], "converged");
  auto r = test::run_ipd("register " + d / "s.txt " + d / "r.txt --method cpd --trials 7 --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["em_iterations"], 7);
  EXPECT_EQ(j["stop"], "reached the trial limit");
  j = nlohmann::json::parse(
      test::run_ipd("register " + d / "r.txt " + d / "s.txt --method paper --trials 5 --json").out);
  EXPECT_EQ(j["trials"], 5);
  EXPECT_EQ(j["hypotheses"], 30);  // each sample in all 6 orders
  // --trials 0 is refused by the method's own budget field (RegistrationOptions::validate).
  const std::pair<const char*, const char*> refusals[] = {
      {"cpd", "--trials: cpd.iterations must be at least 1, got 0"},
      {"paper", "--trials: paper.samples must be at least 1, got 0"},
      {"consensus", "--trials: consensus.max_hypotheses must be at least 1, got 0"}};
  for (const auto& [method, message] : refusals) {
    r = test::run_ipd("register " + d / "r.txt " + d / "s.txt --trials 0 --method " + method);
    EXPECT_EQ(r.exit_code, 2) << method;
    EXPECT_NE(r.err.find(message), std::string::npos) << method << ": " << r.err;
  }
}

// --list prints what its help says: one report per pair in the file's order (blank and # lines skipped), as
// text or, with --json, one object per line; a pair that fails is an {real, synth, error} object (and the
// error on stderr).
TEST(Cli, RegisterListPrintsWhatItsHelpSays) {
  test::TempDir d;
  write_register_pair(d);
  test::write_text(d / "list.tsv", d / "s.txt" + "\t" + d / "r.txt" + "\n# a comment\n\n" + d / "r.txt" + "\t" +
                                       d / "none.txt" + "\n" + d / "r.txt" + "\t" + d / "s.txt" + "\n");
  EXPECT_NE(
      test::run_ipd("register --help")
          .out.find(
              "TSV file of real_path<TAB>synth_path lines (blank and # lines skipped); prints one report per pair, "
              "in the file's order: text, or with --json one JSON object per line (a pair that fails: {real, "
              "synth, error})"),
      std::string::npos);
  auto r = test::run_ipd("register --list " + d / "list.tsv");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_EQ(r.err.find(d / "none.txt: no such label file\n"), 0u) << r.err;
  std::istringstream text(r.out);
  std::vector<std::string> titles;  // the two reports' titles; every other line is indented, none for the failed pair
  for (std::string line; std::getline(text, line);)
    if (line.rfind("  ", 0) != 0) titles.push_back(line);
  EXPECT_EQ(titles, (std::vector<std::string>{d / "s.txt -> " + d / "r.txt", d / "r.txt -> " + d / "s.txt"})) << r.out;
  r = test::run_ipd("register --list " + d / "list.tsv --json");
  EXPECT_EQ(r.exit_code, 1);
  std::istringstream lines(r.out);
  std::vector<nlohmann::json> objects;
  for (std::string line; std::getline(lines, line);) objects.push_back(nlohmann::json::parse(line));
  ASSERT_EQ(objects.size(), 3u) << r.out;
  EXPECT_EQ(objects[0]["real"], d / "s.txt");
  EXPECT_EQ(objects[1],
            nlohmann::json(
                {{"real", d / "r.txt"}, {"synth", d / "none.txt"}, {"error", d / "none.txt: no such label file"}}));
  EXPECT_EQ(objects[2]["real"], d / "r.txt");
  EXPECT_EQ(objects[2]["pairs"], nlohmann::json::parse("[[0,1],[2,2],[3,0]]"));
}

// The text report says what each count counts, in plain numbers: centres within the gate vs the pairs the
// method forms (how), "1 trial" in the singular, thousands separators (no "1.01e+06"), no "-0.00000", the fit under
// its measure's name, and no score where nothing was scored (a 0 read as a perfect fit).
TEST(Cli, RegisterTextSaysWhatEachCountCounts) {
  test::TempDir d;
  write_register_pair(d);
  auto r = test::run_ipd("register " + d / "r.txt " + d / "r.txt");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("  method consensus: 0 trials, 0 hypotheses, not scored; stopped: identical layouts (no search "
                       "needed)\n"),
            std::string::npos)
      << r.out;
  r = test::run_ipd("register " + d / "r.txt " + d / "r2.txt");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("  method consensus: 1 trial, 1 hypothesis, soft inliers 3.99843; stopped: "), std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find("\n  4 centres within the gate; 4 pairs by aligned-box IoU (one-to-one)\n"), std::string::npos)
      << r.out;
  EXPECT_TRUE(std::regex_search(
      r.out,
      std::regex(R"(\n  work: 4 of \d{1,3}(,\d{3})+ point evaluations \(the bound for this many rocks\); confidence)")))
      << r.out;
  EXPECT_NE(r.out.find("[1.00000 0.00000 0.00000; 0.00000 1.00000 0.00000]"), std::string::npos) << r.out;
  // Without --image-size it says what it assumed (ipd-studio and ipd table take the size from study.yaml).
  EXPECT_NE(r.err.find("note: pictures taken as square (aspect 1); --image-size W,H measures angles in pixels"),
            std::string::npos)
      << r.err;
  EXPECT_EQ(test::run_ipd("register " + d / "r.txt " + d / "r.txt --image-size 960,600").err.find("note: pictures"),
            std::string::npos);
  r = test::run_ipd("register " + d / "r.txt " + d / "s.txt --method paper");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("  method paper: 1,000 trials, 6,000 hypotheses, "), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("\n  3 centres within the gate; 3 pairs by mutual nearest neighbour\n"), std::string::npos)
      << r.out;
  EXPECT_EQ(r.out.find("e+"), std::string::npos) << r.out;
}

// `ipd table` states the prediction threshold it used and which scenes' registrations were ambiguous (the
// paper method cannot tell the 4-rock and 3-rock layouts above apart: confidence 0.000).
TEST(Cli, TableNamesTheThresholdAndTheAmbiguousRegistrations) {
  test::TempDir d;
  test::write_text(d / "study.yaml", "domains: [real, synth]\nmodels: {det: {trained_on: real}}\n");
  test::write_text(d / "real/labels/s1.txt",
                   "0 0.2 0.2 0.05 0.05\n0 0.7 0.3 0.05 0.05\n0 0.4 0.8 0.05 0.05\n0 0.8 0.8 0.05 0.05\n");
  test::write_text(d / "synth/labels/s1.txt", "0 0.81 0.81 0.05 0.05\n0 0.21 0.21 0.05 0.05\n0 0.41 0.81 0.05 0.05\n");
  test::write_text(d / "real/predictions/det/s1.txt", "0 0.2 0.2 0.05 0.05 0.9\n");
  test::write_text(d / "synth/predictions/det/s1.txt", "0 0.81 0.81 0.05 0.05 0.4\n");
  auto r = test::run_ipd("table " + d.path() + " --method paper --bootstrap 0 --conf 0.3");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("\nPredictions with confidence below 0.3 dropped (--conf, else study.yaml's conf_threshold).\n"),
            std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find("\n1 scene: registration ambiguous (see ipd-studio '?'); --verbose lists them\n"),
            std::string::npos)
      << r.out;
  r = test::run_ipd("table " + d.path() + " --method paper --bootstrap 0 --verbose");
  EXPECT_EQ(r.out.find("Predictions with confidence below"), std::string::npos) << r.out;  // none dropped
  EXPECT_NE(
      r.out.find("\n1 scene: registration ambiguous (see ipd-studio '?'):\n  real vs synth: s1: another alignment "
                 "fits as well or almost as well (e.g. a small overlap or a repetitive layout)\n"),
      std::string::npos)
      << r.out;
  r = test::run_ipd("table " + d.path() + " --method paper --bootstrap 0 --format csv");  // CSV stays CSV
  EXPECT_EQ(r.out.find("ambiguous"), std::string::npos) << r.out;
  EXPECT_NE(r.err.find("note: 1 scene: registration ambiguous"), std::string::npos) << r.err;
}

// A registration the time budget ended keeps its best so far: the table says how many, and under which budget,
// since its pairs may differ on another machine. --budget-ms overrides study.yaml's (0: no limit).
TEST(Cli, TableNamesTheScenesTheTimeBudgetEnded) {
  test::TempDir d;
  test::write_text(d / "study.yaml", "domains: [real, synth]\nregistration: {budget_ms: 0.000001}\n");
  const std::string rocks = "0 0.2 0.2 0.05 0.05\n0 0.7 0.3 0.06 0.05\n0 0.4 0.8 0.05 0.07\n0 0.8 0.8 0.04 0.05\n";
  test::write_text(d / "real/labels/s1.txt", rocks);
  test::write_text(d / "real/labels/s2.txt", rocks);
  test::write_text(d / "synth/labels/s1.txt", "0 0.21 0.2 0.05 0.05\n0 0.71 0.3 0.06 0.05\n0 0.41 0.8 0.05 0.07\n");
  test::write_text(d / "synth/labels/s2.txt", "0 0.2 0.21 0.05 0.05\n0 0.7 0.31 0.06 0.05\n0 0.4 0.81 0.05 0.07\n");
  for (const char* f : {"real/predictions/det/s1.txt", "real/predictions/det/s2.txt", "synth/predictions/det/s1.txt",
                        "synth/predictions/det/s2.txt"})
    test::write_text(d / f, "0 0.2 0.2 0.05 0.05 0.9\n");
  const std::string note =
      "\n2 registrations (a scene in a domain pair) ended by the time budget of 1e-06 ms (--budget-ms, else "
      "study.yaml's registration.budget_ms); their pairs may differ on another machine or run (a larger budget, or "
      "0 for none, lets the search finish)\n";
  auto r = test::run_ipd("table " + d.path() + " --bootstrap 0 --no-cache");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find(note), std::string::npos) << r.out;
  r = test::run_ipd("table " + d.path() + " --bootstrap 0 --no-cache --budget-ms 0");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.out.find("time budget"), std::string::npos) << r.out;
  r = test::run_ipd("table " + d.path() + " --bootstrap 0 --no-cache --budget-ms 0.000002");
  EXPECT_NE(r.out.find("\n2 registrations (a scene in a domain pair) ended by the time budget of 2e-06 ms"),
            std::string::npos)
      << r.out;
  for (const char* bad : {"-1", "nan", "inf"}) {
    r = test::run_ipd("table " + d.path() + " --budget-ms " + bad);
    EXPECT_EQ(r.exit_code, 2) << bad;
    EXPECT_NE(r.err.find(std::string("--budget-ms: must be a number of milliseconds >= 0 (0: no limit), got ") + bad),
              std::string::npos)
        << r.err;
  }
}

}  // namespace
}  // namespace ipd

namespace ipd {
namespace {
// A study's label paths are built from its folders (one fs::path join a folder, a string append a file): the
// same text fs::path gives, whether the root ends in a slash or not.
TEST(Study, LabelPathsAreTheirFolderJoinedWithTheStem) {
  for (const std::string root : {"/data/polar", "/data/polar/", "rel"}) {
    Study s;
    s.root = root;
    const std::string base = root.back() == '/' ? root : root + "/";
    EXPECT_EQ(s.label_path("real", "scene_01"), base + "real/labels/scene_01.txt");
    EXPECT_EQ(s.prediction_path("real", "det-real", "scene_01"), base + "real/predictions/det-real/scene_01.txt");
    EXPECT_EQ(s.label_folder("real"), base + "real/labels");
    EXPECT_EQ(Study::label_file(s.prediction_folder("hapke", "m"), "x"), base + "hapke/predictions/m/x.txt");
  }
}
}  // namespace
}  // namespace ipd

namespace ipd {
namespace {
// A scene is a `<stem>.txt`: the stem keeps its inner dots, a hidden `.txt` is no scene, classes.txt holds class
// names, and a `.TXT` is refused naming it (its boxes would otherwise silently count as none).
TEST(Study, ScenesAreTheLowerCaseTxtFilesByTheirStems) {
  test::TempDir d;
  for (const char* f : {"real/labels/s.1.txt", "real/labels/.txt", "real/labels/classes.txt", "real/labels/s2.txt",
                        "real/labels/notes.md"})
    test::write_text(d / f, "");
  const Study s = open_study(d.path());
  EXPECT_EQ(s.domains.at(0).stems, (std::vector<std::string>{"s.1", "s2"}));
  test::write_text(d / "real/labels/s3.TXT", "");
  try {
    open_study(d.path());
    ADD_FAILURE() << "a .TXT file was read";
  } catch (const StudyError& e) {
    EXPECT_EQ(std::string(e.what()),
              d.path() + "/real/labels/s3.TXT: only lower-case .txt label files are read; rename it to s3.txt");
  }
}
}  // namespace
}  // namespace ipd
