// What a ranking computed, kept to be used again: each (model, reference, candidate) cell and each candidate's
// comparison with the best, with a digest of the stamps of every file they came from. `ipd rank` run again after
// new variants were rendered into the study then reads and computes the new (or changed) candidates only: an
// optimiser calling it after each batch of renders pays for the batch, not for the whole study.
//
// It lives beside the parsed-study cache (study_cache_dir: STUDY/.ipd-cache/rank/, or the user cache named by a
// hash of the study's folder), reached without following links (cache_file.h), and trusts what it holds as that
// cache does: every file is signed under this installation's key (cache_signer.h) and names its format, the
// study's folder and the settings, so a corrupt, copied, forged or older file is ignored, never read in part; a
// label file is taken as unchanged when its (size, mtime, ctime, inode) are (study_cache.h says why that is enough).
//
// A cell is used again only when all it depends on is as it was:
//  - the settings (rank_cache_settings): model and its training domain, reference, class asked for and how label
//    sets' classes are numbered, confidence threshold, task, registration options and the bootstrap;
//  - both domains' files (DomainStamps): every GT and prediction file's stamp, each folder's (a file added or
//    removed) and the domain's scenes;
//  - the pair's hand pairs and review files (pair_file_stamps), and which way round the table holds the pair.
// Only a run that said nothing but numbers is kept (no warning, no label error, no note). A run on kept cells reads
// the reference, the candidates it computes and every domain whose files changed, and says what a whole run would:
//  - what is said of the whole study (the class chosen, outlines read as boxes, shifted class numbers, label errors)
//    comes of the domains read, the others having said nothing when they were read as they are now; the class
//    chosen is the reference's, which is always read;
//  - what is said of a pair comes of its two domains: a kept pair said nothing, so its domains share every scene,
//    each with its prediction file (a scene without a counterpart, or without a prediction file that another
//    domain has, is a warning), and a new domain can't make it say anything;
//  - what pairing says of the whole study (hand files no pair reads, square pictures) is looked for on every run,
//    and a study with any of it is read whole (app/cli/rank_reuse.cpp).
//
// The index (every cell's numbers, comparisons and the domains' stamps) is one small file; each cell's scenes (what a
// new comparison with it needs) are a file of their own, read only when a comparison must be computed again.
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "core/ipd/ipd.h"
#include "core/ipd/label_fingerprint.h"
#include "core/stats/study_statistics.h"

namespace ipd {

// What a ranking must know of a domain it does not read again: whether its files are as they were.
struct DomainStamps {
  std::string stamps;     // digest of the stamps of its folders, GT and prediction files, and its scenes
  std::string gt_stamps;  // the same over its labels/ folder alone (the label set's fingerprint resumes past it)
};
using DomainStampsMap = std::map<std::string, DomainStamps>;

// Every domain's stamps now, its folders examined on `threads` cores (0: every core) without following links.
// Throws IoError for a link or a folder that can't be read.
DomainStampsMap stamp_domains(const Study& study, int threads);
// Digest of the stamps of the hand pairs (pairs/A__B/, pairs/B__A/) and review files (review/A__B.json,
// review/B__A.json) of the pair. Throws IoError for a link there.
std::string pair_file_stamps(const Study& study, const std::string& a, const std::string& b);

// Everything but the files that a ranking cell's numbers depend on, as one string. `registration`: the options
// each scene is registered with (the study's aspect added here); `bootstrap`: the intervals' and comparisons'.
std::string rank_cache_settings(const Study& study, const std::string& model, const std::string& ref,
                                const RegistrationOptions& registration, const BootstrapOptions& bootstrap);
// The digest a cell is kept under: the settings, both domains' stamps, the pair as the table holds it (a, b) and
// its hand pairs and review files.
std::string rank_cell_inputs(const std::string& settings, const DomainStamps& a_stamps, const DomainStamps& b_stamps,
                             const std::string& a, const std::string& b, const std::string& pair_files);

// The provenance of one (reference, candidate) pair (provenance.h counts these over a table's pairs).
struct PairProvenance {
  int scenes_with_hand_pairs = 0, pairs_set_by_hand = 0, rocks_excluded = 0;
  int scenes_reviewed = 0, pairs_checked = 0, scenes_with_stale_hand_pairs = 0;
  std::vector<std::string> edited_stems;  // scenes whose pairs file counted, in the table's scene order
};

// A candidate's comparison with the best, and what it was computed from.
struct KeptComparison {
  std::string best, best_inputs;
  int permutations = 0;
  RendererComparison comparison;
};

struct KeptCell {
  std::string candidate, inputs;
  TableCell cell;  // as the table had it, intervals included; per_scene only when it is to be written
  bool no_predictions_at_threshold = false;
  PairProvenance provenance;
  std::optional<KeptComparison> vs_best;
};

// What one ranking leaves for the next.
struct RankRecord {
  std::string fingerprint;  // the label set's (label_fingerprint.h), with its state after each domain
  std::vector<FingerprintCheckpoint> checkpoints;
  DomainStampsMap domains;  // every domain of the study
  std::vector<KeptCell> cells;
};

class RankCache {
 public:
  // Reads the index of `study_root`'s cache for `settings` (empty root: no cache; nothing is read or written).
  // An unusable index (missing, corrupt, another study, other settings, another format) reads as empty.
  RankCache(const std::string& study_root, std::string settings);

  bool enabled() const { return !dir_.empty(); }
  const std::string& settings() const { return settings_; }
  const RankRecord& record() const { return record_; }
  // The kept cell of `candidate` when it was kept under `inputs`; null otherwise.
  const KeptCell* cell(const std::string& candidate, const std::string& inputs) const;
  // The scenes of that cell (its per_scene), from its own file; nullopt when the file is missing or unusable.
  std::optional<std::vector<SceneIpd>> scenes(const KeptCell& cell) const;
  // Replaces the index with `record`; each cell given with scenes (per_scene) gets its scenes file written. A
  // cache that can't be written only costs time: failures are ignored.
  void save(const RankRecord& record) const;

 private:
  std::string dir_, prefix_, settings_, folder_;
  RankRecord record_;
};

}  // namespace ipd
