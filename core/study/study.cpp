#include "core/study/study.h"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <filesystem>
#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <set>

#include "core/study/study_names.h"
#include "core/util/atomic_file.h"
#include "core/util/json_input.h"

namespace fs = std::filesystem;

namespace ipd {

namespace {

const std::set<std::string> kImageExtensions = {".png", ".jpg", ".jpeg", ".tif", ".tiff", ".bmp", ".webp"};

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::tolower(c); });
  return s;
}

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
                                   key.size() > 40 ? key.substr(0, 37) + "..." : key, it->second));
  }
}

}  // namespace

namespace {
StudyConfig parse_study_config_nodes(const std::string& text, const std::string& file);
}

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
  // Documents are split here, not by YAML::LoadAll: yaml-cpp 0.7's LoadAll loops without end, eating memory,
  // on some malformed multi-document inputs (a 123-byte study.yaml found by fuzz_study_yaml took > 16 GB).
  // A `---` after the first document's content starts a second one; Load() alone would silently ignore it.
  size_t first_end = text.size();
  {
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
        if ((marker && content) || end_marker) first_end = pos;
        else if (!blank && !marker && line[0] != '%') content = true;
      } else if (!blank && !marker && !end_marker) {
        throw StudyError(fmt::format("{}:{}: a second YAML document; expected one mapping of settings", file, line_no));
      }
      pos = eol + 1;
    }
  }
  std::vector<YAML::Node> documents;
  try {
    documents.push_back(YAML::Load(text.substr(0, first_end)));
  } catch (const YAML::ParserException& e) {
    throw StudyError(fmt::format("{}:{}: invalid YAML: {}", file, e.mark.line + 1, e.msg));
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
      c.rock_class = yaml_get<int>(v, file, "rock_class");
      if (c.rock_class < 0) throw StudyError(fmt::format("{}:{}: rock_class must be >= 0", file, line));
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
      c.domain_order = yaml_get<std::vector<std::string>>(v, file, "domains");
    } else if (key == "models") {
      if (!v.IsMap()) throw StudyError(fmt::format("{}:{}: models must map a model name to its settings", file, line));
      check_unique_keys(v, file, "models.");
      for (const auto& m : v) {
        const std::string name = m.first.as<std::string>();
        // The name becomes the default model and part of export file names: it must be one.
        if (const std::string why = file_name_problem(name, kMaxModelNameBytes); !why.empty())
          throw StudyError(fmt::format("{}:{}: model name '{}' {}", file, m.first.Mark().line + 1,
                                       printable_name(name), why));
        if (!m.second.IsMap() && !m.second.IsNull())
          throw StudyError(fmt::format("{}:{}: models.{} must be a mapping like {{trained_on: real}}", file,
                                       m.first.Mark().line + 1, name));
        if (m.second.IsMap()) check_unique_keys(m.second, file, "models." + name + ".");
        const YAML::Node& t = m.second["trained_on"];
        c.trained_on[name] = t ? yaml_get<std::string>(t, file, "trained_on") : "";
      }
    } else if (key == "registration") {
      if (!v.IsMap()) throw StudyError(fmt::format("{}:{}: registration must be a mapping", file, line));
      check_unique_keys(v, file, "registration.");
      int trials = 0;  // 0: not given
      for (const auto& r : v) {
        const std::string k = r.first.as<std::string>();
        if (k == "method") {
          const std::string name = yaml_get<std::string>(r.second, file, "registration.method");
          if (!parse_method(name, &c.registration.method))
            throw StudyError(fmt::format("{}:{}: unknown registration method '{}' (expected {})", file,
                                         r.first.Mark().line + 1, name, method_choices()));
        } else if (k == "seed") {
          c.registration.seed = yaml_get<std::uint64_t>(r.second, file, "registration.seed");
        } else if (k == "trials") {
          trials = yaml_get<int>(r.second, file, "registration.trials");
          if (trials < 1)
            throw StudyError(fmt::format("{}:{}: registration.trials must be at least 1, got {}", file,
                                         r.first.Mark().line + 1, trials));
        } else if (k == "gate") {
          c.registration.pair_gate = yaml_get<double>(r.second, file, "registration.gate");
        } else {
          throw StudyError(fmt::format("{}:{}: unknown registration setting '{}' (expected method, seed, trials, gate)",
                                       file, r.first.Mark().line + 1, k));
        }
      }
      // trials is the configured method's search budget, as ipd register's --trials: cpd's EM iterations.
      if (trials > 0)
        (c.registration.method == RegistrationMethod::kCpd ? c.registration.cpd_iterations
                                                           : c.registration.max_trials) = trials;
      const std::string bad = c.registration.validate();
      if (!bad.empty()) throw StudyError(fmt::format("{}:{}: {}", file, line, bad));
    } else {
      throw StudyError(fmt::format(
          "{}:{}: unknown setting '{}' (expected rock_class, conf_threshold, image_size, domains, models, registration)",
          file, line, key));
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

std::string Study::label_path(const std::string& d, const std::string& stem) const {
  return (fs::path(root) / d / "labels" / (stem + ".txt")).string();
}

std::string Study::prediction_path(const std::string& d, const std::string& model, const std::string& stem) const {
  return (fs::path(root) / d / "predictions" / model / (stem + ".txt")).string();
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
    throw StudyError(fmt::format("{}: {} name '{}' {}", printable_name(where.string()), what, printable_name(name), why));
}

// Every entry of a directory; one that can't be read is an error, never an empty directory.
std::vector<fs::directory_entry> list_directory(const fs::path& dir) {
  std::vector<fs::directory_entry> out;
  std::error_code ec;
  for (fs::directory_iterator it(dir, ec); !ec && it != fs::directory_iterator(); it.increment(ec)) out.push_back(*it);
  if (ec) throw StudyError(fmt::format("{}: cannot read the directory: {}", dir.string(), ec.message()));
  return out;
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
  if (kind_of(yaml) != FileKind::kMissing) {
    try {
      s.config = parse_study_config(read_file(yaml.string(), kMaxStudyYamlBytes), yaml.string());
    } catch (const IoError& e) {
      throw StudyError(e.what());
    }
  }
  std::vector<std::string> names;
  for (const auto& e : list_directory(root)) {
    const std::string name = e.path().filename().string();
    if (name == "pairs" || name.empty() || name[0] == '.') continue;
    if (kind_of(e.path()) != FileKind::kDirectory) continue;
    if (kind_of(e.path() / "labels") == FileKind::kDirectory) names.push_back(name);
  }
  if (names.empty())
    throw StudyError(root_in + ": no domains found (expected subdirectories like real/labels/ with YOLO label files)");
  for (const auto& want : s.config.domain_order)
    if (std::find(names.begin(), names.end(), want) == names.end())
      throw StudyError(fmt::format("{}: study.yaml lists domain '{}' but there is no {}/labels/ directory",
                                   root_in, want, want));
  // Configured order first, then "real", then alphabetical.
  auto rank = [&](const std::string& n) {
    const auto p = std::find(s.config.domain_order.begin(), s.config.domain_order.end(), n);
    if (p != s.config.domain_order.end()) return static_cast<int>(p - s.config.domain_order.begin());
    return n == "real" ? 1000 : 2000;
  };
  std::sort(names.begin(), names.end(), [&](const auto& x, const auto& y) {
    return std::make_pair(rank(x), x) < std::make_pair(rank(y), y);
  });
  std::set<std::string> all_models;
  for (const auto& name : names) {
    Domain d;
    d.name = name;
    d.dir = (root / name).string();
    check_name(root / name, name, "domain", kMaxDomainNameBytes);
    std::set<std::string> stems;
    for (const auto& f : list_directory(root / name / "labels")) {
      if (f.path().extension() != ".txt" || f.path().filename() == "classes.txt") continue;
      check_name(f.path(), f.path().stem().string(), "scene", kMaxStemBytes);
      stems.insert(f.path().stem().string());
    }
    if (kind_of(root / name / "images") == FileKind::kDirectory) {
      for (const auto& f : list_directory(root / name / "images")) {
        if (!kImageExtensions.count(lower(f.path().extension().string()))) continue;
        const std::string stem = f.path().stem().string();
        check_name(f.path(), stem, "scene", kMaxStemBytes);
        stems.insert(stem);
        d.images[stem] = f.path().string();
      }
    }
    if (kind_of(root / name / "predictions") == FileKind::kDirectory) {
      for (const auto& m : list_directory(root / name / "predictions")) {
        if (kind_of(m.path()) != FileKind::kDirectory) continue;
        check_name(m.path(), m.path().filename().string(), "model", kMaxModelNameBytes);
        d.models.push_back(m.path().filename().string());
        all_models.insert(d.models.back());
      }
      std::sort(d.models.begin(), d.models.end());
    }
    d.stems.assign(stems.begin(), stems.end());
    s.domains.push_back(std::move(d));
  }
  for (const auto& [m, dom] : s.config.trained_on) {
    if (!dom.empty() && !s.domain(dom))
      throw StudyError(fmt::format("{}: study.yaml says model '{}' was trained on '{}', which is not a domain here",
                                   root_in, m, dom));
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
  return s;
}

SceneMatch match_scenes(const Domain& a, const Domain& b) {
  SceneMatch m;
  std::set_intersection(a.stems.begin(), a.stems.end(), b.stems.begin(), b.stems.end(), std::back_inserter(m.common));
  std::set_difference(a.stems.begin(), a.stems.end(), b.stems.begin(), b.stems.end(), std::back_inserter(m.only_a));
  std::set_difference(b.stems.begin(), b.stems.end(), a.stems.begin(), a.stems.end(), std::back_inserter(m.only_b));
  return m;
}

namespace {

constexpr int kMaxJsonDepth = 16;  // {"pairs": [[i, j]]} needs 3

// A rock index within [0, limit), without narrowing (4294967296 is not 0).
bool as_index(const nlohmann::json& v, int limit, int* out) {
  long long x = -1;
  if (v.is_number_unsigned()) {
    const auto u = v.get<std::uint64_t>();
    if (u >= static_cast<std::uint64_t>(limit)) return false;
    x = static_cast<long long>(u);
  } else if (v.is_number_integer()) {
    x = v.get<std::int64_t>();
  } else {
    return false;
  }
  if (x < 0 || x >= limit) return false;
  *out = static_cast<int>(x);
  return true;
}

FixedPairs parse_fixed_pairs(const std::string& text, const std::string& file, bool swapped, int count_a,
                             int count_b) {
  const nlohmann::json j = parse_json_input(text, file, "{\"pairs\": [[i, j], ...]}", kMaxJsonDepth);
  if (!j.is_object() || !j.contains("pairs") || !j["pairs"].is_array())
    throw StudyError(file + ": expected an object with a \"pairs\" array, like {\"pairs\": [[0, 2], [1, 0]]}");
  for (const auto& item : j.items())
    if (item.key() != "pairs" && item.key() != "excluded_a" && item.key() != "excluded_b")
      throw StudyError(fmt::format("{}: unknown key \"{}\" (expected pairs, excluded_a, excluded_b)", file,
                                   item.key().size() > 40 ? item.key().substr(0, 37) + "..." : item.key()));
  FixedPairs fp;
  // The file's own order: first index belongs to the first domain of its directory name.
  const int n_first = swapped ? count_b : count_a, n_second = swapped ? count_a : count_b;
  std::set<int> used_first, used_second;
  int k = 0;
  for (const auto& p : j["pairs"]) {
    if (!p.is_array() || p.size() != 2 || !p[0].is_number_integer() || !p[1].is_number_integer())
      throw StudyError(fmt::format("{}: pair {} must be two integer rock indices, found {}", file, k + 1, describe_json(p)));
    int x = -1, y = -1;
    if (!as_index(p[0], n_first, &x) || !as_index(p[1], n_second, &y))
      throw StudyError(fmt::format("{}: pair {} [{}, {}] is out of range: the images have {} and {} rocks", file,
                                   k + 1, describe_json(p[0]), describe_json(p[1]), n_first, n_second));
    if (!used_first.insert(x).second || !used_second.insert(y).second)
      throw StudyError(fmt::format("{}: pair {} [{}, {}] uses a rock that is already paired", file, k + 1, x, y));
    fp.pairs.emplace_back(swapped ? y : x, swapped ? x : y);
    ++k;
  }
  auto read_excluded = [&](const char* key, int limit, std::vector<int>* out) {
    if (!j.contains(key)) return;
    if (!j[key].is_array()) throw StudyError(fmt::format("{}: \"{}\" must be an array of rock indices", file, key));
    for (const auto& v : j[key]) {
      int x = -1;
      if (!as_index(v, limit, &x))
        throw StudyError(fmt::format("{}: \"{}\" holds {}, expected a rock index below {}", file, key, describe_json(v), limit));
      out->push_back(x);
    }
  };
  read_excluded("excluded_a", n_first, swapped ? &fp.excluded_b : &fp.excluded_a);
  read_excluded("excluded_b", n_second, swapped ? &fp.excluded_a : &fp.excluded_b);
  std::sort(fp.pairs.begin(), fp.pairs.end());
  return fp;
}

}  // namespace

std::optional<FixedPairs> read_fixed_pairs(const Study& study, const std::string& a, const std::string& b,
                                           const std::string& stem, int count_a, int count_b,
                                           std::vector<std::string>* warnings) {
  std::optional<FixedPairs> found;
  fs::path found_path;
  for (const bool swapped : {false, true}) {
    const fs::path p = fs::path(swapped ? study.pairs_dir(b, a) : study.pairs_dir(a, b)) / (stem + ".json");
    try {
      if (file_kind(p.string()) == FileKind::kMissing) continue;  // a dangling link or no access: IoError
      if (found) {
        // Both orders exist (e.g. a save interrupted before it removed the old name): the first one counts.
        if (warnings)
          warnings->push_back(fmt::format("{}: ignored: {} holds this scene's pairs too and is read first; remove one",
                                          p.string(), found_path.string()));
        break;
      }
      found = parse_fixed_pairs(read_file(p.string(), kMaxPairsFileBytes), p.string(), swapped, count_a, count_b);
      found_path = p;
    } catch (const IoError& e) {
      throw StudyError(e.what());
    }
  }
  return found;
}

std::string fixed_pairs_json(const FixedPairs& fp) {
  nlohmann::json j;
  j["pairs"] = nlohmann::json::array();
  for (const auto& [x, y] : fp.pairs) j["pairs"].push_back({x, y});
  if (!fp.excluded_a.empty()) j["excluded_a"] = fp.excluded_a;
  if (!fp.excluded_b.empty()) j["excluded_b"] = fp.excluded_b;
  return j.dump() + "\n";
}

void write_fixed_pairs(const Study& study, const std::string& a, const std::string& b, const std::string& stem,
                       const FixedPairs& fp) {
  write_file_atomically((fs::path(study.pairs_dir(a, b)) / (stem + ".json")).string(), fixed_pairs_json(fp));
}

}  // namespace ipd
