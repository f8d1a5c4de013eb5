#include "ipd/study.h"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <filesystem>
#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <set>

#include "ipd/atomic_file.h"

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
  YAML::Node root;
  try {
    root = YAML::Load(text);
  } catch (const YAML::ParserException& e) {
    throw StudyError(fmt::format("{}:{}: invalid YAML: {}", file, e.mark.line + 1, e.msg));
  }
  if (!root || root.IsNull()) return c;
  if (!root.IsMap()) throw StudyError(file + ": expected a mapping of settings at the top level");
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
      for (const auto& m : v) {
        const std::string name = m.first.as<std::string>();
        if (!m.second.IsMap() && !m.second.IsNull())
          throw StudyError(fmt::format("{}:{}: models.{} must be a mapping like {{trained_on: real}}", file,
                                       m.first.Mark().line + 1, name));
        const YAML::Node& t = m.second["trained_on"];
        c.trained_on[name] = t ? yaml_get<std::string>(t, file, "trained_on") : "";
      }
    } else if (key == "registration") {
      if (!v.IsMap()) throw StudyError(fmt::format("{}:{}: registration must be a mapping", file, line));
      for (const auto& r : v) {
        const std::string k = r.first.as<std::string>();
        if (k == "method") {
          const std::string name = yaml_get<std::string>(r.second, file, "registration.method");
          if (!parse_method(name, &c.registration.method))
            throw StudyError(fmt::format("{}:{}: unknown registration method '{}' (expected paper, consensus or cpd)",
                                         file, r.first.Mark().line + 1, name));
        } else if (k == "seed") {
          c.registration.seed = yaml_get<std::uint64_t>(r.second, file, "registration.seed");
        } else if (k == "trials") {
          c.registration.max_trials = yaml_get<int>(r.second, file, "registration.trials");
        } else if (k == "gate") {
          c.registration.pair_gate = yaml_get<double>(r.second, file, "registration.gate");
        } else {
          throw StudyError(fmt::format("{}:{}: unknown registration setting '{}' (expected method, seed, trials, gate)",
                                       file, r.first.Mark().line + 1, k));
        }
      }
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

Study open_study(const std::string& root_in) {
  std::error_code ec;
  const fs::path root(root_in);
  if (!fs::exists(root, ec)) throw StudyError(root_in + ": no such study directory");
  if (!fs::is_directory(root, ec)) throw StudyError(root_in + ": is not a directory, expected a study directory");
  Study s;
  s.root = root.string();
  const fs::path yaml = root / "study.yaml";
  if (fs::exists(yaml, ec)) {
    try {
      s.config = parse_study_config(read_file(yaml.string()), yaml.string());
    } catch (const IoError& e) {
      throw StudyError(e.what());
    }
  }
  std::vector<std::string> names;
  fs::directory_iterator it(root, ec);
  if (ec) throw StudyError(fmt::format("{}: cannot read the study directory: {}", root_in, ec.message()));
  for (const auto& e : it) {
    if (!e.is_directory(ec)) continue;
    const std::string name = e.path().filename().string();
    if (name == "pairs" || name.empty() || name[0] == '.') continue;
    if (fs::is_directory(e.path() / "labels", ec)) names.push_back(name);
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
    std::set<std::string> stems;
    for (const auto& f : fs::directory_iterator(root / name / "labels", ec))
      if (f.path().extension() == ".txt" && f.path().filename() != "classes.txt") stems.insert(f.path().stem().string());
    if (fs::is_directory(root / name / "images", ec)) {
      for (const auto& f : fs::directory_iterator(root / name / "images", ec)) {
        if (!kImageExtensions.count(lower(f.path().extension().string()))) continue;
        const std::string stem = f.path().stem().string();
        stems.insert(stem);
        d.images[stem] = f.path().string();
      }
    }
    if (fs::is_directory(root / name / "predictions", ec)) {
      for (const auto& m : fs::directory_iterator(root / name / "predictions", ec)) {
        if (!m.is_directory(ec)) continue;
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

FixedPairs parse_fixed_pairs(const std::string& text, const std::string& file, bool swapped, int count_a,
                             int count_b) {
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(text);
  } catch (const nlohmann::json::parse_error& e) {
    throw StudyError(fmt::format("{}: invalid JSON at byte {}: expected {{\"pairs\": [[i, j], ...]}}", file, e.byte));
  }
  if (!j.is_object() || !j.contains("pairs") || !j["pairs"].is_array())
    throw StudyError(file + ": expected an object with a \"pairs\" array, like {\"pairs\": [[0, 2], [1, 0]]}");
  FixedPairs fp;
  // The file's own order: first index belongs to the first domain of its directory name.
  const int n_first = swapped ? count_b : count_a, n_second = swapped ? count_a : count_b;
  std::set<int> used_first, used_second;
  int k = 0;
  for (const auto& p : j["pairs"]) {
    if (!p.is_array() || p.size() != 2 || !p[0].is_number_integer() || !p[1].is_number_integer())
      throw StudyError(fmt::format("{}: pair {} must be two integer rock indices, found {}", file, k + 1, p.dump()));
    const int x = p[0].get<int>(), y = p[1].get<int>();
    if (x < 0 || x >= n_first || y < 0 || y >= n_second)
      throw StudyError(fmt::format("{}: pair {} [{}, {}] is out of range: the images have {} and {} rocks", file,
                                   k + 1, x, y, n_first, n_second));
    if (!used_first.insert(x).second || !used_second.insert(y).second)
      throw StudyError(fmt::format("{}: pair {} [{}, {}] uses a rock that is already paired", file, k + 1, x, y));
    fp.pairs.emplace_back(swapped ? y : x, swapped ? x : y);
    ++k;
  }
  auto read_excluded = [&](const char* key, int limit, std::vector<int>* out) {
    if (!j.contains(key)) return;
    if (!j[key].is_array()) throw StudyError(fmt::format("{}: \"{}\" must be an array of rock indices", file, key));
    for (const auto& v : j[key]) {
      if (!v.is_number_integer() || v.get<int>() < 0 || v.get<int>() >= limit)
        throw StudyError(fmt::format("{}: \"{}\" holds {}, expected a rock index below {}", file, key, v.dump(), limit));
      out->push_back(v.get<int>());
    }
  };
  read_excluded("excluded_a", n_first, swapped ? &fp.excluded_b : &fp.excluded_a);
  read_excluded("excluded_b", n_second, swapped ? &fp.excluded_a : &fp.excluded_b);
  std::sort(fp.pairs.begin(), fp.pairs.end());
  return fp;
}

}  // namespace

std::optional<FixedPairs> read_fixed_pairs(const Study& study, const std::string& a, const std::string& b,
                                           const std::string& stem, int count_a, int count_b) {
  std::error_code ec;
  for (const bool swapped : {false, true}) {
    const fs::path p = fs::path(swapped ? study.pairs_dir(b, a) : study.pairs_dir(a, b)) / (stem + ".json");
    if (!fs::exists(p, ec)) continue;
    try {
      return parse_fixed_pairs(read_file(p.string()), p.string(), swapped, count_a, count_b);
    } catch (const IoError& e) {
      throw StudyError(e.what());
    }
  }
  return std::nullopt;
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
