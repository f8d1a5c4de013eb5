#include "core/session/review_state.h"

#include <fmt/format.h>
#include <algorithm>
#include <array>
#include <filesystem>
#include <nlohmann/json.hpp>

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

bool same_box(const Box& b, const std::array<double, 4>& v) {
  return b.cx == v[0] && b.cy == v[1] && b.w == v[2] && b.h == v[3];
}

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
    const nlohmann::json j = parse_json_input(text, file_, kExpected, kMaxJsonDepth);
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
      const std::string stem = scene_name(v, "\"reviewed\"");
      const int k = scene_of(stem);
      if (k < 0)
        problem(stem, fmt::format("the review mark of scene {} is dropped: {} - {} has no such scene", describe_json(v),
                                  a_, b_));
      else if (!out_->state.reviewed[k])
        out_->state.toggle_reviewed(k);
    }
  }

  void checked(const nlohmann::json& list) {
    if (!list.is_array())
      throw StudyError(file_ + ": \"checked\" must be an array of {\"scene\", \"rock_a\", \"rock_b\"}");
    for (const auto& c : list) {
      const bool shape =
          c.is_object() && c.size() == 3 && c.contains("scene") && c.contains("rock_a") && c.contains("rock_b");
      if (!shape)
        throw StudyError(
            fmt::format("{}: \"checked\" holds {}, expected {{\"scene\": s, \"rock_a\": [cx, cy, w, h], "
                        "\"rock_b\": [cx, cy, w, h]}}",
                        file_, describe_json(c)));
      const std::string stem = scene_name(c["scene"], "\"checked\"");
      const auto box_a = parse_box(c["rock_a"], "rock_a", file_), box_b = parse_box(c["rock_b"], "rock_b", file_);
      const int k = scene_of(stem);
      if (k < 0) {
        problem(stem, fmt::format("the check of a pair in scene {} is dropped: {} - {} has no such scene",
                                  describe_json(c["scene"]), a_, b_));
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
      if (!found)
        problem(stem, fmt::format("the check of the pair {} | {} in scene {} is dropped: those rocks are no longer "
                                  "a pair (look at it again)",
                                  box_text(box_a), box_text(box_b), describe_json(c["scene"])));
    }
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
  return reviewed_scenes == 0 && std::all_of(checked.begin(), checked.end(), [](const auto& c) { return c.empty(); });
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

std::string review_json(const ReviewState& state, const ReviewScenes& scenes) {
  nlohmann::ordered_json j;
  j["reviewed"] = nlohmann::ordered_json::array();
  j["checked"] = nlohmann::ordered_json::array();
  for (size_t k = 0; k < state.reviewed.size(); ++k)
    if (state.reviewed[k]) j["reviewed"].push_back(scenes.stems[k]);
  for (size_t k = 0; k < state.checked.size(); ++k) {
    const int scene = static_cast<int>(k);
    const RockPairs& now = scenes.pairs(scene);
    for (const auto& [a, b] : state.checked[k]) {
      // A check of a pair since edited away is not written: it was about rocks that are no longer paired.
      if (std::find(now.begin(), now.end(), std::make_pair(a, b)) == now.end()) continue;
      const Box& ba = scenes.gt(scene, true).at(a);
      const Box& bb = scenes.gt(scene, false).at(b);
      nlohmann::ordered_json c;
      c["scene"] = scenes.stems[k];
      c["rock_a"] = {ba.cx, ba.cy, ba.w, ba.h};
      c["rock_b"] = {bb.cx, bb.cy, bb.w, bb.h};
      j["checked"].push_back(std::move(c));
    }
  }
  return dump_json_output(j) + "\n";
}

}  // namespace ipd
