#include "core/registration/registration_cache.h"

#include <unistd.h>

#include <fmt/format.h>
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "core/util/cache_file.h"
#include "core/util/cache_signer.h"

namespace fs = std::filesystem;
using nlohmann::json;

namespace ipd {

namespace {

// Bump when the entry layout or any registration method changes its results: 4 after the consensus changes
// d3f1512, 5270185, 1e663dd and 4eeddd8 (entries of format 3 held their predecessors' answers); 5 for flat
// triples proposing similarities and the second look; 6 for translation votes in centred bins; 7 for the
// gate's floor, the guarded polish and the soft refinement of a confirmed best; 8 for cpd's confidence; 9 for
// cpd's rivals under the unmoved camera too; 10 for entries signed with the installation's key (cache_signer.h); 11
// for the identity given to identical layouts without a search; 12 for the ambiguity reason (no support, too
// few pairs, a degenerate or a beaten alignment: confidence 0 or a rival adopted) and the paper's search past an
// exact fit; 13 for the size-fair pairing rule (near misses within the noise floor pair too); 14 for the
// consensus judgement's prior on the camera (misalignment_cost); 15 for answers nothing was compared with (the
// time budget's or no plausible alignment's identity, EM's unjudged fit), which read confident or "a rival" before;
// 16 for samples and EM iterations apart and a fit kept with its measure.
constexpr int kFormat = 16;
// An entry of 20,000 pairs is under 1 MB; anything much larger was not written by store().
constexpr size_t kMaxEntryBytes = size_t{16} << 20;

struct Fnv {
  std::uint64_t h;
  void bytes(const void* p, size_t n) {
    const auto* c = static_cast<const unsigned char*>(p);
    for (size_t k = 0; k < n; ++k) h = (h ^ c[k]) * 0x100000001b3ull;
  }
  template <typename T>
  void value(const T& v) {
    bytes(&v, sizeof v);
  }
};

template <typename F>
void feed(F&& f, const std::vector<Box>& a, const std::vector<Box>& b, const RegistrationOptions& o) {
  f.value(kFormat);
  f.value(static_cast<int>(o.method));
  f.value(o.seed);
  // The same bytes as when one flat struct held these (0 and 1.0 for unset; one trial count for paper and
  // consensus), so entries written before the options were split by method stay valid.
  f.value(o.method == RegistrationMethod::kPaper ? o.paper.samples : o.consensus.max_hypotheses);
  f.value(o.time_budget_ms.value_or(0.0));
  f.value(o.aspect.value_or(1.0));
  f.value(o.paper.pair_gate);
  f.value(o.consensus.min_scale);
  f.value(o.consensus.max_scale);
  f.value(o.consensus.max_rotation_deg);
  f.value(o.consensus.max_anisotropy);
  f.value(o.consensus.inlier_gate.value_or(0.0));
  f.value(o.min_pair_iou);
  f.value(o.pair_noise_floor);
  f.value(o.pair_max_size_ratio);
  f.value(o.cpd.iterations);
  f.value(o.cpd.outlier_weight);
  f.value(o.work_budget.value_or(0.0));
  for (const auto* set : {&a, &b}) {
    f.value(set->size());
    for (const Box& x : *set) {
      f.value(x.cls);
      f.value(x.cx);
      f.value(x.cy);
      f.value(x.w);
      f.value(x.h);
    }
  }
}

std::string hex64(std::uint64_t v) { return fmt::format("{:016x}", v); }

}  // namespace

std::string study_cache_dir(const std::string& study_root) {
  std::error_code ec;
  const fs::path own = fs::path(study_root) / ".ipd-cache";
  const bool exists = fs::exists(own, ec);
  if (exists ? ::access(own.c_str(), W_OK) == 0 : ::access(study_root.c_str(), W_OK) == 0) return own.string();
  return usable_user_cache_root();  // "" (no cache) when it can't be used safely
}

std::string registration_cache_dir(const std::string& study_root) {
  const std::string dir = study_cache_dir(study_root);
  return dir.empty() ? "" : (fs::path(dir) / "registration").string();
}

void RegistrationCache::preload(RegistrationEntries entries) {
  std::lock_guard<std::mutex> l(memory_->mu);
  memory_->served_preloaded.clear();  // it points into the entries replaced here
  memory_->preloaded = std::move(entries);
}

RegistrationEntries RegistrationCache::served() const {
  std::lock_guard<std::mutex> l(memory_->mu);
  RegistrationEntries out = memory_->served;
  for (const auto* entry : memory_->served_preloaded) out.emplace(entry->first, entry->second);
  return out;
}

bool RegistrationCache::served_only_preloaded() const {
  std::lock_guard<std::mutex> l(memory_->mu);
  for (const auto& entry : memory_->served)
    if (!memory_->preloaded.count(entry.first)) return false;
  return true;
}

RegistrationEntries RegistrationCache::entries_to_keep() const {
  RegistrationEntries out = served();
  std::lock_guard<std::mutex> l(memory_->mu);
  size_t unused = 0;
  for (const auto& entry : memory_->preloaded) unused += !out.count(entry.first);
  if (unused > kKeptUnusedFactor * out.size()) return out;
  for (const auto& entry : memory_->preloaded) out.emplace(entry.first, entry.second);
  return out;
}

void RegistrationCache::remember(const std::string& key, const RegistrationReport& report) const {
  std::lock_guard<std::mutex> l(memory_->mu);
  memory_->served.emplace(key, report);
}

std::string registration_cache_key(const std::vector<Box>& a, const std::vector<Box>& b, const RegistrationOptions& o) {
  Fnv h1{0xcbf29ce484222325ull}, h2{0x84222325cbf29ce4ull};
  feed(h1, a, b, o);
  feed(h2, a, b, o);
  return hex64(h1.h) + hex64(h2.h);
}

std::string RegistrationCache::entry_path(const std::string& key) const {
  return (fs::path(dir_) / entry_name(key)).string();
}

std::string RegistrationCache::entry_name(const std::string& key) { return key.substr(0, 2) + "/" + key + ".json"; }

const CacheDir* RegistrationCache::directory(bool create) const {
  std::lock_guard<std::mutex> l(memory_->dir_mu);
  if (!memory_->dir && (create || !memory_->dir_looked_for)) memory_->dir = CacheDir::open(dir_, create);
  memory_->dir_looked_for = true;
  return memory_->dir.get();
}

std::optional<RegistrationReport> RegistrationCache::load(const std::string& key, int count_a, int count_b) const {
  if (const auto it = memory_->preloaded.find(key); it != memory_->preloaded.end()) {
    const RegistrationReport& r = it->second;
    std::vector<char> used_a(std::max(count_a, 0), 0), used_b(std::max(count_b, 0), 0);
    bool fits = true;
    for (const auto& [i, j] : r.pairs) {
      fits = fits && i >= 0 && i < count_a && j >= 0 && j < count_b && !used_a[i] && !used_b[j];
      if (!fits) break;
      used_a[i] = used_b[j] = 1;
    }
    if (fits) {
      std::lock_guard<std::mutex> l(memory_->mu);
      memory_->served_preloaded.insert(&*it);
      return r;
    }
  }
  if (dir_.empty()) return std::nullopt;
  const CacheDir* dir = directory(false);
  if (!dir) return std::nullopt;
  const std::optional<std::string> text = dir->read(entry_name(key), kMaxEntryBytes);
  if (!text) return std::nullopt;
  // An entry file that is there but not usable is replaced by store(): forged or foreign entries don't stay.
  const auto unusable = [&] {
    std::lock_guard<std::mutex> l(memory_->mu);
    memory_->unusable_on_disk.insert(key);
    return std::optional<RegistrationReport>();
  };
  try {
    // Layout: the payload on the first line, its signature (64 hex digits) on the second. An entry this
    // installation did not write (copied with a study, written by hand or by another build) doesn't verify.
    const size_t nl = text->find('\n');
    if (nl == std::string::npos || text->size() != nl + 1 + 64 + 1 ||
        text->compare(
            nl + 1, 64,
            CacheSigner::instance().mac_hex(kRegistrationEntrySignature, std::string_view(*text).substr(0, nl))) != 0)
      return unusable();
    const json j = json::parse(text->substr(0, nl));
    if (j.at("key").get<std::string>() != key || j.at("format").get<int>() != kFormat) return unusable();
    RegistrationReport r;
    RegistrationMethod m;
    if (!parse_method(j.at("method").get<std::string>(), &m)) return unusable();
    r.method = m;
    const auto aff = j.at("affine").get<std::vector<double>>();
    if (aff.size() != 6) return unusable();
    for (int k = 0; k < 6; ++k) {
      if (!std::isfinite(aff[k])) return unusable();
      r.affine(k / 3, k % 3) = aff[k];
    }
    std::vector<char> used_a(count_a, 0), used_b(count_b, 0);
    for (const auto& p : j.at("pairs")) {
      const int i = p.at(0).get<int>(), jb = p.at(1).get<int>();
      if (i < 0 || i >= count_a || jb < 0 || jb >= count_b || used_a[i] || used_b[jb]) return unusable();
      used_a[i] = used_b[jb] = 1;
      r.pairs.emplace_back(i, jb);
    }
    r.samples = j.at("samples").get<int>();
    r.em_iterations = j.at("em_iterations").get<int>();
    r.hypotheses = j.at("hypotheses").get<int>();
    r.inliers = j.at("inliers").get<int>();
    const int measure = j.at("fit_measure").get<int>();
    if (measure < 0 || measure > static_cast<int>(FitMeasure::kMixtureWidth)) return unusable();
    r.fit = {static_cast<FitMeasure>(measure), j.at("fit").get<double>()};
    const int stop = j.at("stop").get<int>();
    if (stop < 0 || stop > static_cast<int>(kLastStopReason)) return unusable();
    r.stop = static_cast<StopReason>(stop);
    r.note = j.at("note").get<std::string>();
    r.elapsed_ms = j.at("elapsed_ms").get<double>();
    r.confidence = j.at("confidence").get<double>();
    const int ambiguity = j.at("ambiguity").get<int>();
    if (ambiguity < 0 || ambiguity >= kAmbiguityCount) return std::nullopt;
    r.ambiguity = static_cast<Ambiguity>(ambiguity);
    r.ambiguous = r.ambiguity != Ambiguity::kNone;
    remember(key, r);
    return r;
  } catch (const std::exception&) {
    return unusable();  // unreadable or not what we wrote: recompute
  }
}

bool RegistrationCache::store(const std::string& key, const RegistrationReport& r) const {
  if (dir_.empty()) return false;
  remember(key, r);
  if (memory_->deferred) {
    std::lock_guard<std::mutex> l(memory_->mu);
    if (!memory_->unusable_on_disk.count(key)) return true;
  }
  json j;
  j["format"] = kFormat;
  j["key"] = key;
  j["method"] = to_string(r.method);
  std::vector<double> aff;
  for (int k = 0; k < 6; ++k) aff.push_back(r.affine(k / 3, k % 3));
  j["affine"] = aff;
  j["pairs"] = r.pairs;
  j["samples"] = r.samples;
  j["em_iterations"] = r.em_iterations;
  j["hypotheses"] = r.hypotheses;
  j["inliers"] = r.inliers;
  j["fit_measure"] = static_cast<int>(r.fit.measure);
  j["fit"] = std::isfinite(r.fit.value) ? r.fit.value : 0.0;
  j["stop"] = static_cast<int>(r.stop);
  j["note"] = r.note;
  j["elapsed_ms"] = r.elapsed_ms;
  j["confidence"] = std::isfinite(r.confidence) ? r.confidence : 0.0;
  j["ambiguity"] = static_cast<int>(r.ambiguity);
  const std::string payload = j.dump();
  // A cache that can't be written only costs time: failures just return false.
  const CacheDir* dir = directory(true);
  return dir &&
         dir->write(entry_name(key),
                    payload + "\n" + CacheSigner::instance().mac_hex(kRegistrationEntrySignature, payload) + "\n");
}

RegistrationReport register_rocks_cached(const RegistrationCache* cache, const std::vector<Box>& a,
                                         const std::vector<Box>& b, const RegistrationOptions& options, bool* hit) {
  if (hit) *hit = false;
  if (!cache || cache->dir().empty() || options.record_trace) return register_rocks(a, b, options);
  const std::string key = registration_cache_key(a, b, options);
  if (auto r = cache->load(key, static_cast<int>(a.size()), static_cast<int>(b.size()))) {
    if (hit) *hit = true;
    return *r;
  }
  RegistrationReport r = register_rocks(a, b, options);
  cache->store(key, r);
  return r;
}

}  // namespace ipd
