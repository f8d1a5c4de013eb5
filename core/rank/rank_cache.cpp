#include "core/rank/rank_cache.h"

#include <fmt/format.h>

#include <algorithm>
#include <filesystem>

#include "core/ipd/study_cache.h"
#include "core/ipd/study_cache_codec.h"
#include "core/ipd/study_pipeline.h"
#include "core/registration/registration_cache.h"
#include "core/util/cache_file.h"
#include "core/util/cache_signer.h"
#include "core/util/contained_file.h"
#include "core/util/parallel.h"
#include "core/util/sha256.h"

namespace fs = std::filesystem;

namespace ipd {

namespace {

// What each file's signature says it is (cache_signer.h); the format is in the name, so an older file never
// verifies as this one.
constexpr const char* kIndexKind = "rank index 1";
constexpr const char* kScenesKind = "rank cell scenes 1";
constexpr size_t kMaxIndexBytes = size_t{256} << 20;
constexpr size_t kMaxScenesBytes = size_t{1} << 30;

using cache_codec::Reader;
using cache_codec::Writer;

void add_stamp(Sha256& h, const FileStamp& s) {
  Writer w;
  cache_codec::write_stamp(w, s);
  h.add(w.out);
}

void add_text(Sha256& h, const std::string& s) {
  h.add(s);
  h.add(std::string_view("\0", 1));
}

// Digest of one folder of label files: its own stamp, its classes.txt's, and each scene's file by stem.
std::string stamp_label_folder(const Study& study, const std::string& relative, const std::vector<std::string>& stems) {
  const OpenFolder folder(study.root, relative);
  Sha256 h;
  add_text(h, relative);
  add_stamp(h, stamp_of_folder(folder));
  add_stamp(h, stamp_at(folder, "classes.txt"));
  for (const std::string& stem : stems) {
    add_text(h, stem);
    add_stamp(h, stamp_at(folder, stem + ".txt"));
  }
  return h.hex();
}

// Every entry of a folder that may not be there, each stamped: a pairs folder.
void add_folder_entries(Sha256& h, const Study& study, const std::string& relative) {
  add_text(h, relative);
  const OpenFolder folder(study.root, relative);
  add_stamp(h, stamp_of_folder(folder));
  if (folder.fd() < 0) return;
  for (const FolderEntry& e : entries_beneath(study.root, relative)) {
    add_text(h, e.name);
    add_stamp(h, stamp_at(folder, e.name));
  }
}

void write_cell(Writer& w, const TableCell& c) {
  for (const std::string* s : {&c.model, &c.trained_on, &c.a, &c.b, &c.no_value_reason}) w.str(*s);
  for (const double v : {c.ipd, c.ci_low, c.ci_high, c.se, c.sum_abs_diff}) w.pod(v);
  for (const long v : {c.pairs, c.unpaired_a, c.unpaired_b}) w.pod<std::int64_t>(v);
  w.pod<std::int32_t>(c.scenes);
  w.pod<std::uint8_t>(c.involves_training_domain);
  w.pod<std::uint8_t>(c.missing_predictions);
}

TableCell read_cell(Reader& r) {
  TableCell c;
  for (std::string* s : {&c.model, &c.trained_on, &c.a, &c.b, &c.no_value_reason}) *s = r.str();
  for (double* v : {&c.ipd, &c.ci_low, &c.ci_high, &c.se, &c.sum_abs_diff}) *v = r.pod<double>();
  for (long* v : {&c.pairs, &c.unpaired_a, &c.unpaired_b}) *v = static_cast<long>(r.pod<std::int64_t>());
  c.scenes = r.pod<std::int32_t>();
  c.involves_training_domain = r.pod<std::uint8_t>() != 0;
  c.missing_predictions = r.pod<std::uint8_t>() != 0;
  return c;
}

void write_strings(Writer& w, const std::vector<std::string>& v) {
  w.pod<std::uint64_t>(v.size());
  for (const std::string& s : v) w.str(s);
}

std::vector<std::string> read_strings(Reader& r) {
  const auto n = r.pod<std::uint64_t>();
  std::vector<std::string> v;
  for (std::uint64_t k = 0; k < n; ++k) v.push_back(r.str());
  return v;
}

void write_comparison(Writer& w, const KeptComparison& k) {
  w.str(k.best);
  w.str(k.best_inputs);
  w.pod<std::int32_t>(k.permutations);
  const RendererComparison& c = k.comparison;
  for (const std::string* s : {&c.model, &c.ref, &c.a, &c.b}) w.str(*s);
  w.pod(c.result);
  write_strings(w, c.scenes);
}

KeptComparison read_comparison(Reader& r) {
  KeptComparison k;
  k.best = r.str();
  k.best_inputs = r.str();
  k.permutations = r.pod<std::int32_t>();
  RendererComparison& c = k.comparison;
  for (std::string* s : {&c.model, &c.ref, &c.a, &c.b}) *s = r.str();
  c.result = r.pod<Comparison>();
  c.scenes = read_strings(r);
  return k;
}

void write_provenance(Writer& w, const PairProvenance& p) {
  for (const int v : {p.scenes_with_hand_pairs, p.pairs_set_by_hand, p.rocks_excluded, p.scenes_reviewed,
                      p.pairs_checked, p.scenes_with_stale_hand_pairs})
    w.pod<std::int32_t>(v);
  write_strings(w, p.edited_stems);
}

PairProvenance read_provenance(Reader& r) {
  PairProvenance p;
  for (int* v : {&p.scenes_with_hand_pairs, &p.pairs_set_by_hand, &p.rocks_excluded, &p.scenes_reviewed,
                 &p.pairs_checked, &p.scenes_with_stale_hand_pairs})
    *v = r.pod<std::int32_t>();
  p.edited_stems = read_strings(r);
  return p;
}

void write_stamps(Writer& w, const DomainStamps& f) {
  w.str(f.stamps);
  w.str(f.gt_stamps);
}

DomainStamps read_stamps(Reader& r) {
  DomainStamps f;
  f.stamps = r.str();
  f.gt_stamps = r.str();
  return f;
}

void write_scene(Writer& w, const SceneIpd& s) {
  w.str(s.stem);
  w.vec(s.perf_a);
  w.vec(s.perf_b);
  std::vector<std::int32_t> counted;
  counted.reserve(2 * s.counted.size());
  for (const auto& [i, j] : s.counted) counted.push_back(i), counted.push_back(j);
  w.vec(counted);
  w.pod(s.sum_abs_diff);
  for (const int v : {s.pairs, s.unpaired_a, s.unpaired_b}) w.pod<std::int32_t>(v);
}

SceneIpd read_scene(Reader& r) {
  SceneIpd s;
  s.stem = r.str();
  s.perf_a = r.vec<double>();
  s.perf_b = r.vec<double>();
  const std::vector<std::int32_t> counted = r.vec<std::int32_t>();
  if (counted.size() % 2 != 0 || s.perf_a.size() != s.perf_b.size() || s.perf_a.size() * 2 != counted.size())
    throw std::runtime_error("scene sizes");
  for (size_t k = 0; k < counted.size(); k += 2) s.counted.emplace_back(counted[k], counted[k + 1]);
  s.sum_abs_diff = r.pod<double>();
  for (int* v : {&s.pairs, &s.unpaired_a, &s.unpaired_b}) *v = r.pod<std::int32_t>();
  return s;
}

// The signed file: its signature, then the bytes it signs.
std::string signed_file(const char* kind, const std::string& payload) {
  return CacheSigner::instance().mac(kind, payload) + payload;
}

std::optional<std::string_view> verified_payload(const char* kind, const std::string& file) {
  if (file.size() < CacheSigner::kMacBytes) return std::nullopt;
  const std::string_view payload = std::string_view(file).substr(CacheSigner::kMacBytes);
  if (!CacheSigner::instance().verify(kind, payload, std::string_view(file).substr(0, CacheSigner::kMacBytes)))
    return std::nullopt;
  return payload;
}

// A cell's scenes file, named by its model and domains: the next ranking with them replaces it.
std::string scenes_name(const TableCell& c) {
  Sha256 h;
  for (const std::string* s : {&c.model, &c.a, &c.b}) add_text(h, *s);
  return h.hex().substr(0, 32) + ".bin";
}

}  // namespace

DomainStampsMap stamp_domains(const Study& study, int threads) {
  struct Job {
    const Domain* domain;
    std::string relative, digest;
  };
  std::vector<Job> jobs;
  for (const Domain& d : study.domains) {
    jobs.push_back({&d, d.name + "/labels", {}});
    for (const std::string& m : d.models) jobs.push_back({&d, d.name + "/predictions/" + m, {}});
  }
  parallel_for(jobs.size(), threads,
               [&](size_t k) { jobs[k].digest = stamp_label_folder(study, jobs[k].relative, jobs[k].domain->stems); });
  DomainStampsMap out;
  for (size_t k = 0; k < jobs.size();) {
    const Domain* d = jobs[k].domain;
    DomainStamps& f = out[d->name];
    f.gt_stamps = jobs[k].digest;  // labels/ comes first
    Sha256 all;
    for (; k < jobs.size() && jobs[k].domain == d; ++k) add_text(all, jobs[k].digest);
    f.stamps = all.hex();
  }
  return out;
}

std::string pair_file_stamps(const Study& study, const std::string& a, const std::string& b) {
  Sha256 h;
  for (const auto& [x, y] : {std::make_pair(a, b), std::make_pair(b, a)})
    add_folder_entries(h, study, "pairs/" + x + "__" + y);
  const OpenFolder review(study.root, "review");
  add_stamp(h, stamp_of_folder(review));
  for (const auto& [x, y] : {std::make_pair(a, b), std::make_pair(b, a)}) {
    const std::string name = x + "__" + y + ".json";
    add_text(h, name);
    add_stamp(h, stamp_at(review, name));
  }
  return h.hex();
}

std::string rank_cache_settings(const Study& study, const std::string& model, const std::string& ref,
                                const RegistrationOptions& registration, const BootstrapOptions& bootstrap) {
  std::string trained_on;
  for (const ModelInfo& m : study.models)
    if (m.name == model) trained_on = m.trained_on;
  // Numbers as their exact bits (hex floats): 0.1 and 0.1000000001 are other settings.
  return fmt::format(
      "model {}\ntrained on {}\nref {}\nclass {}\nclass numbering {}\nconf {:a}\ntask {}\nregistration {}\n"
      "bootstrap {} {:a} {}\n",
      model, trained_on, ref, study.config.rock_class, study.classes.map_key(), study.config.conf_threshold,
      static_cast<int>(study.config.task), registration_cache_key({}, {}, with_study_aspect(study, registration)),
      bootstrap.resamples, bootstrap.level, bootstrap.seed);
}

std::string rank_cell_inputs(const std::string& settings, const DomainStamps& a_stamps, const DomainStamps& b_stamps,
                             const std::string& a, const std::string& b, const std::string& pair_files) {
  Sha256 h;
  for (const std::string* s : {&settings, &a_stamps.stamps, &b_stamps.stamps, &a, &b, &pair_files}) add_text(h, *s);
  return h.hex();
}

RankCache::RankCache(const std::string& study_root, std::string settings) : settings_(std::move(settings)) {
  if (study_root.empty()) return;
  dir_ = study_cache_dir(study_root);
  if (dir_.empty()) return;
  folder_ = same_folder_name(study_root);
  // Inside the study, its own folder; in the user cache directory, which read-only studies share, one a study.
  prefix_ = fs::path(dir_).filename() == ".ipd-cache" ? "rank/" : "rank/" + study_folder_key(study_root) + "/";
  const auto dir = CacheDir::open(dir_, false);
  if (!dir) return;
  const std::optional<std::string> file = dir->read(prefix_ + "index.bin", kMaxIndexBytes);
  if (!file) return;
  const auto payload = verified_payload(kIndexKind, *file);
  if (!payload) return;
  try {
    Reader r(*payload);
    if (r.view() != folder_ || r.view() != settings_) return;
    RankRecord rec;
    rec.fingerprint = r.str();
    for (auto n = r.pod<std::uint64_t>(); n > 0; --n) {
      FingerprintCheckpoint p;
      p.domain = r.str();
      p.files = r.pod<std::uint64_t>();
      p.state = r.str();
      rec.checkpoints.push_back(std::move(p));
    }
    for (auto n = r.pod<std::uint64_t>(); n > 0; --n) {
      std::string name = r.str();
      rec.domains[name] = read_stamps(r);
    }
    for (auto n = r.pod<std::uint64_t>(); n > 0; --n) {
      KeptCell c;
      c.candidate = r.str();
      c.inputs = r.str();
      c.cell = read_cell(r);
      c.no_predictions_at_threshold = r.pod<std::uint8_t>() != 0;
      c.provenance = read_provenance(r);
      if (r.pod<std::uint8_t>() != 0) c.vs_best = read_comparison(r);
      rec.cells.push_back(std::move(c));
    }
    if (!r.at_end()) return;
    record_ = std::move(rec);
  } catch (const std::exception&) {
    // Truncated or out of range: as if there were no file.
  }
}

const KeptCell* RankCache::cell(const std::string& candidate, const std::string& inputs) const {
  for (const KeptCell& c : record_.cells)
    if (c.candidate == candidate) return c.inputs == inputs ? &c : nullptr;
  return nullptr;
}

std::optional<std::vector<SceneIpd>> RankCache::scenes(const KeptCell& cell) const {
  if (dir_.empty()) return std::nullopt;
  const auto dir = CacheDir::open(dir_, false);
  if (!dir) return std::nullopt;
  const std::optional<std::string> file = dir->read(prefix_ + scenes_name(cell.cell), kMaxScenesBytes);
  if (!file) return std::nullopt;
  const auto payload = verified_payload(kScenesKind, *file);
  if (!payload) return std::nullopt;
  try {
    Reader r(*payload);
    if (r.view() != folder_ || r.view() != settings_ || r.view() != cell.inputs) return std::nullopt;
    std::vector<SceneIpd> out;
    for (auto n = r.pod<std::uint64_t>(); n > 0; --n) out.push_back(read_scene(r));
    if (!r.at_end() || static_cast<int>(out.size()) != cell.cell.scenes) return std::nullopt;
    return out;
  } catch (const std::exception&) {
    return std::nullopt;
  }
}

void RankCache::save(const RankRecord& record) const {
  if (dir_.empty()) return;
  const auto dir = CacheDir::open(dir_, true);
  if (!dir) return;
  for (const KeptCell& c : record.cells) {
    if (c.cell.per_scene.empty()) continue;
    Writer w;
    for (const std::string* s : {&folder_, &settings_, &c.inputs}) w.str(*s);
    w.pod<std::uint64_t>(c.cell.per_scene.size());
    for (const SceneIpd& s : c.cell.per_scene) write_scene(w, s);
    // Written before the index that vouches for it: a run stopped in between finds an index without the new cell.
    if (!dir->write(prefix_ + scenes_name(c.cell), signed_file(kScenesKind, w.out))) return;
  }
  Writer w;
  w.str(folder_);
  w.str(settings_);
  w.str(record.fingerprint);
  w.pod<std::uint64_t>(record.checkpoints.size());
  for (const FingerprintCheckpoint& p : record.checkpoints) {
    w.str(p.domain);
    w.pod<std::uint64_t>(p.files);
    w.str(p.state);
  }
  w.pod<std::uint64_t>(record.domains.size());
  for (const auto& [name, stamps] : record.domains) {
    w.str(name);
    write_stamps(w, stamps);
  }
  w.pod<std::uint64_t>(record.cells.size());
  for (const KeptCell& c : record.cells) {
    w.str(c.candidate);
    w.str(c.inputs);
    write_cell(w, c.cell);
    w.pod<std::uint8_t>(c.no_predictions_at_threshold);
    write_provenance(w, c.provenance);
    w.pod<std::uint8_t>(c.vs_best.has_value());
    if (c.vs_best) write_comparison(w, *c.vs_best);
  }
  dir->write(prefix_ + "index.bin", signed_file(kIndexKind, w.out));
}

}  // namespace ipd
