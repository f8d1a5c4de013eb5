// Inputs that could give a wrong or silently changed number: label files in another case, duplicate JSON keys,
// names that are not UTF-8, CSV fields with commas, options out of range (COCO imports:
// test_coco_input_checks.cpp). Each is an error naming the file (and line).
#include <gtest/gtest.h>

#include <filesystem>

#include "core/report/csv.h"
#include "core/report/table_format.h"
#include "core/stats/study_statistics.h"
#include "core/study/study.h"
#include "core/util/errors.h"
#include "core/util/json_input.h"
#include "core/util/json_output.h"
#include "core/util/number_text.h"
#include "tests/support/test_support.h"

namespace ipd {
namespace {

namespace fs = std::filesystem;

void write_tiny_study_input_checks(const test::TempDir& d) {
  test::write_text(d / "real/labels/s1.txt", "0 0.2 0.2 0.1 0.1\n0 0.6 0.6 0.1 0.1\n");
  test::write_text(d / "synth/labels/s1.txt", "0 0.6 0.6 0.1 0.1\n0 0.2 0.2 0.1 0.1\n");
  test::write_text(d / "real/predictions/det/s1.txt", "0 0.2 0.2 0.1 0.1 0.9\n0 0.65 0.6 0.1 0.1 0.4\n");
  test::write_text(d / "synth/predictions/det/s1.txt", "0 0.25 0.2 0.1 0.1 0.8\n");
}

// --- whole-text numbers -------------------------------------------------------------------------------------

TEST(NumberText, TheWholeTextIsTheNumber) {
  double v = -1;
  EXPECT_TRUE(parse_decimal("0.25", &v));
  EXPECT_EQ(v, 0.25);
  EXPECT_TRUE(parse_decimal("-.5e1", &v));
  EXPECT_EQ(v, -5.0);
  EXPECT_FALSE(parse_decimal(std::string("0.20\0", 5), &v));
  EXPECT_FALSE(parse_decimal("0.2 ", &v));
  EXPECT_FALSE(parse_decimal(" 0.2", &v));
  EXPECT_FALSE(parse_decimal("0x10", &v));
  EXPECT_FALSE(parse_decimal("1e", &v));
  EXPECT_FALSE(parse_decimal("", &v));
  EXPECT_FALSE(parse_decimal("nan", &v));
  EXPECT_EQ(v, -5.0);  // untouched by a refusal
  long long n = 0;
  EXPECT_TRUE(parse_integer("42", 1, 100, &n));
  EXPECT_EQ(n, 42);
  EXPECT_FALSE(parse_integer(std::string("5\0", 2), 1, 100, &n));
  EXPECT_FALSE(parse_integer("0", 1, 100, &n));
  EXPECT_FALSE(parse_integer("-", -5, 5, &n));
  EXPECT_FALSE(parse_integer("99999999999999999999", 1, 100, &n));
  EXPECT_EQ(quoted_for_message(std::string("a\0b\x1b\xff", 5)), "a\\x00b\\x1B\\xFF");
  std::uint64_t seed = 7;
  EXPECT_TRUE(parse_seed("18446744073709551615", &seed));
  EXPECT_EQ(seed, 18446744073709551615ull);
  EXPECT_TRUE(parse_seed("0", &seed));
  EXPECT_EQ(seed, 0u);
  EXPECT_FALSE(parse_seed("18446744073709551616", &seed));
  EXPECT_FALSE(parse_seed("99999999999999999999", &seed));
  EXPECT_FALSE(parse_seed("-1", &seed));
  EXPECT_FALSE(parse_seed("+1", &seed));
  EXPECT_FALSE(parse_seed("", &seed));
  EXPECT_EQ(seed, 0u);  // untouched by a refusal
}

// --- label files in another case ----------------------------------------------------------------------------

// 0001.TXT was skipped without a word and its scene read as "no rocks"; next to a 0001.txt it would be
// ambiguous which one counts. Only lower-case .txt is read; any other case is an error naming the file.
TEST(InputChecks, LabelFilesInAnotherCaseAreRefusedByName) {
  test::TempDir d;
  write_tiny_study_input_checks(d);
  test::write_text(d / "real/labels/s2.TXT", "0 0.5 0.5 0.1 0.1\n");
  EXPECT_EQ(test::open_study_error(d.path()),
            d / "real/labels/s2.TXT" + ": only lower-case .txt label files are read; rename it to s2.txt");
  fs::rename(d / "real/labels/s2.TXT", d / "real/labels/s1.Txt");
  EXPECT_EQ(test::open_study_error(d.path()),
            d / "real/labels/s1.Txt" +
                ": s1.txt holds this scene's boxes too, and only lower-case .txt files are "
                "read; remove or merge one of them");
  fs::remove(d / "real/labels/s1.Txt");
  // A prediction file in another case would read as "the detector found nothing" in that scene.
  test::write_text(d / "synth/predictions/det/S1.TXT", "0 0.25 0.2 0.1 0.1 0.8\n");
  EXPECT_EQ(test::open_study_error(d.path()),
            d / "synth/predictions/det/S1.TXT" + ": only lower-case .txt label files are read; rename it to S1.txt");
  fs::remove(d / "synth/predictions/det/S1.TXT");
  // Two pictures of one scene: which one is shown depended on the directory's order.
  test::write_text(d / "real/images/s1.png", "");
  test::write_text(d / "real/images/s1.jpg", "");
  EXPECT_EQ(test::open_study_error(d.path()),
            d / "real/images/s1.png" + ": s1.jpg is a picture of this scene too; keep one of them");
  fs::remove(d / "real/images/s1.jpg");
  EXPECT_EQ(test::open_study_error(d.path()), "no error");
  // classes.txt (written by ipd import coco) is not a scene.
  test::write_text(d / "real/labels/classes.txt", "rock\n");
  EXPECT_EQ(open_study(d.path()).domain("real")->stems, std::vector<std::string>{"s1"});
  const auto r = test::run_ipd("table " + d.path() + " --bootstrap 0");
  EXPECT_EQ(r.exit_code, 0) << r.err;
}

// --- duplicate keys in JSON ---------------------------------------------------------------------------------

// nlohmann keeps the last of two equal keys: {"pairs": [...], "pairs": [...]} silently dropped the first
// list of hand pairs.
TEST(InputChecks, DuplicateJsonKeysAreAnErrorNamingFileAndKey) {
  const std::string expected = "{\"pairs\": [[i, j], ...]}";
  auto message = [&](const std::string& text) {
    try {
      parse_json_input(text, "p.json", expected, 16);
    } catch (const StudyError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_EQ(
      message("{\"pairs\": [[0, 1]], \"pairs\": [[1, 0]]}"),
      "p.json: duplicate key \"pairs\" in one object (a JSON reader keeps only one of them); expected " + expected);
  EXPECT_EQ(message("{\"a\": {\"x\": 1, \"y\": 2, \"x\": 3}}"),
            "p.json: duplicate key \"x\" in one object (a JSON reader keeps only one of them); expected " + expected);
  // The same key in different objects is fine.
  EXPECT_EQ(message("{\"a\": {\"x\": 1}, \"b\": {\"x\": 2}, \"c\": [{\"x\": 3}, {\"x\": 4}]}"), "no error");
  // Through the study, as ipd table reads a pairs file.
  test::TempDir d;
  write_tiny_study_input_checks(d);
  test::write_text(d / "pairs/real__synth/s1.json", "{\"pairs\": [[0, 1]], \"excluded_a\": [], \"pairs\": [[1, 0]]}");
  const auto r = test::run_ipd("table " + d.path() + " --bootstrap 0");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_EQ(r.err, "error: " + d / "pairs/real__synth/s1.json" +
                       ": duplicate key \"pairs\" in one object (a JSON reader keeps only one of them); expected " +
                       expected + "\n");
}

// --- names that are not UTF-8 in JSON output ----------------------------------------------------------------

TEST(InputChecks, Utf8IsCheckedStrictly) {
  EXPECT_TRUE(is_utf8("Ger\xC3\xB6lle \xE2\x80\x93 \xF0\x9F\xAA\xA8"));
  EXPECT_FALSE(is_utf8("Ger\xF6lle"));        // Latin-1
  EXPECT_FALSE(is_utf8("\xC0\xAF"));          // overlong '/'
  EXPECT_FALSE(is_utf8("\xED\xA0\x80"));      // a surrogate
  EXPECT_FALSE(is_utf8("\xF4\x90\x80\x80"));  // above U+10FFFF
  EXPECT_FALSE(is_utf8("\xE2\x80"));          // cut short
  EXPECT_EQ(escape_non_utf8("Ger\xF6lle\xC3\xB6\n"), "Ger\\xF6lle\xC3\xB6\\x0A");
}

// A Latin-1 scene name made every JSON output fail with nlohmann's bare "invalid UTF-8 byte at index 3:
// 0xF6"; now the error names the file to rename, and the text output still works.
TEST(InputChecks, NamesThatAreNotUtf8AreRefusedInJsonNamingTheFile) {
  test::TempDir d;
  write_tiny_study_input_checks(d);
  test::write_text(d / "study.yaml", "image_size: [1000, 1000]\n");  // square pictures, said so
  const std::string latin1 = "Ger\xF6lle";
  for (const char* dom : {"real", "synth"}) {
    fs::rename(std::string(d / dom) + "/labels/s1.txt", std::string(d / dom) + "/labels/" + latin1 + ".txt");
    fs::rename(std::string(d / dom) + "/predictions/det/s1.txt",
               std::string(d / dom) + "/predictions/det/" + latin1 + ".txt");
  }
  const std::string message = "error: " + d / "real/labels/Ger\\xF6lle.txt" +
                              ": the name is not UTF-8 text, which JSON output cannot hold; rename it (text and CSV "
                              "output take it as it is)\n";
  for (const std::string command :
       {"table --bootstrap 0 --format json", "export rocks --format json", "breakdown --bootstrap 0 --format json"}) {
    const auto r = test::run_ipd(command + " " + d.path());
    EXPECT_EQ(r.exit_code, 1) << command;
    EXPECT_EQ(r.err, message) << command;
    EXPECT_EQ(r.out, "") << command;
  }
  EXPECT_EQ(test::run_ipd("table " + d.path() + " --bootstrap 0").exit_code, 0);
  EXPECT_EQ(test::run_ipd("export rocks --format csv " + d.path()).exit_code, 0);
  // ipd register --json: the path itself is the name.
  const auto r =
      test::run_ipd("register --json " + d / "real/labels/" + latin1 + ".txt " + d / "synth/labels/" + latin1 + ".txt");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_EQ(r.err, "error: " + d / "real/labels/Ger\\xF6lle.txt" +
                       ": the name is not UTF-8 text, which JSON output cannot hold; rename it (the text report takes "
                       "it as it is)\n");
  // Anything else that reaches JSON output is quoted, escaped, never nlohmann's bare message.
  try {
    dump_json_output(nlohmann::json{{"x", {latin1}}});
    ADD_FAILURE();
  } catch (const StudyError& e) {
    EXPECT_EQ(std::string(e.what()),
              "cannot write JSON: 'Ger\\xF6lle' is not UTF-8 text, and JSON holds only UTF-8; rename the file or "
              "directory it comes from (text and CSV output take it as it is)");
  }
}

// --- CSV quoting ---------------------------------------------------------------------------------------------

TEST(InputChecks, CsvFieldsAreQuotedAsRfc4180) {
  EXPECT_EQ(csv_field("plain"), "plain");
  EXPECT_EQ(csv_field("a,b"), "\"a,b\"");
  EXPECT_EQ(csv_field("say \"hi\""), "\"say \"\"hi\"\"\"");
  EXPECT_EQ(csv_field("two\nlines"), "\"two\nlines\"");
  EXPECT_EQ(csv_field("cr\r"), "\"cr\r\"");
  EXPECT_EQ(csv_row({"a", "b,c", ""}), "a,\"b,c\",\n");
}

// A model named "det,v2" shifted every column of the table's CSV by one.
TEST(InputChecks, TableCsvQuotesNamesWithCommas) {
  test::TempDir d;
  write_tiny_study_input_checks(d);
  fs::rename(d / "real/predictions/det", d / "real/predictions/det,v2");
  fs::rename(d / "synth/predictions/det", d / "synth/predictions/det,v2");
  test::write_text(d / "study.yaml", "models: {'det,v2': {trained_on: real}}\n");
  const auto r = test::run_ipd("table --format csv --bootstrap 0 " + d.path());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const size_t nl = r.out.find('\n');
  EXPECT_EQ(r.out.substr(0, nl),
            "model,trained_on,a,b,ipd,pairs,unpaired_a,unpaired_b,scenes,involves_training_domain,ci_low,ci_high,se,"
            "reason,label_fingerprint,scenes_with_hand_pairs,pairs_set_by_hand,rocks_excluded,scenes_reviewed,"
            "pairs_checked,scenes_with_stale_hand_pairs");
  const std::string row = r.out.substr(nl + 1);  // the provenance columns end it: fingerprint, no hand edits
  EXPECT_EQ(row.substr(0, 51), "\"det,v2\",real,real,synth,0.500000,2,0,0,1,true,,,,,") << row;
  EXPECT_EQ(row.substr(row.size() - 7), ",0,0,0\n") << row;
  const auto b = test::run_ipd("breakdown --format csv --bootstrap 0 --by region " + d.path());
  ASSERT_EQ(b.exit_code, 0) << b.err;
  EXPECT_NE(b.out.find("\n\"det,v2\",real,real,synth,"), std::string::npos) << b.out;
}

// --- options out of range ------------------------------------------------------------------------------------

// An option out of range is an error naming the option, never the default; the registration options' ranges are
// theirs (RegistrationOptions::validate), named after the option given.
TEST(InputChecks, OptionsOutOfRangeAreErrorsNotTheDefault) {
  test::TempDir d;
  write_tiny_study_input_checks(d);
  const std::string pair = " " + d / "real/labels/s1.txt" + " " + d / "synth/labels/s1.txt";
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"--max-rotation -5", "--max-rotation: max_rotation_deg must be in (0, 180], got -5"},
      {"--max-rotation 0", "--max-rotation: max_rotation_deg must be in (0, 180], got 0"},
      {"--max-rotation 181", "--max-rotation: max_rotation_deg must be in (0, 180], got 181"},
      {"--max-anisotropy 0", "--max-anisotropy: max_anisotropy must be a number >= 1, got 0"},
      {"--max-anisotropy 0.5", "--max-anisotropy: max_anisotropy must be a number >= 1, got 0.5"},
      {"--trials 0", "--trials: consensus.max_hypotheses must be at least 1, got 0"},
      {"--method cpd --trials 0", "--trials: cpd.iterations must be at least 1, got 0"},
      {"--budget-ms -1", "--budget-ms: must be a number of milliseconds >= 0 (0: no limit), got -1"},
      {"--class -2", "--class: must be a class number >= 0 (leave it out for every class), got -2"},
      {"--threads -1", "--threads: must be >= 0 (0: every core), got -1"},
      {"--image-size 0,10", "--image-size: width and height must be positive, got 0,10"},
      // CLI11 read -5 into the unsigned seed as 2^64 - 5: another seed, without a word.
      {"--seed -5", "--seed: must be a whole number from 0 to 18446744073709551615, got -5"},
      // And 2^64 as 2^64 - 1.
      {"--seed 18446744073709551616",
       "--seed: must be a whole number from 0 to 18446744073709551615, got "
       "18446744073709551616"},
  };
  for (const auto& [option, message] : cases) {
    const auto r = test::run_ipd("register" + pair + " " + option);
    EXPECT_EQ(r.exit_code, 2) << option;
    EXPECT_NE(r.err.find(message), std::string::npos) << option << ": " << r.err;
    EXPECT_EQ(r.out, "") << option;
  }
  EXPECT_EQ(test::run_ipd("register --max-rotation 180 --max-anisotropy 1" + pair).exit_code, 0);
  // The study commands: a negative --seed read as "not given" (study.yaml's seed).
  for (const char* seed : {"-5", "-1"}) {
    const auto r = test::run_ipd("table --seed " + std::string(seed) + " " + d.path());
    EXPECT_EQ(r.exit_code, 2) << seed;
    EXPECT_EQ(r.err.rfind(
                  "--seed: must be a whole number from 0 to 18446744073709551615, got " + std::string(seed) + "\n", 0),
              0u)
        << r.err;
  }
  // --bootstrap 1 is refused (one resample has no spread), with the engine's own words.
  auto one = test::run_ipd("table --bootstrap 1 " + d.path());
  EXPECT_EQ(one.exit_code, 2);
  EXPECT_EQ(one.err.rfind("--bootstrap: the number of bootstrap resamples must be 0 (no intervals) or at least 2 (an "
                          "interval needs two resamples), not 1\n",
                          0),
            0u)
      << one.err;
  EXPECT_EQ(test::run_ipd("table --bootstrap 2 " + d.path()).exit_code, 0);
  // A domain named twice left one domain and read "at least two domains are needed".
  const auto twice = test::run_ipd("table --domains real,real " + d.path());
  EXPECT_EQ(twice.exit_code, 2);
  EXPECT_EQ(twice.err.rfind("--domains: names 'real' twice (a domain is compared with another)\n", 0), 0u) << twice.err;
  // ipd detect: a negative class kept nothing ("no rocks" everywhere), negative threads meant every core.
  auto detect = test::run_ipd("detect " + d.path() + " --detector classical --out " + d / "x" + " --classes 0,-1");
  EXPECT_EQ(detect.exit_code, 2);
  EXPECT_EQ(detect.err.rfind("classes must be class numbers >= 0, got -1\n", 0), 0u) << detect.err;
  detect = test::run_ipd("detect " + d.path() + " --detector classical --out " + d / "x" + " --threads -2");
  EXPECT_EQ(detect.exit_code, 2);
  EXPECT_EQ(detect.err.rfind("--threads: must be >= 0 (0: every core), got -2\n", 0), 0u) << detect.err;
  const auto demo = test::run_ipd("demo " + d / "demo" + " --seed -3");
  EXPECT_EQ(demo.exit_code, 2);
  EXPECT_FALSE(fs::exists(d / "demo"));
}

// One seed range everywhere: --seed 2^64 - 1 was read as 2^63 - 1 by the study commands, so it gave other
// intervals than the same seed in study.yaml.
TEST(InputChecks, TheLargestSeedIsTheSameSeedOnTheCommandLineAndInStudyYaml) {
  test::TempDir d;
  write_tiny_study_input_checks(d);
  const auto given = test::run_ipd("table --format json --bootstrap 10 --seed 18446744073709551615 " + d.path());
  EXPECT_EQ(given.exit_code, 0) << given.err;
  EXPECT_NE(given.out.find("\"seed\": 18446744073709551615"), std::string::npos) << given.out;
  test::write_text(d / "study.yaml", "registration:\n  seed: 18446744073709551615\n");
  const auto from_yaml = test::run_ipd("table --format json --bootstrap 10 " + d.path());
  EXPECT_EQ(from_yaml.exit_code, 0) << from_yaml.err;
  EXPECT_EQ(from_yaml.out, given.out);
}

// ipd breakdown took up to 100 bins, ipd figure breakdown up to 20: one range, so every printed breakdown can
// be drawn.
TEST(InputChecks, BreakdownBinsHaveOneRangePrintedOrDrawn) {
  test::TempDir d;
  write_tiny_study_input_checks(d);
  for (const std::string& command : std::vector<std::string>{"breakdown", "figure breakdown --out " + d / "b.svg"}) {
    const auto r = test::run_ipd(command + " --bootstrap 0 --bins 21 " + d.path());
    EXPECT_EQ(r.exit_code, 2) << command;
    EXPECT_EQ(r.err.rfind("--bins: Value 21 not in range 1 to 20\n", 0), 0u) << command << ": " << r.err;
    EXPECT_EQ(test::run_ipd(command + " --bootstrap 0 --bins 20 " + d.path()).exit_code, 0) << command;
  }
  BreakdownOptions o;
  o.bins = 21;
  EXPECT_EQ(o.validate(), "--bins must be between 1 and 20, not 21");
}

// ipd demo writes a new study: over an existing directory with files (a study with hand pairs, say) it writes
// nothing and says so; an empty directory is fine.
TEST(InputChecks, DemoRefusesADirectoryThatHoldsFiles) {
  test::TempDir d;
  fs::create_directories(d.path() + "/old/pairs");
  test::write_text(d / "old/pairs/scene_01.txt", "1 2\n");
  const auto demo = test::run_ipd("demo " + d / "old" + " --labels-only --scenes 1 --rocks 8");
  EXPECT_EQ(demo.exit_code, 1);
  EXPECT_EQ(demo.err, "error: " + d / "old" +
                          ": already exists and is not an empty directory; ipd demo writes a new study into an empty "
                          "or new directory\n");
  EXPECT_FALSE(fs::exists(d / "old/study.yaml"));
  fs::create_directories(d.path() + "/empty");
  EXPECT_EQ(test::run_ipd("demo " + d / "empty" + " --labels-only --scenes 1 --rocks 8").exit_code, 0);
  EXPECT_TRUE(fs::exists(d / "empty/study.yaml"));
}

// A file named `pairs` read as "no hand pairs" without a word; it holds none, and says so.
TEST(InputChecks, AFileInPlaceOfThePairsFolderIsSaid) {
  test::TempDir d;
  test::write_two_rock_study(d);
  test::write_text(d / "pairs", "");
  const auto r = test::run_ipd("table " + d.path() + " --bootstrap 0");
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_NE(r.err.find("warning: " + d / "pairs" + ": is a file, expected the folder of hand pairs: none are read"),
            std::string::npos)
      << r.err;
}

// A mistyped command is named: CLI11 said only "A subcommand is required", and "ipd tabel demo" ran ipd demo
// ("OUT_DIR is required").
TEST(InputChecks, AnUnknownCommandIsNamedWithTheCommandsThereAre) {
  auto r = test::run_ipd("tabel demo");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.err,
            "error: 'tabel' is not a command of ipd; expected one of: table, register, demo, figure, bench, detect, "
            "import, compare, rank, breakdown, export, metrics\n");
  r = test::run_ipd("figure pairz study");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.err,
            "error: 'pairz' is not a command of ipd figure; expected one of: pairs, registration, table, compare, "
            "distribution, breakdown, gallery, sweep\n");
}

// A domain listed twice was dropped without a word (and the columns' order changed).
TEST(InputChecks, StudyYamlDomainsListedTwiceAreAnError) {
  EXPECT_EQ(test::study_yaml_error("rock_class: 0\ndomains: [real, real, hapke]\n"),
            "study.yaml:2: domains lists 'real' twice; each domain once, in the order to show");
}

// study.yaml's registration block: every number is checked where it is written.
TEST(InputChecks, StudyYamlRegistrationNumbersAreChecked) {
  EXPECT_EQ(test::study_yaml_error("registration:\n  seed: -1\n"),
            "study.yaml:2: registration.seed must be a whole number from 0 to 18446744073709551615, got -1");
  EXPECT_EQ(test::study_yaml_error("registration:\n  seed: 18446744073709551616\n"),
            "study.yaml:2: registration.seed must be a whole number from 0 to 18446744073709551615, got "
            "18446744073709551616");
  EXPECT_EQ(
      test::study_yaml_error("registration:\n  gate: 0\n"),
      "study.yaml:2: registration.gate must be a number > 0 (a fraction of the rocks' spread; default 0.2), got 0");
  EXPECT_EQ(test::study_yaml_error("registration:\n  gate: .inf\n"),
            "study.yaml:2: registration.gate must be a number > 0 (a fraction of the rocks' spread; default 0.2), got "
            ".inf");
  EXPECT_EQ(test::study_yaml_error("registration:\n  method: paper\n  trials: -3\n"),
            "study.yaml:3: registration.trials must be at least 1, got -3");
  EXPECT_EQ(parse_study_config("registration: {seed: 12, gate: 0.3}\n", "study.yaml").registration.seed, 12u);
}

}  // namespace
}  // namespace ipd
