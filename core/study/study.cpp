#include "core/study/study.h"

#include <yaml-cpp/yaml.h>

#include <fmt/format.h>
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <set>
#include <string>
#include <string_view>

#include "core/study/study_names.h"
#include "core/study/study_yaml_domains.h"
#include "core/study/yolo_source.h"
#include "core/util/atomic_file.h"
#include "core/util/contained_file.h"
#include "core/util/json_input.h"
#include "core/util/json_output.h"
#include "core/util/number_text.h"
#include "core/util/utf8.h"

namespace fs = std::filesystem;

namespace ipd {

namespace {

// How much of a name a message quotes: enough to recognise it, never the whole of a pasted blob.
constexpr size_t kShownNameBytes = 60;

const std::set<std::string> kImageExtensions = {".png", ".jpg", ".jpeg", ".tif", ".tiff", ".bmp", ".webp"};

template <typename T>
T yaml_get(const YAML::Node& n, const std::string& file, const char* what) {
  try {
    return n.as<T>();
  } catch (const YAML::Exception&) {
    throw StudyError(fmt::format("{}:{}: {} has the wrong type", file, n.Mark().line + 1, what));
  }
}

// yaml-cpp keeps the last of two equal keys: a setting written twice is a mistake to report, not to guess.
void check_unique_keys(const YAML::Node& map, const std::string& file, const std::string& prefix) {
  std::map<std::string, int> first_line;
  for (const auto& kv : map) {
    if (!kv.first.IsScalar()) continue;
    const std::string key = kv.first.Scalar();
    const int line = kv.first.Mark().line + 1;
    const auto [it, fresh] = first_line.emplace(key, line);
    if (!fresh)
      throw StudyError(fmt::format("{}:{}: duplicate setting '{}{}' (first given on line {})", file, line, prefix,
                                   quoted_for_message(key), it->second));
  }
}

// A model's settings: {trained_on: DOMAIN}, or nothing when the training domain is unknown. A misspelt key
// (`traind_on`) or `trained_on: null` would otherwise leave the model without its training domain, and every
// cell of its row would then count as a cross-domain cell.
std::string parse_model_settings(const YAML::Node& settings, const std::string& file, const std::string& name) {
  if (!settings.IsMap()) return "";
  const std::string where = "models." + quoted_for_message(name);
  check_unique_keys(settings, file, where + ".");
  std::string trained_on;
  for (const auto& kv : settings) {
    const int line = kv.first.Mark().line + 1;
    const std::string key = kv.first.IsScalar() ? kv.first.Scalar() : std::string("(a list or mapping)");
    if (key != "trained_on")
      throw StudyError(fmt::format("{}:{}: unknown setting '{}.{}' (expected trained_on)", file, line, where,
                                   quoted_for_message(key)));
    if (kv.second.IsNull())
      throw StudyError(
          fmt::format("{}:{}: {}.trained_on is empty (null); expected the name of the domain the "
                      "model was trained on (leave the setting out when it is unknown)",
                      file, line, where));
    trained_on = yaml_get<std::string>(kv.second, file, "trained_on");
    if (trained_on.empty())
      throw StudyError(
          fmt::format("{}:{}: {}.trained_on is an empty name; expected the name of the domain the "
                      "model was trained on (leave the setting out when it is unknown)",
                      file, line, where));
  }
  return trained_on;
}

}  // namespace

namespace {

// Where the first YAML document of `text` ends. Documents are split here, not by YAML::LoadAll: yaml-cpp 0.7's
// LoadAll loops without end, eating memory, on some malformed multi-document inputs (a 123-byte study.yaml
// found by fuzz_study_yaml took > 16 GB). A `---` after the first document's content starts a second one;
// Load() alone would silently ignore it, so content after it is an error.
size_t first_document_end(const std::string& text, const std::string& file) {
  size_t first_end = text.size();
  bool content = false;
  int line_no = 0;
  for (size_t pos = 0; pos < text.size();) {
    const size_t eol = std::min(text.find('\n', pos), text.size());
    std::string line = text.substr(pos, eol - pos);
    ++line_no;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    const size_t first = line.find_first_not_of(" \t");
    const bool blank = first == std::string::npos || line[first] == '#';
    const bool marker = line.rfind("---", 0) == 0 && (line.size() == 3 || line[3] == ' ' || line[3] == '\t');
    const bool end_marker = line.rfind("...", 0) == 0 && (line.size() == 3 || line[3] == ' ' || line[3] == '\t');
    if (first_end == text.size()) {
      if ((marker && content) || end_marker)
        first_end = pos;
      else if (!blank && !marker && line[0] != '%')
        content = true;
    } else if (!blank && !marker && !end_marker) {
      throw StudyError(fmt::format("{}:{}: a second YAML document; expected one mapping of settings", file, line_no));
    }
    pos = eol + 1;
  }
  return first_end;
}

// `models:` - each model's name (a file name: it becomes part of export file names) and settings.
void parse_models(const YAML::Node& v, const std::string& file, int line, StudyConfig* c) {
  if (!v.IsMap()) throw StudyError(fmt::format("{}:{}: models must map a model name to its settings", file, line));
  check_unique_keys(v, file, "models.");
  for (const auto& m : v) {
    const std::string name = m.first.as<std::string>();
    // The name becomes the default model and part of export file names: it must be one.
    if (const std::string why = file_name_problem(name, kMaxModelNameBytes); !why.empty())
      throw StudyError(fmt::format("{}:{}: model name '{}' {}", file, m.first.Mark().line + 1,
                                   printable_name(name, kShownNameBytes), why));
    // `det:` with nothing after it (a line cut short, a value forgotten) would silently drop the model's
    // training domain: an unknown one is said with `{}`.
    if (m.second.IsNull())
      throw StudyError(
          fmt::format("{}:{}: models.{} has no value; expected its settings like {{trained_on: real}} "
                      "({{}} when the training domain is unknown)",
                      file, m.first.Mark().line + 1, quoted_for_message(name)));
    if (!m.second.IsMap())
      throw StudyError(fmt::format("{}:{}: models.{} must be a mapping like {{trained_on: real}}", file,
                                   m.first.Mark().line + 1, quoted_for_message(name)));
    c->trained_on[name] = parse_model_settings(m.second, file, name);
  }
}

// `registration:` - method, seed, trials (the method's search budget), gate and budget_ms (the time budget of each
// registration), validated together.
void parse_registration(const YAML::Node& v, const std::string& file, int line, StudyConfig* c) {
  if (!v.IsMap()) throw StudyError(fmt::format("{}:{}: registration must be a mapping", file, line));
  check_unique_keys(v, file, "registration.");
  int trials = 0;  // 0: not given
  for (const auto& r : v) {
    const std::string k = r.first.as<std::string>();
    if (k == "method") {
      const std::string name = yaml_get<std::string>(r.second, file, "registration.method");
      if (!parse_method(name, &c->registration.method))
        throw StudyError(fmt::format("{}:{}: unknown registration method '{}' (expected {})", file,
                                     r.first.Mark().line + 1, quoted_for_message(name), method_choices()));
    } else if (k == "seed") {
      // parse_seed's range, as --seed's: yaml-cpp reads "-1" as 2^64 - 1 for an unsigned type, and 2^64 is
      // "the wrong type"; either is an error naming the range.
      if (!r.second.IsScalar()) yaml_get<std::uint64_t>(r.second, file, "registration.seed");
      if (!parse_seed(r.second.Scalar(), &c->registration.seed))
        throw StudyError(fmt::format("{}:{}: registration.seed must be {}, got {}", file, r.first.Mark().line + 1,
                                     kSeedRange, quoted_for_message(r.second.Scalar())));
    } else if (k == "trials") {
      trials = yaml_get<int>(r.second, file, "registration.trials");
      if (trials < 1)
        throw StudyError(fmt::format("{}:{}: registration.trials must be at least 1, got {}", file,
                                     r.first.Mark().line + 1, trials));
    } else if (k == "gate") {
      c->registration.paper.pair_gate = yaml_get<double>(r.second, file, "registration.gate");
      if (!(c->registration.paper.pair_gate > 0) || !std::isfinite(c->registration.paper.pair_gate))
        throw StudyError(
            fmt::format("{}:{}: registration.gate must be a number > 0 (a fraction of the rocks' "
                        "spread; default 0.2), got {}",
                        file, r.first.Mark().line + 1, quoted_for_message(r.second.Scalar())));
    } else if (k == "budget_ms") {
      // A number > 0: what --budget-ms takes. yaml-cpp reads "nan" and ".inf" as doubles: both are refused.
      double ms = 0;
      if (!r.second.IsScalar() || !YAML::convert<double>::decode(r.second, ms) || !(ms > 0) || !std::isfinite(ms))
        throw StudyError(
            fmt::format("{}:{}: registration.budget_ms must be a number of milliseconds > 0 (unset: "
                        "no time limit), got {}",
                        file, r.first.Mark().line + 1,
                        r.second.IsNull()     ? std::string("nothing")
                        : r.second.IsScalar() ? quoted_for_message(r.second.Scalar())
                                              : std::string("a list or map")));
      c->registration.time_budget_ms = ms;
    } else {
      throw StudyError(
          fmt::format("{}:{}: unknown registration setting '{}' (expected method, seed, trials, gate, budget_ms)", file,
                      r.first.Mark().line + 1, quoted_for_message(k)));
    }
  }
  // trials is the configured method's search budget, as ipd register's --trials: cpd's EM iterations.
  if (trials > 0) c->registration.trials() = trials;
  const std::string bad = c->registration.validate();
  if (!bad.empty()) throw StudyError(fmt::format("{}:{}: {}", file, line, bad));
}

StudyConfig parse_study_config_nodes(const std::string& text, const std::string& file);
}  // namespace

StudyConfig parse_study_config(const std::string& text, const std::string& file) {
  try {
    return parse_study_config_nodes(text, file);
  } catch (const YAML::Exception& e) {  // anything the checks below didn't anticipate still names the file
    throw StudyError(fmt::format("{}:{}: {}", file, e.mark.line + 1, e.msg.empty() ? "invalid setting" : e.msg));
  }
}

namespace {
StudyConfig parse_study_config_nodes(const std::string& text, const std::string& file) {
  StudyConfig c;
  const size_t first_end = first_document_end(text, file);
  std::vector<YAML::Node> documents;
  try {
    documents.push_back(YAML::Load(text.substr(0, first_end)));
  } catch (const YAML::ParserException& e) {
    // yaml-cpp quotes the offending byte (a NUL, say) as it is: shown as \xHH.
    throw StudyError(fmt::format("{}:{}: invalid YAML: {}", file, e.mark.line + 1, escape_non_utf8(e.msg)));
  }
  if (documents.empty()) return c;
  const YAML::Node& root = documents.front();
  if (!root || root.IsNull()) return c;
  if (!root.IsMap()) throw StudyError(file + ": expected a mapping of settings at the top level");
  check_unique_keys(root, file, "");
  for (const auto& kv : root) {
    if (!kv.first.IsScalar())
      throw StudyError(fmt::format("{}:{}: expected a setting name, found a {}", file, kv.first.Mark().line + 1,
                                   kv.first.IsSequence() ? "list" : "mapping"));
    const std::string key = kv.first.as<std::string>();
    const YAML::Node& v = kv.second;
    const int line = kv.first.Mark().line + 1;
    if (key == "rock_class") {
      // A class number, or a name that the study's classes resolve (study_classes.h).
      const std::string word = yaml_get<std::string>(v, file, "rock_class");
      const bool number = !word.empty() && word.find_first_not_of("+-0123456789") == std::string::npos;
      if (number) {
        c.rock_class = yaml_get<int>(v, file, "rock_class");
        if (c.rock_class < 0) throw StudyError(fmt::format("{}:{}: rock_class must be >= 0", file, line));
      } else {
        c.rock_class_word = word;
        c.rock_class_line = line;
      }
    } else if (key == "classes") {
      c.class_names = yaml_get<std::vector<std::string>>(v, file, "classes");
      for (size_t k = 0; k < c.class_names.size(); ++k) {
        if (c.class_names[k].empty()) continue;  // "" keeps a number unnamed (a 1-based export's 0)
        if (std::find(c.class_names.begin(), c.class_names.begin() + static_cast<long>(k), c.class_names[k]) !=
            c.class_names.begin() + static_cast<long>(k))
          throw StudyError(fmt::format("{}:{}: classes lists '{}' twice; each class once, at its number", file, line,
                                       quoted_for_message(c.class_names[k])));
      }
    } else if (key == "task") {
      const std::string word = yaml_get<std::string>(v, file, "task");
      if (!parse_task(word, &c.task))
        throw StudyError(fmt::format("{}:{}: task must be detect (box IoU) or segment (mask IoU), found '{}'", file,
                                     line, quoted_for_message(word)));
    } else if (key == "conf_threshold") {
      c.conf_threshold = yaml_get<double>(v, file, "conf_threshold");
      if (!(c.conf_threshold >= 0 && c.conf_threshold <= 1))
        throw StudyError(fmt::format("{}:{}: conf_threshold must be in [0, 1]", file, line));
    } else if (key == "image_size") {
      if (!v.IsSequence() || v.size() != 2)
        throw StudyError(fmt::format("{}:{}: image_size must be [width, height]", file, line));
      c.image_width = yaml_get<int>(v[0], file, "image_size width");
      c.image_height = yaml_get<int>(v[1], file, "image_size height");
      if (c.image_width <= 0 || c.image_height <= 0)
        throw StudyError(fmt::format("{}:{}: image_size must be positive", file, line));
    } else if (key == "domains") {
      parse_study_domains(v, file, line, &c);
    } else if (key == "models") {
      parse_models(v, file, line, &c);
    } else if (key == "registration") {
      parse_registration(v, file, line, &c);
    } else {
      throw StudyError(
          fmt::format("{}:{}: unknown setting '{}' (expected rock_class, classes, task, conf_threshold, image_size, "
                      "domains, models, registration)",
                      file, line, quoted_for_message(key)));
    }
  }
  return c;
}
}  // namespace

const Domain* Study::domain(const std::string& name) const {
  for (const auto& d : domains)
    if (d.name == name) return &d;
  return nullptr;
}

const Domain& Study::require_domain(const std::string& name, const char* role) const {
  if (const Domain* d = domain(name)) return *d;
  throw StudyError(fmt::format("{}: no domain '{}' in this study ({}the study's domains: {})", root,
                               quoted_for_message(name), role ? std::string(role) + "; " : "", domain_names()));
}

std::string Study::domain_names() const {
  std::string out;
  for (const auto& d : domains) out += (out.empty() ? "" : ", ") + quoted_for_message(d.name);
  return out;
}

std::string Study::label_folder(const std::string& d) const { return (fs::path(root) / d / "labels").string(); }

std::string Study::prediction_folder(const std::string& d, const std::string& model) const {
  return (fs::path(root) / d / "predictions" / model).string();
}

// A stem is one name (study_names.h), so this is the folder's path joined with it as fs::path would.
std::string Study::label_file(const std::string& folder, const std::string& stem) {
  std::string path;
  path.reserve(folder.size() + stem.size() + 5);
  return path.append(folder).append(1, '/').append(stem).append(".txt");
}

std::string Study::label_path(const std::string& d, const std::string& stem) const {
  return label_file(label_folder(d), stem);
}

std::string Study::prediction_path(const std::string& d, const std::string& model, const std::string& stem) const {
  return label_file(prediction_folder(d, model), stem);
}

std::string Study::pairs_dir(const std::string& a, const std::string& b) const {
  return (fs::path(root) / "pairs" / (a + "__" + b)).string();
}

double Study::aspect() const {
  if (config.image_width > 0 && config.image_height > 0)
    return static_cast<double>(config.image_width) / config.image_height;
  return 1.0;
}

namespace {

// What is at `p`; a dangling link or a path that can't be examined is a StudyError naming it.
FileKind kind_of(const fs::path& p) {
  try {
    return file_kind(p.string());
  } catch (const IoError& e) {
    throw StudyError(e.what());
  }
}

// A folder or file name that the study turns into parts of other file names (study_names.h).
void check_name(const fs::path& where, const std::string& name, const char* what, size_t max_bytes) {
  if (const std::string why = file_name_problem(name, max_bytes); !why.empty())
    throw StudyError(fmt::format("{}: {} name '{}' {}", printable_name(where.string()), what,
                                 printable_name(name, kShownNameBytes), why));
}

// A study is read only inside itself: a file or folder of it that is a symbolic link (a prediction file, a
// domain folder, study.yaml) would make the tool read, and count, what lies elsewhere. Checked as the study is
// scanned (the files are then read without following links: read_labels_beneath).
void refuse_link(const fs::directory_entry& e) {
  std::error_code ec;
  if (e.is_symlink(ec))
    throw StudyError(printable_name(e.path().string()) +
                     ": is a symbolic link; reading through it is refused (links inside a study are never followed)");
}

// Every entry of a directory; one that can't be read is an error, never an empty directory.
std::vector<fs::directory_entry> list_directory(const fs::path& dir) {
  std::vector<fs::directory_entry> out;
  std::error_code ec;
  for (fs::directory_iterator it(dir, ec); !ec && it != fs::directory_iterator(); it.increment(ec)) out.push_back(*it);
  if (ec) throw StudyError(fmt::format("{}: cannot read the directory: {}", dir.string(), ec.message()));
  return out;
}

// Label (or prediction) files of one directory, by stem. Only `<stem>.txt` is read (Study::label_path); a
// file whose extension is .txt in another case (0001.TXT from a Windows tool) would be silently skipped and
// its scene read as having no rocks, so it is an error, saying whether 0001.txt is there too.
std::set<std::string> label_stems(const fs::path& dir) {
  std::set<std::string> stems;
  std::vector<fs::path> refused;
  for (const auto& f : list_directory(dir)) {
    const fs::path& p = f.path();
    // The name's stem and extension as fs::path has them (the last dot, unless it leads the name), taken from
    // the name's text once: a 10,000-scene study lists 120,000 of them on every open.
    const std::string name = p.filename().string();
    const size_t dot = name.rfind('.');
    const bool has_extension = dot != std::string::npos && dot > 0 && name != "..";
    const std::string_view extension = has_extension ? std::string_view(name).substr(dot) : std::string_view();
    if (name == "classes.txt") continue;  // class names (ipd import coco), not a scene
    if (extension == ".txt") {
      refuse_link(f);
      std::string stem = name.substr(0, dot);
      check_name(p, stem, "scene", kMaxStemBytes);
      stems.insert(std::move(stem));
    } else if (ascii_lower(std::string(extension)) == ".txt") {
      refused.push_back(p);
    }
  }
  if (refused.empty()) return stems;
  std::sort(refused.begin(), refused.end());
  const fs::path& p = refused.front();
  const std::string stem = p.stem().string();
  if (stems.count(stem))
    throw StudyError(
        fmt::format("{}: {}.txt holds this scene's boxes too, and only lower-case .txt files are read; "
                    "remove or merge one of them",
                    p.string(), stem));
  throw StudyError(fmt::format("{}: only lower-case .txt label files are read; rename it to {}.txt", p.string(), stem));
}

// One domain: its scenes (label files and pictures), its pictures by stem and its prediction sets. Two
// pictures of one scene (0001.png and 0001.jpg) are an error: which one is shown would depend on the
// directory's order.
Domain scan_domain(const fs::path& root, const std::string& name, std::set<std::string>* all_models) {
  Domain d;
  d.name = name;
  d.dir = (root / name).string();
  check_name(root / name, name, "domain", kMaxDomainNameBytes);
  for (const char* folder : {"labels", "images", "predictions"}) {
    std::error_code ec;
    refuse_link(fs::directory_entry(root / name / folder, ec));
  }
  std::set<std::string> stems = label_stems(root / name / "labels");
  if (kind_of(root / name / "images") == FileKind::kDirectory) {
    std::vector<fs::path> pictures;
    for (const auto& f : list_directory(root / name / "images"))
      if (kImageExtensions.count(ascii_lower(f.path().extension().string()))) {
        refuse_link(f);
        pictures.push_back(f.path());
      }
    std::sort(pictures.begin(), pictures.end());
    for (const auto& p : pictures) {
      const std::string stem = p.stem().string();
      check_name(p, stem, "scene", kMaxStemBytes);
      const auto [it, fresh] = d.images.emplace(stem, p.string());
      if (!fresh)
        throw StudyError(fmt::format("{}: {} is a picture of this scene too; keep one of them", p.string(),
                                     fs::path(it->second).filename().string()));
      stems.insert(stem);
    }
  }
  if (kind_of(root / name / "predictions") == FileKind::kDirectory) {
    for (const auto& m : list_directory(root / name / "predictions")) {
      refuse_link(m);
      if (kind_of(m.path()) != FileKind::kDirectory) continue;
      check_name(m.path(), m.path().filename().string(), "model", kMaxModelNameBytes);
      label_stems(m.path());  // the same rule as labels/: a 0001.TXT there would read as "nothing detected"
      d.models.push_back(m.path().filename().string());
      all_models->insert(d.models.back());
    }
    std::sort(d.models.begin(), d.models.end());
  }
  d.stems.assign(stems.begin(), stems.end());
  return d;
}

}  // namespace

Study open_study(const std::string& root_in) {
  const fs::path root(root_in);
  const FileKind root_kind = kind_of(root);
  if (root_kind == FileKind::kMissing) throw StudyError(root_in + ": no such study directory");
  if (root_kind != FileKind::kDirectory) throw StudyError(root_in + ": is not a directory, expected a study directory");
  Study s;
  s.root = root.string();
  const fs::path yaml = root / "study.yaml";
  try {
    // Not through a link: a study's settings are its own.
    if (const auto text = read_file_beneath(root.string(), "study.yaml", kMaxStudyYamlBytes))
      s.config = parse_study_config(*text, yaml.string());
  } catch (const IoError& e) {
    throw StudyError(e.what());
  }
  std::vector<std::string> names;
  for (const auto& e : list_directory(root)) {
    const std::string name = e.path().filename().string();
    if (name == "pairs" || name.empty() || name[0] == '.') continue;
    if (kind_of(e.path()) != FileKind::kDirectory) continue;
    if (kind_of(e.path() / "labels") != FileKind::kDirectory) continue;
    refuse_link(e);  // a domain folder that is a link: a domain elsewhere
    names.push_back(name);
  }
  if (names.empty())
    throw StudyError(root_in + ": no domains found (expected subdirectories like real/labels/ with YOLO label files)" +
                     yolo_dataset_hint(root.string(), root_in));
  if (names.size() > kMaxDomains)
    throw StudyError(
        fmt::format("{}: {} domains, more than the {} a study may hold (every pair of domains is "
                    "compared; 1,000 one-scene domains take 24 s and 1 GB)",
                    root_in, names.size(), kMaxDomains));
  for (const auto& want : s.config.domain_order)
    if (std::find(names.begin(), names.end(), want) == names.end())
      throw StudyError(fmt::format("{}: study.yaml lists domain '{}' but there is no {}/labels/ directory", root_in,
                                   quoted_for_message(want), quoted_for_message(want)));
  // Configured order first, then "real", then alphabetical.
  auto rank = [&](const std::string& n) {
    const auto p = std::find(s.config.domain_order.begin(), s.config.domain_order.end(), n);
    if (p != s.config.domain_order.end()) return static_cast<int>(p - s.config.domain_order.begin());
    return n == "real" ? 1000 : 2000;
  };
  std::sort(names.begin(), names.end(),
            [&](const auto& x, const auto& y) { return std::make_pair(rank(x), x) < std::make_pair(rank(y), y); });
  std::set<std::string> all_models;
  for (const auto& name : names) s.domains.push_back(scan_domain(root, name, &all_models));
  for (const auto& [m, dom] : s.config.trained_on) {
    if (!dom.empty() && !s.domain(dom))
      throw StudyError(fmt::format("{}: study.yaml says model '{}' was trained on '{}', which is not a domain here",
                                   root_in, quoted_for_message(m), quoted_for_message(dom)));
    all_models.insert(m);
  }
  for (const auto& m : all_models) {
    const auto t = s.config.trained_on.find(m);
    s.models.push_back({m, t == s.config.trained_on.end() ? "" : t->second});
  }
  auto dom_rank = [&](const ModelInfo& m) {
    for (size_t k = 0; k < s.domains.size(); ++k)
      if (s.domains[k].name == m.trained_on) return static_cast<int>(k);
    return 1 << 20;
  };
  std::stable_sort(s.models.begin(), s.models.end(),
                   [&](const auto& x, const auto& y) { return dom_rank(x) < dom_rank(y); });
  try {
    s.classes = read_study_classes(s.root, s.config, s.domains);
  } catch (const IoError& e) {
    throw StudyError(e.what());
  }
  if (!s.config.rock_class_word.empty()) {
    try {
      s.config.rock_class = s.classes.resolve(s.config.rock_class_word);
    } catch (const StudyError& e) {
      throw StudyError(fmt::format("{}:{}: rock_class: {}", yaml.string(), s.config.rock_class_line, e.what()));
    }
  }
  return s;
}

void require_utf8_names(const Study& s) {
  auto check = [](const std::string& name, const std::string& path) {
    if (!is_utf8(name))
      throw StudyError(
          fmt::format("{}: the name is not UTF-8 text, which JSON output cannot hold; rename it (text "
                      "and CSV output take it as it is)",
                      escape_non_utf8(path)));
  };
  for (const auto& d : s.domains) {
    check(d.name, d.dir);
    for (const auto& m : d.models) check(m, (fs::path(d.dir) / "predictions" / m).string());
    for (const auto& stem : d.stems) {
      const auto picture = d.images.find(stem);
      check(stem, picture != d.images.end() ? picture->second : s.label_path(d.name, stem));
    }
  }
  for (const auto& m : s.models) check(m.name, (fs::path(s.root) / "study.yaml").string() + " (models." + m.name + ")");
}

SceneMatch match_scenes(const Domain& a, const Domain& b) {
  SceneMatch m;
  std::set_intersection(a.stems.begin(), a.stems.end(), b.stems.begin(), b.stems.end(), std::back_inserter(m.common));
  std::set_difference(a.stems.begin(), a.stems.end(), b.stems.begin(), b.stems.end(), std::back_inserter(m.only_a));
  std::set_difference(b.stems.begin(), b.stems.end(), a.stems.begin(), a.stems.end(), std::back_inserter(m.only_b));
  return m;
}

}  // namespace ipd
