// An on-disk cache of registration results, so reopening a study (or re-running `ipd table`) does not
// register every scene again. An entry is keyed by a hash of both scenes' GT boxes (the label files'
// contents as parsed), the method and every option that can change the result; it lives in
// STUDY/.ipd-cache/registration/, or in the user cache directory when the study is read-only. Entries are
// written atomically without following links (cache_file.h) and signed with this installation's key
// (cache_signer.h): a missing, truncated, corrupt, copied or forged entry is recomputed, never used.
// Traces (RegistrationOptions::record_trace) are not cached: a replay registers the scene again.
#pragma once

#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <unordered_map>
#include <unordered_set>
#include <vector>

#include "core/geometry/geometry.h"
#include "core/registration/registration.h"
#include "core/util/cache_file.h"

namespace ipd {

// STUDY/.ipd-cache when the study root is writable, else $XDG_CACHE_HOME (or ~/.cache)/ipd-studio: where
// every cache of a study lives (registration entries, the parsed-study file of study_cache.h).
std::string study_cache_dir(const std::string& study_root);

// STUDY/.ipd-cache/registration when the study root is writable, else $XDG_CACHE_HOME (or ~/.cache)
// /ipd-studio/registration. Keys are content hashes, so studies may share the user directory.
std::string registration_cache_dir(const std::string& study_root);

// 32 hex digits: two 64-bit FNV-1a hashes (different seeds) of the boxes and the options.
std::string registration_cache_key(const std::vector<Box>& a, const std::vector<Box>& b,
                                   const RegistrationOptions& options);

// What an entry's signature says it is (cache_signer.h), so a signed file of another cache can't pass for one.
inline constexpr const char* kRegistrationEntrySignature = "registration entry";

using RegistrationEntries = std::unordered_map<std::string, RegistrationReport>;  // key -> report

class RegistrationCache {
 public:
  explicit RegistrationCache(std::string dir) : dir_(std::move(dir)) {}
  const std::string& dir() const { return dir_; }

  // Entries read in one go (the parsed-study file, study_cache.h): load() tries them before the entry
  // files, with the same checks. Every entry load() or store() hands out is remembered (served()), so the
  // caller can write the set this run used back in one file.
  void preload(RegistrationEntries entries);
  RegistrationEntries served() const;
  // True when this run used no entry beyond the preloaded ones (the one-file copy needs no rewrite).
  bool served_only_preloaded() const;
  // What the one file should keep: the entries served this run, plus preloaded ones this run did not use
  // (another method's, another domain selection's) while they are at most kKeptUnusedFactor times as many,
  // so switching between a few settings keeps each one's results without the file growing without end.
  static constexpr size_t kKeptUnusedFactor = 3;
  RegistrationEntries entries_to_keep() const;
  // Entries are only remembered, not written one file each: the caller writes them all at once (the
  // parsed-study file). Creating 30,000 entry files cost more than registering the scenes again.
  void defer_writes() { memory_->deferred = true; }

  // The cached report for `key`, or nullopt when absent or unusable (bad checksum, other key, pair
  // indices outside [0, count) or a rock paired twice).
  std::optional<RegistrationReport> load(const std::string& key, int count_a, int count_b) const;
  // Writes the entry atomically; false (and nothing written) when the directory can't be written.
  bool store(const std::string& key, const RegistrationReport& report) const;
  std::string entry_path(const std::string& key) const;
  static std::string entry_name(const std::string& key);  // "ab/<key>.json", relative to dir()

 private:
  struct Memory {
    RegistrationEntries preloaded;
    mutable std::mutex mu;
    RegistrationEntries served;  // guarded by mu: entries registered or read from their files this run
    // guarded by mu: preloaded entries served this run (not copied: a warm run serves 30,000)
    std::unordered_set<const RegistrationEntries::value_type*> served_preloaded;
    std::mutex dir_mu;
    std::shared_ptr<const CacheDir> dir;  // guarded by dir_mu; opened on first use
    bool dir_looked_for = false;
    bool deferred = false;
    std::unordered_set<std::string> unusable_on_disk;  // guarded by mu: rewritten by store() even when deferred
  };
  // The opened cache directory (created when `create`); nullptr when missing or refused.
  const CacheDir* directory(bool create) const;
  void remember(const std::string& key, const RegistrationReport& report) const;
  std::string dir_;
  std::shared_ptr<Memory> memory_ = std::make_shared<Memory>();
};

// register_rocks through the cache (nullptr: no cache). `hit` tells whether the result came from disk.
RegistrationReport register_rocks_cached(const RegistrationCache* cache, const std::vector<Box>& a,
                                         const std::vector<Box>& b, const RegistrationOptions& options,
                                         bool* hit = nullptr);

}  // namespace ipd
