#include "core/report/provenance.h"

#include <fmt/format.h>

#include <algorithm>
#include <memory>
#include <optional>
#include <stdexcept>

#include "core/session/review_state.h"
#include "core/util/contained_file.h"

namespace ipd {

namespace {

std::string plural(int n, const char* one, const char* many) { return fmt::format("{} {}", n, n == 1 ? one : many); }

}  // namespace

std::string label_set_fingerprint_of(const StudyLabels& labels) {
  return labels.label_fingerprint.empty() ? label_set_fingerprint(labels.study) : labels.label_fingerprint;
}

namespace {
// The review marks of column `c` that still apply to the table's scenes and pairs.
void count_reviews(const CrossTable& table, size_t c, const StudyLabels& labels, Provenance* p) {
  const std::string& a = table.columns[c].first;
  const std::string& b = table.columns[c].second;
  std::vector<const ScenePairing*> scenes;
  for (const ScenePairing& s : table.pairings[c]) scenes.push_back(&s);
  std::sort(scenes.begin(), scenes.end(), [](const auto* x, const auto* y) { return x->stem < y->stem; });
  ReviewScenes r;
  for (const ScenePairing* s : scenes) r.stems.push_back(s->stem);
  r.gt = [&](int k, bool side_a) -> const std::vector<Box>& {
    return labels.gt_of(side_a ? a : b, scenes[k]->stem).boxes;
  };
  r.pairs = [&](int k) -> const RockPairs& { return scenes[k]->pairs; };
  r.take_class_of(labels.study);
  const ReviewRead read = load_review(labels.study.root, a, b, r);
  p->scenes_reviewed += read.state.reviewed_scenes;
  p->pairs_checked += read.state.checked_pairs();
}
}  // namespace

void add_column_provenance(const CrossTable& table, size_t c, const StudyLabels& labels, Provenance* p) {
  for (const ScenePairing& s : table.pairings[c]) {
    p->scenes_with_stale_hand_pairs +=
        std::any_of(s.pairs_problems.begin(), s.pairs_problems.end(), [](const PairsProblem& w) { return w.unusable; });
    if (!s.fixed) continue;
    ++p->scenes_with_hand_pairs;
    p->pairs_set_by_hand += static_cast<int>(s.pairs.size());
    p->rocks_excluded += static_cast<int>(s.excluded_a.size() + s.excluded_b.size());
    p->edited_scenes.push_back({table.columns[c].first, table.columns[c].second, s.stem});
  }
  count_reviews(table, c, labels, p);
}

Provenance labels_provenance(const StudyLabels& labels) {
  Provenance p;
  p.label_fingerprint = label_set_fingerprint_of(labels);
  p.class_name = provenance_class(labels);
  if (!p.class_name.empty()) p.class_maps = labels.study.classes.notes;
  p.segment = labels.study.config.task == Task::kSegment;
  return p;
}

Provenance table_provenance(const CrossTable& table, const StudyLabels& labels, const DomainPairFilter& only) {
  Provenance p = labels_provenance(labels);
  for (size_t c = 0; c < table.pairings.size() && c < table.columns.size(); ++c)
    if (includes_pair(only, table.columns[c].first, table.columns[c].second))
      add_column_provenance(table, c, labels, &p);
  return p;
}

Provenance session_provenance(const Session& session, const DomainPairFilter& only) {
  Provenance p;
  const auto& pairs = session.domain_pairs();
  for (size_t c = 0; c < pairs.size(); ++c) {
    if (!includes_pair(only, pairs[c].first, pairs[c].second)) continue;
    for (const SceneState& s : session.scenes_of(static_cast<int>(c))) {
      p.scenes_with_stale_hand_pairs += s.pairs_unusable;
      if (!s.edited) continue;
      ++p.scenes_with_hand_pairs;
      p.pairs_set_by_hand += static_cast<int>(s.current.pairs.size());
      p.rocks_excluded += static_cast<int>(s.current.excluded_a.size() + s.current.excluded_b.size());
      p.edited_scenes.push_back({pairs[c].first, pairs[c].second, s.stem});
    }
  }
  for (size_t c = 0; c < pairs.size(); ++c) {
    if (!includes_pair(only, pairs[c].first, pairs[c].second)) continue;
    const ReviewState& r = session.review_of(static_cast<int>(c));
    p.scenes_reviewed += r.reviewed_scenes;
    // Checks that are pairs now: one whose pair was edited away is kept in the file but does not apply.
    const auto& scenes = session.scenes_of(static_cast<int>(c));
    for (size_t k = 0; k < scenes.size() && k < r.checked.size(); ++k) {
      if (r.checked[k].empty()) continue;
      RockPairs now = scenes[k].current.pairs;  // sorted once: a dense scene has thousands of pairs and checks
      std::sort(now.begin(), now.end());
      for (const auto& pair : r.checked[k]) p.pairs_checked += std::binary_search(now.begin(), now.end(), pair);
    }
  }
  p.label_fingerprint = label_set_fingerprint_of(session.labels());
  p.class_name = provenance_class(session.labels());
  if (!p.class_name.empty()) p.class_maps = session.study().classes.notes;
  p.segment = session.study().config.task == Task::kSegment;
  return p;
}

std::string provenance_note(const Provenance& p) {
  std::string note =
      p.scenes_with_hand_pairs == 0
          ? fmt::format("Label files {}; no hand pairs (every pair from registration)", p.label_fingerprint)
          : fmt::format("Label files {}; hand pairs in {} ({} set by hand, {} excluded)", p.label_fingerprint,
                        plural(p.scenes_with_hand_pairs, "scene", "scenes"),
                        plural(p.pairs_set_by_hand, "pair", "pairs"), plural(p.rocks_excluded, "rock", "rocks"));
  if (p.scenes_reviewed > 0 || p.pairs_checked > 0)
    note += fmt::format("; {} reviewed, {} checked as correct", plural(p.scenes_reviewed, "scene", "scenes"),
                        plural(p.pairs_checked, "pair", "pairs"));
  if (p.scenes_with_stale_hand_pairs > 0)
    note += fmt::format("; stale hand pairs not used in {} (registration counts there)",
                        plural(p.scenes_with_stale_hand_pairs, "scene", "scenes"));
  note += ".";
  if (!p.class_name.empty()) note = fmt::format("Class {}. {}", p.class_name, note);
  return p.segment ? "Mask IoU (task segment). " + note : note;
}

std::string provenance_class(const StudyLabels& labels) {
  const int cls = labels.study.config.rock_class;
  const bool named = std::any_of(labels.study.classes.names.begin(), labels.study.classes.names.end(),
                                 [](const std::string& n) { return !n.empty(); });
  if (!named && cls != kAllClasses && cls <= 0) return {};
  return class_statement(labels);
}

nlohmann::ordered_json provenance_json(const Provenance& p) {
  nlohmann::ordered_json edited = nlohmann::ordered_json::array();
  for (const EditedScene& e : p.edited_scenes) edited.push_back({{"a", e.a}, {"b", e.b}, {"stem", e.stem}});
  nlohmann::ordered_json j = {{"label_fingerprint", p.label_fingerprint}};
  if (p.segment) j["task"] = "segment";
  if (!p.class_name.empty()) {
    j["class"] = p.class_name;
    j["class_maps"] = p.class_maps;
  }
  nlohmann::ordered_json rest = {{"scenes_with_hand_pairs", p.scenes_with_hand_pairs},
                                 {"pairs_set_by_hand", p.pairs_set_by_hand},
                                 {"rocks_excluded", p.rocks_excluded},
                                 {"scenes_reviewed", p.scenes_reviewed},
                                 {"pairs_checked", p.pairs_checked},
                                 {"scenes_with_stale_hand_pairs", p.scenes_with_stale_hand_pairs},
                                 {"edited_scenes", edited}};
  for (const auto& [key, value] : rest.items()) j[key] = value;
  return j;
}

std::vector<std::pair<std::string, std::string>> provenance_csv_fields(const Provenance& p) {
  std::vector<std::pair<std::string, std::string>> out;
  const nlohmann::ordered_json json = provenance_json(p);  // items() refers to it: not a temporary
  for (const auto& [key, value] : json.items()) {
    if (value.is_structured()) continue;  // lists (the edited scenes) stay in the JSON and --verbose
    out.emplace_back(key, value.is_string() ? value.get<std::string>() : value.dump());
  }
  return out;
}

bool provenance_edited(const Provenance& p) {
  return p.scenes_with_hand_pairs > 0 || p.rocks_excluded > 0 || p.scenes_with_stale_hand_pairs > 0;
}

Provenance scene_provenance(bool fixed, int pairs, int rocks_excluded, std::string label_fingerprint) {
  Provenance p;
  if (fixed) {
    p.scenes_with_hand_pairs = 1;
    p.pairs_set_by_hand = pairs;
  }
  p.rocks_excluded = rocks_excluded;
  p.label_fingerprint = std::move(label_fingerprint);
  return p;
}

}  // namespace ipd
