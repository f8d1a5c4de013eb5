#include "core/session/review_state.h"

#include <fmt/format.h>
#include <algorithm>
#include <array>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "core/study/fixed_pairs.h"
#include "core/study/hand_work_class.h"
#include "core/study/study.h"
#include "core/util/contained_file.h"
#include "core/util/errors.h"
#include "core/util/json_input.h"
#include "core/util/json_output.h"

namespace fs = std::filesystem;

namespace ipd {

namespace {

constexpr int kMaxJsonDepth = 8;  // {"checked": [{"rock_a": [cx, ...]}]} needs 4
constexpr const char* kExpected =
    "{\"reviewed\": [scene, ...], \"checked\": [{\"scene\": s, \"rock_a\": [cx, cy, w, h], \"rock_b\": [...]}]}";

// The rock's box, within the tolerance fixed pairs use (fixed_pairs.h: kSameRockTolerance).
bool same_box(const Box& b, const std::array<double, 4>& v) { return same_rock_box(b, v[0], v[1], v[2], v[3]); }

std::array<double, 4> parse_box(const nlohmann::json& j, const char* key, const std::string& file) {
  const bool numbers =
      j.is_array() && j.size() == 4 && std::all_of(j.begin(), j.end(), [](const auto& v) { return v.is_number(); });
  if (!numbers)
    throw StudyError(fmt::format("{}: \"{}\" holds {}, expected a box [cx, cy, w, h]", file, key, describe_json(j)));
  return {j[0].get<double>(), j[1].get<double>(), j[2].get<double>(), j[3].get<double>()};
}

std::string box_text(const std::array<double, 4>& v) { return fmt::format("({} {} {} {})", v[0], v[1], v[2], v[3]); }

class ReviewParser {
 public:
  ReviewParser(std::string file, const std::string& a, const std::string& b, const ReviewScenes& scenes,
               ReviewRead* out)
      : file_(std::move(file)), a_(a), b_(b), scenes_(scenes), out_(out) {}

  void parse(const std::string& text) {
    const nlohmann::json j = parse_json_input(text, file_, kExpected, kMaxJsonDepth, kMaxHandWorkJsonValues);
    if (!j.is_object()) throw StudyError(file_ + ": expected an object like " + kExpected);
    for (const auto& item : j.items())
      if (item.key() != "reviewed" && item.key() != "checked")
        throw StudyError(
            fmt::format("{}: unknown key {} (expected reviewed, checked)", file_, describe_json(item.key())));
    if (j.contains("reviewed")) reviewed(j["reviewed"]);
    if (j.contains("checked")) checked(j["checked"]);
  }

 private:
  int scene_of(const std::string& stem) const {
    const auto& s = scenes_.stems;
    const auto it = std::lower_bound(s.begin(), s.end(), stem);
    return it != s.end() && *it == stem ? static_cast<int>(it - s.begin()) : -1;
  }
  void problem(const std::string& stem, std::string message) {
    Problem p;
    p.file = file_;
    p.domain = a_;
    p.other_domain = b_;
    p.scene = stem;
    p.message = std::move(message);
    out_->problems.push_back(std::move(p));
  }
  std::string scene_name(const nlohmann::json& v, const char* where) const {
    if (!v.is_string())
      throw StudyError(fmt::format("{}: {} holds {}, expected a scene name", file_, where, describe_json(v)));
    return v.get<std::string>();
  }

  void reviewed(const nlohmann::json& list) {
    if (!list.is_array()) throw StudyError(file_ + ": \"reviewed\" must be an array of scene names");
    for (const auto& v : list) {
      std::optional<int> cls;
      const nlohmann::json* name = &v;
      if (v.is_object()) {
        const bool shape = v.contains("scene") && v.size() == (v.contains("class") ? 2u : 1u);
        if (!shape)
          throw StudyError(
              fmt::format("{}: \"reviewed\" holds {}, expected a scene name or {{\"scene\": s, "
                          "\"class\": N}}",
                          file_, describe_json(v)));
        name = &v["scene"];
        if (v.contains("class")) cls = parse_hand_work_class(v["class"], file_, "the \"class\" of a review mark");
      }
      const std::string stem = scene_name(*name, "\"reviewed\"");
      if (is_other_class_work(cls, scenes_.shown_class)) {
        out_->state.kept_reviewed.push_back({stem, cls});  // another class's audit: kept, not this class's
        continue;
      }
      const int k = scene_of(stem);
      if (k < 0) {
        problem(stem, fmt::format("the review mark of scene {} does not apply now: {} - {} has no such scene (kept in "
                                  "the file)",
                                  describe_json(*name), a_, b_));
        out_->state.kept_reviewed.push_back({stem, cls});
      } else if (!out_->state.reviewed[k]) {
        out_->state.toggle_reviewed(k);
      }
    }
  }

  void checked(const nlohmann::json& list) {
    if (!list.is_array())
      throw StudyError(file_ + ": \"checked\" must be an array of {\"scene\", \"rock_a\", \"rock_b\"}");
    for (const auto& c : list) {
      const bool shape = c.is_object() && c.size() == (c.contains("class") ? 4u : 3u) && c.contains("scene") &&
                         c.contains("rock_a") && c.contains("rock_b");
      if (!shape)
        throw StudyError(
            fmt::format("{}: \"checked\" holds {}, expected {{\"scene\": s, \"rock_a\": [cx, cy, w, h], "
                        "\"rock_b\": [cx, cy, w, h]}} (and \"class\": N in a study of several classes)",
                        file_, describe_json(c)));
      const std::string stem = scene_name(c["scene"], "\"checked\"");
      const auto box_a = parse_box(c["rock_a"], "rock_a", file_), box_b = parse_box(c["rock_b"], "rock_b", file_);
      std::optional<int> cls;
      if (c.contains("class")) cls = parse_hand_work_class(c["class"], file_, "the \"class\" of a check");
      if (is_other_class_work(cls, scenes_.shown_class)) {
        out_->state.kept_checks.push_back({stem, box_a, box_b, cls, true});  // another class's pair: kept
        continue;
      }
      const int k = scene_of(stem);
      if (k < 0) {
        problem(stem, fmt::format("the check of a pair in scene {} does not apply now: {} - {} has no such scene "
                                  "(kept in the file)",
                                  describe_json(c["scene"]), a_, b_));
        out_->state.kept_checks.push_back({stem, box_a, box_b, cls, false});
        continue;
      }
      // The pair of the scene's current pairs whose rocks have these boxes (identical boxes are the same rock).
      bool found = false;
      for (const auto& [i, j] : scenes_.pairs(k))
        if (same_box(scenes_.gt(k, true).at(i), box_a) && same_box(scenes_.gt(k, false).at(j), box_b)) {
          if (!out_->state.is_checked(k, i, j)) out_->state.toggle_checked(k, i, j);
          found = true;
          break;
        }
      if (!found) {
        problem(stem, kept_check_message(k, box_a, box_b, describe_json(c["scene"])));
        out_->state.kept_checks.push_back({stem, box_a, box_b, cls, false});
      }
    }
  }

  // Why a check does not apply, in the words of the panes: rocks by their number from 1 when both are in the
  // label files (not a pair now), else which box is no longer there (a label file was edited).
  std::string kept_check_message(int k, const std::array<double, 4>& box_a, const std::array<double, 4>& box_b,
                                 const std::string& scene) const {
    const int i = rock_of(scenes_.gt(k, true), box_a), j = rock_of(scenes_.gt(k, false), box_b);
    if (i >= 0 && j >= 0)
      return fmt::format(
          "the check of the pair {} rock {} | {} rock {} in scene {} does not apply now: those rocks "
          "are not a pair now (kept in the file: it applies again when they are)",
          a_, i + 1, b_, j + 1, scene);
    std::string gone;
    if (i < 0) gone = fmt::format("{}'s box {}", a_, box_text(box_a));
    if (j < 0) gone += fmt::format("{}{}'s box {}", gone.empty() ? "" : " and ", b_, box_text(box_b));
    return fmt::format(
        "the check of the pair {} | {} in scene {} does not apply now: {} {} no longer in its label "
        "file (moved or deleted; kept in the file: it applies again if the box comes back)",
        box_text(box_a), box_text(box_b), scene, gone, i < 0 && j < 0 ? "are" : "is");
  }
  static int rock_of(const std::vector<Box>& gt, const std::array<double, 4>& box) {
    for (size_t r = 0; r < gt.size(); ++r)
      if (same_box(gt[r], box)) return static_cast<int>(r);
    return -1;
  }

  std::string file_;
  const std::string &a_, &b_;
  const ReviewScenes& scenes_;
  ReviewRead* out_;
};

}  // namespace

int ReviewState::checked_pairs() const {
  int n = 0;
  for (const RockPairs& c : checked) n += static_cast<int>(c.size());
  return n;
}

bool ReviewState::empty() const {
  return reviewed_scenes == 0 && kept_reviewed.empty() && kept_checks.empty() &&
         std::all_of(checked.begin(), checked.end(), [](const auto& c) { return c.empty(); });
}

bool ReviewState::apply_kept_checks(int scene, const std::string& stem, const std::vector<Box>& gt_a,
                                    const std::vector<Box>& gt_b, const RockPairs& pairs) {
  const size_t before = kept_checks.size();
  auto applies = [&](const KeptCheck& k) {
    if (k.scene != stem || k.other_class) return false;
    for (const auto& [i, j] : pairs)
      if (same_box(gt_a.at(i), k.rock_a) && same_box(gt_b.at(j), k.rock_b)) {
        if (!is_checked(scene, i, j)) toggle_checked(scene, i, j);
        return true;
      }
    return false;
  };
  kept_checks.erase(std::remove_if(kept_checks.begin(), kept_checks.end(), applies), kept_checks.end());
  return kept_checks.size() != before;
}

bool ReviewState::is_checked(int scene, int a, int b) const {
  const auto& c = checked[scene];
  return std::binary_search(c.begin(), c.end(), std::make_pair(a, b));
}

bool ReviewState::toggle_reviewed(int scene) {
  reviewed[scene] = !reviewed[scene];
  reviewed_scenes += reviewed[scene] ? 1 : -1;
  return reviewed[scene];
}

bool ReviewState::toggle_checked(int scene, int a, int b) {
  auto& c = checked[scene];
  const auto it = std::lower_bound(c.begin(), c.end(), std::make_pair(a, b));
  if (it != c.end() && *it == std::make_pair(a, b)) {
    c.erase(it);
    return false;
  }
  c.insert(it, {a, b});
  return true;
}

std::string review_relative_path(const std::string& a, const std::string& b) {
  return "review/" + a + "__" + b + ".json";
}

ReviewRead load_review(const std::string& root, const std::string& a, const std::string& b,
                       const ReviewScenes& scenes) {
  ReviewRead out{ReviewState(scenes.stems.size()), {}, {}};
  const std::string rel = review_relative_path(a, b);
  const std::string shown = (fs::path(root) / rel).string();
  try {
    out.text = read_file_beneath(root, rel, kMaxPairsFileBytes);
  } catch (const IoError& e) {
    throw StudyError(e.what());
  }
  if (out.text) ReviewParser(shown, a, b, scenes, &out).parse(*out.text);
  return out;
}

void ReviewScenes::take_class_of(const Study& study) {
  shown_class = study.config.rock_class;
  written_class = hand_work_class(study);
}

std::string review_json(const ReviewState& state, const ReviewScenes& scenes) {
  nlohmann::ordered_json j;
  j["reviewed"] = nlohmann::ordered_json::array();
  j["checked"] = nlohmann::ordered_json::array();
  auto reviewed = [](const std::string& stem, std::optional<int> cls) {
    if (!cls) return nlohmann::ordered_json(stem);
    nlohmann::ordered_json r;
    r["scene"] = stem;
    r["class"] = hand_work_class_json(*cls);
    return r;
  };
  for (size_t k = 0; k < state.reviewed.size(); ++k)
    if (state.reviewed[k]) j["reviewed"].push_back(reviewed(scenes.stems[k], scenes.written_class));
  for (const KeptReviewed& r : state.kept_reviewed) j["reviewed"].push_back(reviewed(r.scene, r.cls));
  auto check = [](const std::string& stem, const std::array<double, 4>& a, const std::array<double, 4>& b,
                  std::optional<int> cls) {
    nlohmann::ordered_json c;
    c["scene"] = stem;
    c["rock_a"] = a;
    c["rock_b"] = b;
    if (cls) c["class"] = hand_work_class_json(*cls);
    return c;
  };
  auto box = [](const Box& b) { return std::array<double, 4>{b.cx, b.cy, b.w, b.h}; };
  for (size_t k = 0; k < state.checked.size(); ++k) {
    const int scene = static_cast<int>(k);
    // Also a check of a pair edited away since: the user's record, which applies again if the pair comes back.
    for (const auto& [a, b] : state.checked[k])
      j["checked"].push_back(check(scenes.stems[k], box(scenes.gt(scene, true).at(a)),
                                   box(scenes.gt(scene, false).at(b)), scenes.written_class));
  }
  for (const KeptCheck& c : state.kept_checks) j["checked"].push_back(check(c.scene, c.rock_a, c.rock_b, c.cls));
  return dump_json_output(j) + "\n";
}

}  // namespace ipd
