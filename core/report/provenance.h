// What a reader of a number needs to tell an automatic result from an edited one: how many scenes have hand
// pairs, how many pairs were set by hand and rocks left out, and a short fingerprint of the label set the
// numbers were computed from (two tables with the same fingerprint came from the same GT label files).
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

#include "core/ipd/ipd.h"
#include "core/ipd/label_fingerprint.h"
#include "core/session/session.h"

namespace ipd {

struct EditedScene {
  std::string a, b, stem;  // the domain pair and the scene whose pairs file counted
};

struct Provenance {
  // Counted over the table's domain pairs: a scene with hand pairs in two domain pairs counts twice, as it
  // was edited twice.
  int scenes_with_hand_pairs = 0;
  int pairs_set_by_hand = 0;  // pairs in those scenes' pairs files
  int rocks_excluded = 0;     // rocks left out of the IPD on purpose, both sides
  // From the review files (core/session/review_state.h), over the same domain pairs: scenes marked
  // reviewed, and pairs checked as correct that are still pairs of their scenes.
  int scenes_reviewed = 0;
  int pairs_checked = 0;
  // Scenes whose pairs file no longer matches their label files (a stored rock moved or deleted): their hand
  // pairs are not used and registration counts there (`ipd table --skip-bad-lines`; the studio until the
  // file is reset). A reader must know that an edit was dropped, not only that none counted.
  int scenes_with_stale_hand_pairs = 0;
  std::string label_fingerprint;
  // The class the numbers are about ("rock (class 0)", "all, class-blind (--class all)") and how label
  // sets' class numbers were mapped by name; empty for a study whose one class has no name (nothing to tell).
  std::string class_name;
  std::vector<std::string> class_maps;
  // Performance values are mask IoUs (task segment); said first in every note and as "task" in the JSON, since a
  // mask-IoU IPD and a box-IoU IPD of the same study differ. Box IoU (the paper's) goes unsaid.
  bool segment = false;
  std::vector<EditedScene> edited_scenes;  // in column and scene order
};

// label_set_fingerprint (core/ipd/label_fingerprint.h) of the labels' study: the one the parsed-study cache
// vouched for when it read every GT file unchanged (StudyLabels::label_fingerprint), else computed from the files.
std::string label_set_fingerprint_of(const StudyLabels& labels);

// The hand-pair counts of `table`, the review marks of its domain pairs (those of `only`, when given) and the
// fingerprint of the labels. Throws StudyError naming a review file that can't be read.
Provenance table_provenance(const CrossTable& table, const StudyLabels& labels, const DomainPairFilter& only = {});
// table_provenance's two parts: what comes from the labels alone (the fingerprint, the class and its maps, the
// task), and the hand pairs and review marks of the table's column `c`, added to `p`.
Provenance labels_provenance(const StudyLabels& labels);
void add_column_provenance(const CrossTable& table, size_t c, const StudyLabels& labels, Provenance* p);
// The same for ipd-studio's session over every domain pair (or those of `only`): its edited scenes (edits not
// yet saved included), as `ipd table` would count them once they are saved.
Provenance session_provenance(const Session& session, const DomainPairFilter& only = {});

// Every output renders provenance through the two functions below, so a field added to Provenance shows
// in all of them (tables, compare, breakdown, the rock export, every figure kind and its metadata).

// The text footnote, "Class rock (class 0). " first when class_name is set: "Label files 1a2b3c4d5e6f; hand pairs in 2
// scenes (5 pairs set by hand, 1 rock excluded)." or "Label files 1a2b3c4d5e6f; no hand pairs (every pair from
// registration).", with "; 12 scenes reviewed, 3 pairs checked as correct" before the full stop when anything was
// reviewed or checked, and
// "; stale hand pairs not used in 1 scene (registration counts there)" when a pairs file was set aside.
std::string provenance_note(const Provenance& p);

// The machine-readable form, keys in a fixed order: label_fingerprint, class and class_maps (when class_name is
// set), scenes_with_hand_pairs,
// pairs_set_by_hand, rocks_excluded, scenes_reviewed, pairs_checked, scenes_with_stale_hand_pairs,
// edited_scenes (an array of {a, b, stem}).
nlohmann::ordered_json provenance_json(const Provenance& p);

// The scalar members of provenance_json as CSV columns (name, value), in the same order: repeated on every
// row, so any CSV reader keeps them without options (comment rows need pandas' comment='#' and break R's
// read.csv on a '#' inside a name).
std::vector<std::pair<std::string, std::string>> provenance_csv_fields(const Provenance& p);

// The class statement provenance carries for `labels` (Provenance::class_name): empty when the study names no
// class, reads one unnamed class and is not class-blind.
std::string provenance_class(const StudyLabels& labels);

// Whether any number may differ from the automatic result (a pair set by hand or a rock left out), or hand
// pairs were set aside as stale. Figures print the note in the figure only then (the fingerprint always goes
// into their metadata).
bool provenance_edited(const Provenance& p);

// The provenance of one scene's pairs (the scene figures): one scene with hand pairs when `fixed`.
Provenance scene_provenance(bool fixed, int pairs, int rocks_excluded, std::string label_fingerprint);

}  // namespace ipd
