#include "core/ipd/study_cache.h"

#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include <fmt/format.h>
#include <algorithm>
#include <array>
#include <atomic>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <map>
#include <memory>
#include <mutex>
#include <new>
#include <string_view>
#include <type_traits>
#include <vector>

#include "core/ipd/label_fingerprint.h"
#include "core/ipd/study_cache_codec.h"
#include "core/util/cache_file.h"
#include "core/util/cache_signer.h"
#include "core/util/contained_file.h"

namespace fs = std::filesystem;

namespace ipd {

namespace {

constexpr char kMagic[8] = {'I', 'P', 'D', 'S', 'T', 'U', 'D', 'Y'};
// Bump when the layout, label parsing or a registration method's results change: 3 for the signature; 4: a
// report keeps why its registration is ambiguous (Ambiguity), not only whether; 5: answers nothing was compared
// with are flagged as such (Ambiguity::kUnchecked, kNoPlausible); 7: outlines, with their areas and centroids
// (an outline's clipping into non-crossing contours is not redone on a warm load); 8: the label set's fingerprint;
// 9: a report's samples and EM iterations apart, its fit with its measure; 10: the fingerprint's running state
// after each domain; 11: each label entry's size before it, so a warm run indexes the file and decodes entries
// on every core as they are taken.
constexpr std::uint32_t kFormat = 11;
constexpr size_t kHeaderBytes = kParsedStudyHeaderBytes;
static_assert(kHeaderBytes == sizeof kMagic + 4 + 8 + CacheSigner::kMacBytes);

// A word-at-a-time hash, naming a read-only study's file in the user cache directory by its path.
std::uint64_t path_hash(const char* p, size_t n) {
  std::uint64_t h = 0x9ae16a3b2f90404full ^ n;
  size_t k = 0;
  for (; k + 8 <= n; k += 8) {
    std::uint64_t w;
    std::memcpy(&w, p + k, 8);
    h = (h ^ w) * 0x9e3779b97f4a7c15ull;
    h ^= h >> 29;
  }
  std::uint64_t tail = 0;
  if (n > k) std::memcpy(&tail, p + k, n - k);  // p may be null when n == 0
  h = (h ^ tail) * 0x9e3779b97f4a7c15ull;
  return h ^ (h >> 32);
}

std::string entry_key(const std::string& domain, const std::string& model, const std::string& stem) {
  return domain + '\n' + model + '\n' + stem;
}

// The stamp of a file whose folder could not be opened: parsed every time, never equal to a file's stamp.
const FileStamp kNeverReused{-3, 0, 0, 0, true};

std::int64_t ns_of(const struct timespec& t) { return std::int64_t{t.tv_sec} * 1000000000 + t.tv_nsec; }

}  // namespace

namespace {

FileStamp stamp_from(const struct stat& st) {
  FileStamp s;
  s.exists = true;
  s.size = st.st_size;
  s.mtime_ns = ns_of(st.st_mtim);
  s.ctime_ns = ns_of(st.st_ctim);
  s.inode = st.st_ino;
  return s;
}

}  // namespace

FileStamp stamp_at(const OpenFolder& folder, const std::string& name) {
  struct stat st {};
  return folder.stat_entry(name, &st) ? stamp_from(st) : FileStamp{};
}

FileStamp stamp_of(const std::string& path) {
  struct stat st {};
  return ::stat(path.c_str(), &st) == 0 ? stamp_from(st) : FileStamp{};
}

FileStamp stamp_of_folder(const OpenFolder& folder) {
  struct stat st {};
  return folder.fd() >= 0 && ::fstat(folder.fd(), &st) == 0 ? stamp_from(st) : FileStamp{};
}

std::string same_folder_name(const std::string& study_root) {
  std::error_code ec;
  const fs::path abs = fs::weakly_canonical(fs::absolute(study_root, ec), ec);
  return ec || abs.empty() ? study_root : abs.string();
}

std::string study_folder_key(const std::string& study_root) {
  const std::string name = same_folder_name(study_root);
  return fmt::format("{:016x}", path_hash(name.data(), name.size()));
}

std::string parsed_study_cache_path(const std::string& study_root) {
  const fs::path dir = study_cache_dir(study_root);
  if (dir.empty()) return "";  // no cache that can be used safely
  if (dir.filename() == ".ipd-cache") return (dir / "parsed-study.bin").string();
  // The user directory is shared by every read-only study: one file per study folder.
  return (dir / "parsed-study" / (study_folder_key(study_root) + ".bin")).string();
}

struct StudyCache::Contents {
  // A label file's entry as read: its stamp then, and where its path and parse lie in `bytes` (decoded by the
  // job that takes it, on every core); `now` is its stamp as load_labels found it.
  struct Entry {
    FileStamp stamp;
    std::string_view body;
    FileStamp now;
    bool stamped = false;  // `now` was taken by this load
    bool taken = false;    // its parse was handed out (a second use would find nothing to decode)
  };
  cache_codec::FileBytes bytes;  // the file as read: entries' keys and bodies point into it
  int rock_class = -1;           // the class asked for (files are stored with it applied, when it is a class)
  std::string class_maps;        // StudyClasses::map_key(): files are stored renumbered into the study's classes
  double conf_threshold = 0;
  // label_set_fingerprint(study) over the GT files stored here (a study of `fingerprint_gt_files` GT files).
  std::string fingerprint;
  std::uint64_t fingerprint_gt_files = 0;
  // The fingerprint's state after each domain (label_fingerprint.h): as read, then as load_labels left it.
  std::vector<FingerprintCheckpoint> checkpoints;
  std::unordered_map<std::string_view, Entry> labels;  // entry_key -> entry
  RegistrationEntries registrations;
  // Filled by load_labels: the stamps of files the file had no entry for (each other file's is its entry's `now`).
  std::mutex mu;
  std::unordered_map<std::string, FileStamp> new_stamps;
  bool filters_match = false;
  std::string key_arena;        // the entries' keys, apart from `bytes` so those can go (release_bytes)
  bool bytes_released = false;  // the entries' bodies are gone: none can be taken any more

  // Reads the label entries' index: each key (copied to one arena, sized by a first pass over the entries, so the
  // file's bytes can go once the entries are decoded while save() still finds each file's stamp by its key), its
  // stamp and where its body lies.
  void index_labels(cache_codec::Reader& r) {
    const auto files = r.pod<std::uint64_t>();
    size_t key_bytes = 0;
    cache_codec::Reader sizes = r;
    for (std::uint64_t k = 0; k < files; ++k) {
      key_bytes += sizes.view().size();
      sizes.bytes(sizes.pod<std::uint32_t>());
    }
    key_arena.reserve(key_bytes);  // never grown past this: the keys' views stay valid
    labels.reserve(files);
    for (std::uint64_t k = 0; k < files; ++k) {
      const std::string_view stored = r.view();
      cache_codec::Reader entry(r.bytes(r.pod<std::uint32_t>()));
      Entry e;
      e.stamp = cache_codec::read_stamp(entry);
      e.body = entry.rest();
      const size_t at = key_arena.size();
      key_arena.append(stored);
      if (!labels.emplace(std::string_view(key_arena).substr(at, stored.size()), e).second)
        throw std::runtime_error("a label file twice");
    }
  }

  // Lets the file's bytes go once load_labels has taken what it could (the keys live in `key_arena`): the table is
  // then computed without the whole file in memory (98 MB for 10,000 scenes).
  void release_bytes() {
    bytes.release();
    bytes_released = true;
  }

  // The parse `e` holds, when its file is unchanged since (its stamp as stored is `now`'s) and it is the file at
  // `path`. Decoded here, by the job that takes it: a warm load decodes on every core. An entry that doesn't decode
  // (it can't once the file verified, unless this code wrote it wrong) is parsed instead.
  bool take(Entry& e, const std::string& path, LabelFile* out) const {
    if (bytes_released || e.taken || !(e.stamp == e.now)) return false;
    try {
      cache_codec::Reader r(e.body);
      const std::string stored_path = r.str();
      LabelFile f = cache_codec::read_label_file(r, stored_path);
      if (!r.at_end()) return false;
      // The same file named as this run names the study (`big` or /tmp/big): its messages say it so too.
      if (stored_path != path) {
        f.path = path;
        for (LabelError& err : f.errors)
          if (err.file == stored_path) err.file = path;
      }
      *out = std::move(f);
    } catch (const std::exception&) {
      return false;
    }
    e.taken = true;
    return true;
  }
};

StudyCache::StudyCache(std::string path, const std::string& study_root, const std::function<void(const char*)>& hook)
    : path_(std::move(path)), root_(same_folder_name(study_root)), contents_(std::make_unique<Contents>()) {
  stats_.state = "missing";
  if (path_.empty()) return;
  auto c = std::make_unique<Contents>();
  cache_codec::FileBytes& file = c->bytes;
  // Reached without following links (a study may bring a .ipd-cache whose entries point anywhere).
  const fs::path where(path_);
  const auto dir = CacheDir::open(where.parent_path().string(), false);
  if (!dir) return;
  dir->remove_stale_temp_files();  // what writers killed mid-save left (each as large as the file)
  const int fd = dir->open_file(where.filename().string());
  if (fd < 0) return;  // missing, or refused and said so
  if (!cache_codec::read_whole_file(fd, hook, &file)) {
    stats_.state = "unreadable";
    return;
  }
  const std::string_view bytes(file.data(), file.size);
  try {
    if (bytes.size() < kHeaderBytes || std::memcmp(bytes.data(), kMagic, sizeof kMagic) != 0)
      throw std::runtime_error("not a parsed-study cache");
    cache_codec::Reader header(bytes.data() + sizeof kMagic, kHeaderBytes - sizeof kMagic);
    if (header.pod<std::uint32_t>() != kFormat) throw std::runtime_error("another format version");
    const auto size = header.pod<std::uint64_t>();
    const std::string_view mac = bytes.substr(kHeaderBytes - CacheSigner::kMacBytes, CacheSigner::kMacBytes);
    if (size != bytes.size() - kHeaderBytes) throw std::runtime_error("truncated");
    // Only what this installation wrote is trusted: a file that came with the study doesn't verify.
    if (!CacheSigner::instance().verify(kParsedStudySignature, bytes.substr(kHeaderBytes), mac))
      throw std::runtime_error("not signed by this installation");
    cache_codec::Reader r(bytes.data() + kHeaderBytes, size);
    if (r.view() != root_) throw std::runtime_error("another study");
    c->rock_class = r.pod<std::int32_t>();
    c->class_maps = r.str();
    c->conf_threshold = r.pod<double>();
    c->fingerprint = r.str();
    c->fingerprint_gt_files = r.pod<std::uint64_t>();
    const auto checkpoints = r.pod<std::uint64_t>();
    for (std::uint64_t k = 0; k < checkpoints; ++k) {
      FingerprintCheckpoint p;
      p.domain = r.str();
      p.files = r.pod<std::uint64_t>();
      p.state = r.str();
      c->checkpoints.push_back(std::move(p));
    }
    c->index_labels(r);
    const auto reports = r.pod<std::uint64_t>();
    c->registrations.reserve(reports);
    for (std::uint64_t k = 0; k < reports; ++k) {
      std::string key = r.str();
      c->registrations.emplace(std::move(key), cache_codec::read_report(r));
    }
    if (!r.at_end()) throw std::runtime_error("trailing bytes");
    contents_ = std::move(c);
    stats_.state = "loaded";
    stats_.registrations_stored = static_cast<int>(contents_->registrations.size());
  } catch (const std::exception& e) {
    stats_.state = std::string("ignored: ") + e.what();
  }
}

StudyCache::~StudyCache() = default;

namespace {
struct Fingerprint {
  std::string fingerprint;  // empty: left to the provenance (a file that can't be read, which it says)
  std::vector<FingerprintCheckpoint> checkpoints;
  int domains_read = -1;
};

// The label set's fingerprint once load_labels has taken what it could from the file. It hashes the GT files'
// bytes: when every one of them was read back unchanged (the stamps vouch for their bytes, as for their parse) and
// the study has no other, the stored one is this study's. Otherwise it is computed here, once, for the file to
// keep, resumed after the leading domains (in its path order) whose GT files all read back unchanged: a study that
// gained a domain reads the files of the domains from it on only. `stored`: what the file held (its fingerprint
// and checkpoints, and how many GT files it covered).
Fingerprint settle_fingerprint(const Study& study, const Fingerprint& stored, std::uint64_t stored_gt_files,
                               const std::map<std::string, std::atomic<int>>& reused_gt_of) {
  std::uint64_t gt_files = 0, reused_gt = 0;
  std::map<std::string, size_t> files_of;
  for (const auto& d : study.domains) {
    gt_files += d.stems.size();
    files_of[d.name] = d.stems.size();
    reused_gt += static_cast<std::uint64_t>(reused_gt_of.at(d.name).load());
  }
  if (!stored.fingerprint.empty() && reused_gt == gt_files && stored_gt_files == gt_files)
    return {stored.fingerprint, stored.checkpoints, 0};
  try {
    ResumedFingerprint f = label_set_fingerprint(study, stored.checkpoints, [&](const std::string& domain) {
      return reused_gt_of.at(domain) == static_cast<int>(files_of.at(domain));
    });
    return {std::move(f.fingerprint), std::move(f.checkpoints), f.domains_read};
  } catch (const std::exception&) {
    return {};
  }
}
}  // namespace

StudyLabels StudyCache::load_labels(const Study& study, const std::function<void(int done, int total)>& progress) {
  Contents& c = *contents_;
  c.filters_match = c.rock_class == study.config.rock_class && c.class_maps == study.classes.map_key() &&
                    c.conf_threshold == study.config.conf_threshold;
  // Each folder of label files is opened once beneath the study (never through a link) and its files' stamps
  // taken relative to it: one fstatat a file instead of resolving its whole path again. A folder that can't be
  // opened so has its files parsed (which says why).
  std::map<std::string, std::map<std::string, std::unique_ptr<OpenFolder>, std::less<>>, std::less<>>
      folders;  // domain -> model ("" for GT) -> folder
  std::uint64_t gt_files = 0;
  std::map<std::string, std::atomic<int>> reused_gt_of;  // domain -> its GT files taken from the file
  if (!path_.empty()) {
    auto open = [&](const std::string& domain, const std::string& model, const std::string& relative) {
      auto& slot = folders[domain][model];
      try {
        slot = std::make_unique<OpenFolder>(study.root, relative);
      } catch (const IoError&) {
        slot = nullptr;
      }
    };
    for (const auto& d : study.domains) {
      gt_files += d.stems.size();
      reused_gt_of.try_emplace(d.name, 0);
      open(d.name, "", d.name + "/labels");
      for (const auto& m : d.models) open(d.name, m, d.name + "/predictions/" + m);
    }
  }
  std::atomic<int> reused{0}, parsed{0};
  // An entry is touched by the one job of its file: no lock needed to stamp or take it.
  const auto reuse = [&](const std::string& domain, const std::string& model, const std::string& stem,
                         const std::string& path, LabelFile* out) {
    const OpenFolder* folder = nullptr;
    if (const auto d = folders.find(domain); d != folders.end())
      if (const auto m = d->second.find(model); m != d->second.end()) folder = m->second.get();
    const FileStamp now = folder ? stamp_at(*folder, stem + ".txt") : kNeverReused;
    std::string key = entry_key(domain, model, stem);
    const auto it = c.labels.find(key);
    if (it == c.labels.end()) {
      std::lock_guard<std::mutex> l(c.mu);
      c.new_stamps.insert_or_assign(std::move(key), now);
      ++parsed;
      return false;
    }
    Contents::Entry& e = it->second;
    e.now = now;
    e.stamped = true;
    if (!c.filters_match || !folder || !c.take(e, path, out)) {
      ++parsed;
      return false;
    }
    ++reused;
    if (model.empty()) ++reused_gt_of.at(domain);
    return true;
  };
  StudyLabels labels = ipd::load_labels(study, progress, reuse);
  c.release_bytes();
  stats_.files_reused = reused;
  stats_.files_parsed = parsed;
  if (!path_.empty()) {
    Fingerprint f =
        settle_fingerprint(study, {c.fingerprint, std::move(c.checkpoints)}, c.fingerprint_gt_files, reused_gt_of);
    labels.label_fingerprint = std::move(f.fingerprint);
    c.checkpoints = std::move(f.checkpoints);
    stats_.fingerprint_domains_read = f.domains_read;
  }
  return labels;
}

RegistrationEntries StudyCache::take_registrations() { return std::move(contents_->registrations); }

void StudyCache::hand_registrations_to(RegistrationCache& registration) {
  registration.preload(take_registrations());
  if (!path_.empty()) registration.defer_writes();
}

const std::vector<FingerprintCheckpoint>& StudyCache::fingerprint_checkpoints() const { return contents_->checkpoints; }

void StudyCache::save(const StudyLabels& labels, const RegistrationCache& registration) {
  if (path_.empty()) return;
  size_t files = 0;
  for (const auto& [d, stems] : labels.gt) files += stems.size();
  for (const auto& [d, models] : labels.predictions)
    for (const auto& [m, stems] : models) files += stems.size();
  const bool labels_same = stats_.state == "loaded" && contents_->filters_match && stats_.files_parsed == 0 &&
                           files == contents_->labels.size() && contents_->fingerprint == labels.label_fingerprint;
  const bool registrations_same = stats_.state == "loaded" && registration.served_only_preloaded();
  if (labels_same && registrations_same) return;
  // Copied only when the file is rewritten: a warm run of a 10,000-scene study keeps 30,000 reports.
  const RegistrationEntries served = registration.entries_to_keep();
  cache_codec::Writer w;
  w.out.reserve(kHeaderBytes + files * 1500);
  w.out.resize(kHeaderBytes);  // filled in below, once the payload's size and checksum are known
  w.str(root_);
  w.pod<std::int32_t>(labels.requested_class);
  w.str(labels.study.classes.map_key());
  w.pod<double>(labels.study.config.conf_threshold);
  w.str(labels.label_fingerprint);
  std::uint64_t gt_files = 0;
  for (const auto& d : labels.study.domains) gt_files += d.stems.size();
  w.pod<std::uint64_t>(gt_files);
  // The states belong to this fingerprint only: with another (a fingerprint left to the provenance) none is kept.
  static const std::vector<FingerprintCheckpoint> kNone;
  const auto& checkpoints = labels.label_fingerprint.empty() ? kNone : contents_->checkpoints;
  w.pod<std::uint64_t>(checkpoints.size());
  for (const FingerprintCheckpoint& p : checkpoints) {
    w.str(p.domain);
    w.pod<std::uint64_t>(p.files);
    w.str(p.state);
  }
  w.pod<std::uint64_t>(files);
  auto put = [&](const std::string& key, const LabelFile& f) {
    w.str(key);
    const size_t size_at = w.reserve_u32();
    const auto it = contents_->labels.find(key);
    const auto added = contents_->new_stamps.find(key);
    cache_codec::write_stamp(w, it != contents_->labels.end() && it->second.stamped ? it->second.now
                                : added != contents_->new_stamps.end()              ? added->second
                                                                                    : FileStamp{});
    w.str(f.path);
    cache_codec::write_label_file(w, f);
    w.patch_u32(size_at, static_cast<std::uint32_t>(w.out.size() - size_at - 4));
  };
  for (const auto& [d, stems] : labels.gt)
    for (const auto& [stem, f] : stems) put(entry_key(d, "", stem), f);
  for (const auto& [d, models] : labels.predictions)
    for (const auto& [m, stems] : models)
      for (const auto& [stem, f] : stems) put(entry_key(d, m, stem), f);
  w.pod<std::uint64_t>(served.size());
  for (const auto& [key, report] : served) {
    w.str(key);
    cache_codec::write_report(w, report);
  }
  cache_codec::Writer header;
  header.out.append(kMagic, sizeof kMagic);
  header.pod<std::uint32_t>(kFormat);
  header.pod<std::uint64_t>(w.out.size() - kHeaderBytes);
  header.out.append(CacheSigner::instance().mac(kParsedStudySignature, std::string_view(w.out).substr(kHeaderBytes)));
  std::memcpy(w.out.data(), header.out.data(), kHeaderBytes);
  // A cache that can't be written only costs time: failures are ignored.
  const fs::path where(path_);
  if (const auto dir = CacheDir::open(where.parent_path().string(), true))
    stats_.written = dir->write(where.filename().string(), w.out, write_hook_);
}

}  // namespace ipd
