#include "core/study/fixed_pairs.h"

#include <fmt/format.h>
#include <algorithm>
#include <climits>
#include <cmath>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <set>

#include "core/study/hand_work_class.h"
#include "core/study/study.h"
#include "core/util/contained_file.h"
#include "core/util/json_input.h"

namespace fs = std::filesystem;

namespace ipd {

DiskVersion version_of(const std::optional<std::string>& contents) {
  DiskVersion v;
  if (!contents) return v;
  v.present = true;
  v.hash = 1469598103934665603ull;  // FNV-1a: a change detector, not a defence against forgery
  for (const unsigned char c : *contents) v.hash = (v.hash ^ c) * 1099511628211ull;
  return v;
}

bool same_rock_box(const Box& b, double cx, double cy, double w, double h) {
  return std::abs(b.cx - cx) <= kSameRockTolerance && std::abs(b.cy - cy) <= kSameRockTolerance &&
         std::abs(b.w - w) <= kSameRockTolerance && std::abs(b.h - h) <= kSameRockTolerance;
}

bool FixedPairsRead::unusable() const {
  return std::any_of(problems.begin(), problems.end(), [](const PairsProblem& p) { return p.unusable; });
}

std::string fixed_pairs_relative_path(const std::string& a, const std::string& b, const std::string& stem) {
  return "pairs/" + a + "__" + b + "/" + stem + ".json";
}

namespace {

constexpr int kMaxJsonDepth = 16;  // {"rocks_a": [[i, cx, cy, w, h]]} needs 3
constexpr size_t kMaxListed = 4;   // rocks named in one message

struct StoredBox {
  double cx, cy, w, h;
  bool matches(const Box& b) const { return same_rock_box(b, cx, cy, w, h); }
  // How far `b` is from this box: the largest difference of a coordinate.
  double distance(const Box& b) const {
    return std::max({std::abs(b.cx - cx), std::abs(b.cy - cy), std::abs(b.w - w), std::abs(b.h - h)});
  }
};

// A rock index >= 0, without narrowing (4294967296 is not 0).
bool as_index(const nlohmann::json& v, int* out) {
  if (v.is_number_unsigned()) {
    const auto u = v.get<std::uint64_t>();
    if (u > static_cast<std::uint64_t>(INT_MAX)) return false;
    *out = static_cast<int>(u);
    return true;
  }
  if (!v.is_number_integer() || v.get<std::int64_t>() < 0 || v.get<std::int64_t>() > INT_MAX) return false;
  *out = static_cast<int>(v.get<std::int64_t>());
  return true;
}

// One side of a pairs file, in the file's own order: the domain, its rocks now, what the file stores.
struct SideInFile {
  std::string domain, label_file;
  const std::vector<Box>* gt = nullptr;
  std::vector<int> excluded;
  std::optional<std::map<int, StoredBox>> stored;  // nullopt: a file without boxes for this side
  std::map<int, int> moved;                        // file index -> row now
  std::vector<std::string> lost;                   // "the box saved from line 4 (0.6 0.6 0.1 0.1)"
};

std::map<int, StoredBox> parse_rocks(const nlohmann::json& j, const char* key, const std::string& file) {
  std::map<int, StoredBox> out;
  if (!j.is_array()) throw StudyError(fmt::format("{}: \"{}\" must be an array of [index, cx, cy, w, h]", file, key));
  for (const auto& r : j) {
    int idx = -1;
    const bool numbers = r.is_array() && r.size() == 5 &&
                         std::all_of(r.begin() + 1, r.end(), [](const auto& v) { return v.is_number(); });
    if (!numbers || !as_index(r[0], &idx))
      throw StudyError(
          fmt::format("{}: \"{}\" holds {}, expected [rock index, cx, cy, w, h]", file, key, describe_json(r)));
    const StoredBox box{r[1].get<double>(), r[2].get<double>(), r[3].get<double>(), r[4].get<double>()};
    if (!out.emplace(idx, box).second) throw StudyError(fmt::format("{}: \"{}\" gives rock {} twice", file, key, idx));
  }
  return out;
}

// Finds each referenced rock of a side with stored boxes: at its row if its box is still there (within
// kSameRockTolerance), else at the free row whose box is nearest to it within the tolerance, the first of
// equals (identical boxes are interchangeable rocks), else lost.
void bind_side(SideInFile* side, const std::set<int>& referenced, const char* key, const std::string& file) {
  const std::vector<Box>& gt = *side->gt;
  std::vector<char> claimed(gt.size(), 0);
  std::vector<int> unplaced;
  for (const int i : referenced) {
    const auto it = side->stored->find(i);
    if (it == side->stored->end())
      throw StudyError(fmt::format("{}: rock {} of '{}' is paired or excluded but has no box in \"{}\"", file, i,
                                   side->domain, key));
    if (i < static_cast<int>(gt.size()) && it->second.matches(gt[i]))
      claimed[i] = 1;
    else
      unplaced.push_back(i);
  }
  for (const int i : unplaced) {
    const StoredBox& want = side->stored->at(i);
    int found = -1;
    for (size_t r = 0; r < gt.size(); ++r)
      if (!claimed[r] && want.matches(gt[r]) && (found < 0 || want.distance(gt[r]) < want.distance(gt[found])))
        found = static_cast<int>(r);
    if (found >= 0) {
      claimed[found] = 1;
      side->moved[i] = found;
    } else {
      // By the label file's line it was saved from (the file stores 0-based indices) and its box: the panes show
      // a right rock in a pair by its pair's number, so "rock 15" alone would point at another box.
      side->lost.push_back(fmt::format("the box saved from line {} ({} {} {} {})", i + 1,
                                       nlohmann::json(want.cx).dump(), nlohmann::json(want.cy).dump(),
                                       nlohmann::json(want.w).dump(), nlohmann::json(want.h).dump()));
    }
  }
}

std::string moved_list(const SideInFile& s) {
  std::string out;
  size_t k = 0;
  for (const auto& [from, to] : s.moved) {
    if (k++ == kMaxListed) return out + ", ...";
    out += fmt::format("{}{} -> {}", out.empty() ? s.domain + " rock " : ", ", from + 1, to + 1);
  }
  return out;
}

std::string lost_list(const SideInFile& s) {
  std::string out;
  for (size_t k = 0; k < s.lost.size(); ++k) {
    if (k == kMaxListed) return out + fmt::format(" and {} more", s.lost.size() - k);
    out += (k ? ", " : "") + s.lost[k];
  }
  return fmt::format("{} of '{}' ({})", out, s.domain, s.label_file);
}

// The problems binding found: one line per file.
std::optional<PairsProblem> binding_problem(const SideInFile& first, const SideInFile& second,
                                            const std::string& file) {
  if (!first.lost.empty() || !second.lost.empty()) {
    std::string what;
    for (const SideInFile* s : {&first, &second})
      if (!s->lost.empty()) what += (what.empty() ? "" : "; ") + lost_list(*s);
    const std::string why = "a stored box is no longer in its label file (moved or deleted): " + what;
    return PairsProblem{file, 0, "hand pairs not used (registration counts instead): " + why, true, why};
  }
  if (first.moved.empty() && second.moved.empty()) return std::nullopt;
  std::string what;
  for (const SideInFile* s : {&first, &second})
    if (!s->moved.empty()) what += (what.empty() ? "" : "; ") + moved_list(*s);
  const size_t n = first.moved.size() + second.moved.size();
  return PairsProblem{file,
                      0,
                      fmt::format("{} hand-paired rock(s) changed rows in their label files and were found again "
                                  "by their boxes: {}",
                                  n, what),
                      false,
                      {}};
}

struct ParsedFile {
  RockPairs pairs;  // file order
  SideInFile first, second;
  std::optional<int> cls;  // the class the pairs are of ("class": N or "all"); none: every class
};

// `n1`, `n2`: the rocks in the label files now, for messages (a stored index may exceed them when the rock
// moved: binding decides that).
RockPairs parse_pair_list(const nlohmann::json& j, const std::string& file, size_t n1, size_t n2) {
  RockPairs out;
  std::set<int> used_first, used_second;
  int k = 0;
  for (const auto& p : j) {
    ++k;
    if (!p.is_array() || p.size() != 2 || !p[0].is_number_integer() || !p[1].is_number_integer())
      throw StudyError(
          fmt::format("{}: pair {} must be two integer rock indices, found {}", file, k, describe_json(p)));
    int x = -1, y = -1;
    if (!as_index(p[0], &x) || !as_index(p[1], &y))
      throw StudyError(fmt::format("{}: pair {} [{}, {}] is out of range: the images have {} and {} rocks", file, k,
                                   describe_json(p[0]), describe_json(p[1]), n1, n2));
    if (!used_first.insert(x).second || !used_second.insert(y).second)
      throw StudyError(fmt::format("{}: pair {} [{}, {}] uses a rock that is already paired", file, k, x, y));
    out.emplace_back(x, y);
  }
  return out;
}

// A rock listed twice is an error, as a rock paired twice is: it was counted twice ("2 rocks excluded").
std::vector<int> parse_excluded(const nlohmann::json& j, const char* key, const std::string& file, size_t n) {
  std::vector<int> out;
  if (!j.contains(key)) return out;
  if (!j[key].is_array()) throw StudyError(fmt::format("{}: \"{}\" must be an array of rock indices", file, key));
  std::set<int> seen;
  for (const auto& v : j[key]) {
    int x = -1;
    if (!as_index(v, &x))
      throw StudyError(
          fmt::format("{}: \"{}\" holds {}, expected a rock index below {}", file, key, describe_json(v), n));
    if (!seen.insert(x).second) throw StudyError(fmt::format("{}: \"{}\" lists rock {} twice", file, key, x));
    out.push_back(x);
  }
  return out;
}

// Range checks of a side read by index alone (a file without boxes), with the messages files always had.
void check_unbound_ranges(const ParsedFile& f, const std::string& file) {
  const int n1 = static_cast<int>(f.first.gt->size()), n2 = static_cast<int>(f.second.gt->size());
  int k = 0;
  for (const auto& [x, y] : f.pairs) {
    ++k;
    if ((!f.first.stored && x >= n1) || (!f.second.stored && y >= n2))
      throw StudyError(
          fmt::format("{}: pair {} [{}, {}] is out of range: the images have {} and {} rocks", file, k, x, y, n1, n2));
  }
  for (const auto& [side, key, n] :
       {std::make_tuple(&f.first, "excluded_a", n1), std::make_tuple(&f.second, "excluded_b", n2)}) {
    if (side->stored) continue;
    for (const int x : side->excluded)
      if (x >= n) throw StudyError(fmt::format("{}: \"{}\" holds {}, expected a rock index below {}", file, key, x, n));
  }
}

ParsedFile parse_file(const std::string& text, const std::string& file, size_t n1, size_t n2) {
  const nlohmann::json j =
      parse_json_input(text, file, "{\"pairs\": [[i, j], ...]}", kMaxJsonDepth, kMaxHandWorkJsonValues);
  if (!j.is_object() || !j.contains("pairs") || !j["pairs"].is_array())
    throw StudyError(file + ": expected an object with a \"pairs\" array, like {\"pairs\": [[0, 2], [1, 0]]}");
  static const std::set<std::string> kKeys = {"pairs", "excluded_a", "excluded_b", "rocks_a", "rocks_b", "class"};
  for (const auto& item : j.items())
    if (!kKeys.count(item.key()))
      throw StudyError(
          fmt::format("{}: unknown key \"{}\" (expected pairs, excluded_a, excluded_b, rocks_a, rocks_b, class)", file,
                      item.key().size() > 40 ? item.key().substr(0, 37) + "..." : item.key()));
  ParsedFile f;
  if (j.contains("class")) f.cls = parse_hand_work_class(j["class"], file, "\"class\"");
  f.pairs = parse_pair_list(j["pairs"], file, n1, n2);
  f.first.excluded = parse_excluded(j, "excluded_a", file, n1);
  f.second.excluded = parse_excluded(j, "excluded_b", file, n2);
  if (j.contains("rocks_a")) f.first.stored = parse_rocks(j["rocks_a"], "rocks_a", file);
  if (j.contains("rocks_b")) f.second.stored = parse_rocks(j["rocks_b"], "rocks_b", file);
  return f;
}

// Reads one pairs file and binds it to the rocks now in the label files; nullopt in `out` when unusable.
// `cls`: the class the study's numbers are about; a file of another class sets `other_class` and gives nothing.
std::optional<FixedPairs> parse_fixed_pairs(const std::string& text, const std::string& file, bool swapped,
                                            SideInFile first, SideInFile second, int cls, int* other_class,
                                            std::vector<PairsProblem>* problems) {
  ParsedFile f = parse_file(text, file, first.gt->size(), second.gt->size());
  // Hand pairs of another class index another class's rocks: not this class's pairs, and no problem of them.
  if (is_other_class_work(f.cls, cls)) {
    *other_class = *f.cls;
    return std::nullopt;
  }
  f.first.domain = first.domain, f.first.label_file = first.label_file, f.first.gt = first.gt;
  f.second.domain = second.domain, f.second.label_file = second.label_file, f.second.gt = second.gt;
  check_unbound_ranges(f, file);
  std::set<int> ref_first(f.first.excluded.begin(), f.first.excluded.end()),
      ref_second(f.second.excluded.begin(), f.second.excluded.end());
  for (const auto& [x, y] : f.pairs) ref_first.insert(x), ref_second.insert(y);
  if (f.first.stored) bind_side(&f.first, ref_first, "rocks_a", file);
  if (f.second.stored) bind_side(&f.second, ref_second, "rocks_b", file);
  if (auto p = binding_problem(f.first, f.second, file)) {
    problems->push_back(*p);
    if (p->unusable) return std::nullopt;
  }
  auto row = [](const SideInFile& s, int i) {
    const auto it = s.moved.find(i);
    return it == s.moved.end() ? i : it->second;
  };
  FixedPairs fp;
  for (const auto& [x, y] : f.pairs) {
    const int r1 = row(f.first, x), r2 = row(f.second, y);
    fp.pairs.emplace_back(swapped ? r2 : r1, swapped ? r1 : r2);
  }
  for (const int x : f.first.excluded) (swapped ? fp.excluded_b : fp.excluded_a).push_back(row(f.first, x));
  for (const int y : f.second.excluded) (swapped ? fp.excluded_a : fp.excluded_b).push_back(row(f.second, y));
  std::sort(fp.pairs.begin(), fp.pairs.end());
  std::sort(fp.excluded_a.begin(), fp.excluded_a.end());
  std::sort(fp.excluded_b.begin(), fp.excluded_b.end());
  return fp;
}

}  // namespace

FixedPairsRead load_fixed_pairs(const Study& study, const std::string& a, const std::string& b, const std::string& stem,
                                const std::vector<Box>& gt_a, const std::vector<Box>& gt_b) {
  FixedPairsRead out;
  std::string found_path;
  bool found = false;
  for (const bool swapped : {false, true}) {
    const std::string rel = swapped ? fixed_pairs_relative_path(b, a, stem) : fixed_pairs_relative_path(a, b, stem);
    const std::string shown = (fs::path(study.root) / rel).string();
    std::optional<std::string> text;
    try {
      text = read_file_beneath(study.root, rel, kMaxPairsFileBytes);
    } catch (const IoError& e) {
      throw StudyError(e.what());
    }
    (swapped ? out.version_ba : out.version_ab) = version_of(text);
    if (!text) continue;
    if (found) {
      // Both orders exist (e.g. a save interrupted before it removed the old name): the first one counts.
      out.problems.push_back(
          {shown,
           0,
           fmt::format("ignored: {} holds this scene's pairs too and is read first; remove one", found_path),
           false,
           {}});
      break;
    }
    SideInFile sa{a, study.label_path(a, stem), &gt_a, {}, {}, {}, {}};
    SideInFile sb{b, study.label_path(b, stem), &gt_b, {}, {}, {}, {}};
    const int cls = study.config.rock_class;
    out.pairs = swapped ? parse_fixed_pairs(*text, shown, true, sb, sa, cls, &out.other_class, &out.problems)
                        : parse_fixed_pairs(*text, shown, false, sa, sb, cls, &out.other_class, &out.problems);
    if (out.other_class != kNoClassChosen) out.other_class_file = shown;
    if (out.pairs)
      if (const auto why = pair_across_classes(*out.pairs, gt_a, gt_b, a, b, study.classes))
        throw StudyError(shown + ": " + *why);
    found = true;
    found_path = shown;
  }
  return out;
}

std::optional<FixedPairs> read_fixed_pairs(const Study& study, const std::string& a, const std::string& b,
                                           const std::string& stem, const std::vector<Box>& gt_a,
                                           const std::vector<Box>& gt_b, std::vector<std::string>* warnings) {
  FixedPairsRead r = load_fixed_pairs(study, a, b, stem, gt_a, gt_b);
  for (const auto& p : r.problems) {
    if (p.unusable) throw StudyError(p.to_string());
    if (warnings) warnings->push_back(p.to_string());
  }
  return std::move(r.pairs);
}

std::optional<std::string> pair_across_classes(const FixedPairs& fp, const std::vector<Box>& gt_a,
                                               const std::vector<Box>& gt_b, const std::string& a, const std::string& b,
                                               const StudyClasses& classes) {
  for (const auto& [x, y] : fp.pairs) {
    const int ca = gt_a.at(static_cast<size_t>(x)).cls, cb = gt_b.at(static_cast<size_t>(y)).cls;
    if (ca != cb)
      return fmt::format("pairs {} rock {} ({}) with {} rock {} ({}): a pair joins two rocks of one class", a, x + 1,
                         classes.name_of(ca), b, y + 1, classes.name_of(cb));
  }
  return std::nullopt;
}

std::string fixed_pairs_json(const FixedPairs& fp, const std::vector<Box>& gt_a, const std::vector<Box>& gt_b,
                             std::optional<int> cls) {
  nlohmann::json j;
  if (cls) j["class"] = hand_work_class_json(*cls);
  j["pairs"] = nlohmann::json::array();
  std::set<int> rocks_a(fp.excluded_a.begin(), fp.excluded_a.end()),
      rocks_b(fp.excluded_b.begin(), fp.excluded_b.end());
  for (const auto& [x, y] : fp.pairs) {
    j["pairs"].push_back({x, y});
    rocks_a.insert(x);
    rocks_b.insert(y);
  }
  if (!fp.excluded_a.empty()) j["excluded_a"] = fp.excluded_a;
  if (!fp.excluded_b.empty()) j["excluded_b"] = fp.excluded_b;
  // The boxes as doubles: nlohmann writes the shortest decimal that reads back to the same value.
  auto rocks = [](const std::set<int>& ids, const std::vector<Box>& gt) {
    nlohmann::json list = nlohmann::json::array();
    for (const int i : ids) {
      const Box& b = gt.at(static_cast<size_t>(i));
      list.push_back({i, b.cx, b.cy, b.w, b.h});
    }
    return list;
  };
  j["rocks_a"] = rocks(rocks_a, gt_a);
  j["rocks_b"] = rocks(rocks_b, gt_b);
  return j.dump() + "\n";
}

void write_fixed_pairs(const Study& study, const std::string& a, const std::string& b, const std::string& stem,
                       const FixedPairs& fp, const std::vector<Box>& gt_a, const std::vector<Box>& gt_b) {
  write_file_beneath(study.root, fixed_pairs_relative_path(a, b, stem),
                     fixed_pairs_json(fp, gt_a, gt_b, hand_work_class(study)));
}

Problem pairs_file_problem(const PairsProblem& w, const std::string& a, const std::string& b, const std::string& stem) {
  Problem q;
  q.file = w.file;
  q.line = w.line;
  q.message = w.message;
  q.unusable_pairs = w.unusable;
  q.pairs_file = true;
  q.domain = a;
  q.other_domain = b;
  q.scene = stem;
  return q;
}

}  // namespace ipd
