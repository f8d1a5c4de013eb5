// The parsed-study cache: one binary file holding every label file of a study as parsed, and the
// registration results the last open used, so reopening a 10,000-scene study reads one file instead of
// 120,000 label files and 30,000 registration entries.
//
// It lives in study_cache_dir() (STUDY/.ipd-cache/parsed-study.bin, or the user cache directory, named
// by a hash of the study's path, when the study is read-only), reached without following links
// (cache_file.h). It is never trusted blindly:
//  - the whole file carries a format version, the study root it belongs to, its payload size and an
//    HMAC-SHA-256 under this installation's key (cache_signer.h): a truncated, corrupt, copied, forged or
//    older file is ignored (and rebuilt), never read in part;
//  - a label file is reused only when its (size, mtime in ns, ctime in ns, inode) and whether it exists
//    are what they were when it was parsed; any other file is parsed again. Stamps suffice, without
//    re-reading the content, because the signature proves this installation recorded them right after
//    parsing that very file, and every change to a file's bytes or name moves its ctime, which no program
//    can set back (only the system clock can). A file rewritten within the file system's timestamp tick
//    of its parse, with the same size and inode, is the one change a stamp can miss. Each folder of label files is
//    opened once beneath the study (contained_file.h: OpenFolder) and its files' stamps taken with fstatat
//    relative to it, without following a link;
//  - the label set's fingerprint (label_fingerprint.h) is kept with the GT files it hashed and given back when every
//    GT file of the study is read back unchanged, under the same stamps' word, so a warm run reads no label file;
//    with it the hash's state after each domain, so a study that gained a variant (or changed one) hashes again
//    only the domains from it on in the fingerprint's path order;
//  - registrations are keyed by the same content hash as the entry files (registration_cache.h), so a
//    changed label file or option simply misses.
// Each label entry is stored with its size: reading the file indexes the entries (key and stamp), and load_labels'
// jobs decode the ones they take, on every core.
// Label files are stored as load_labels() returns them (classes renumbered, class and confidence filters
// applied): the class asked for, the class maps and the threshold are part of the header, and a run with other filters
// (`ipd table --conf`) parses again. The file is rewritten (atomically) only when something changed.
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <unordered_map>

#include "core/ipd/ipd.h"
#include "core/ipd/label_fingerprint.h"
#include "core/registration/registration_cache.h"

namespace ipd {

// The file's layout: magic "IPDSTUDY", format (u32), payload size (u64), then the HMAC-SHA-256 of the payload
// signed as kParsedStudySignature (which names the format too, so no other signed cache passes for one).
inline constexpr const char* kParsedStudySignature = "parsed study 4";
inline constexpr size_t kParsedStudyHeaderBytes = 8 + 4 + 8 + 32;

// What a label file looked like when it was parsed.
struct FileStamp {
  std::int64_t size = -1, mtime_ns = 0, ctime_ns = 0;
  std::uint64_t inode = 0;
  bool exists = false;
  bool operator==(const FileStamp& o) const {
    return size == o.size && mtime_ns == o.mtime_ns && ctime_ns == o.ctime_ns && inode == o.inode && exists == o.exists;
  }
};
// The stamp of `path` now (exists = false when there is nothing there or it can't be examined).
FileStamp stamp_of(const std::string& path);
class OpenFolder;
// The stamp of the entry `name` of an open folder (contained_file.h), examined without following it.
FileStamp stamp_at(const OpenFolder& folder, const std::string& name);
// The stamp of the open folder itself (exists = false when it is not open).
FileStamp stamp_of_folder(const OpenFolder& folder);

// The study's folder as one name whichever way it was given (`big`, ./big, /tmp/big): a cache belongs to the
// folder, not to how a command line spelled it.
std::string same_folder_name(const std::string& study_root);
// 16 hex digits naming that folder in the user cache directory, which every read-only study shares.
std::string study_folder_key(const std::string& study_root);

// STUDY/.ipd-cache/parsed-study.bin, or <user cache>/ipd-studio/parsed-study/<hash of the path>.bin.
std::string parsed_study_cache_path(const std::string& study_root);

struct StudyCacheStats {
  std::string state;  // "missing", "loaded", or why the file was ignored ("corrupt: checksum", ...)
  int files_reused = 0, files_parsed = 0;
  // Domains whose GT files load_labels read for the label set's fingerprint (0: the stored one was given back;
  // -1: not computed).
  int fingerprint_domains_read = -1;
  int registrations_stored = 0;  // in the file when it was read
  bool written = false;          // save() rewrote the file
};

class StudyCache {
 public:
  // Reads `path` (empty: no cache; every call below then just parses). An unusable file is ignored. The file
  // is read into memory through one descriptor (it is verified whole anyway), never mapped: anyone who can
  // write the study could shorten a mapped file, and the next access would crash the program (SIGBUS).
  // `hook` step: "opened" (after the file was opened, before it is read; tests shorten it there).
  explicit StudyCache(std::string path, const std::string& study_root,
                      const std::function<void(const char*)>& hook = {});
  ~StudyCache();
  StudyCache(const StudyCache&) = delete;
  StudyCache& operator=(const StudyCache&) = delete;

  // load_labels() that reuses every unchanged file's parse (same result, same errors).
  StudyLabels load_labels(const Study& study, const std::function<void(int done, int total)>& progress = {});
  // The registrations stored in the file, for RegistrationCache::preload.
  RegistrationEntries take_registrations();
  // Preloads `registration` with the file's registrations and, when this cache has a file to save, defers
  // its entry writes to save(): one signed file written once instead of one file per registration.
  void hand_registrations_to(RegistrationCache& registration);
  // Rewrites the file (atomically) when `labels` (from load_labels above) differ from what was read or
  // `registration` served entries the file did not hold; it keeps registration.entries_to_keep(). A cache that can't be
  // written only costs time: failures are ignored.
  void save(const StudyLabels& labels, const RegistrationCache& registration);

  const StudyCacheStats& stats() const { return stats_; }
  // The label set's fingerprint's state after each domain, as load_labels left it: they belong to the fingerprint
  // it gave (StudyLabels::label_fingerprint), and mean nothing when it gave none.
  const std::vector<FingerprintCheckpoint>& fingerprint_checkpoints() const;
  // Called with "checked" between the check that the file's name is not a link and the rename over it
  // (tests swap a link in there).
  void set_write_hook(std::function<void(const char*)> hook) { write_hook_ = std::move(hook); }

 private:
  struct Contents;
  std::string path_, root_;
  std::function<void(const char*)> write_hook_;
  std::unique_ptr<Contents> contents_;
  StudyCacheStats stats_;
};

}  // namespace ipd
