// Signatures that let a cache trust only what this installation wrote. A study is untrusted input: its
// .ipd-cache/ may come from a collaborator's zip, be written by hand, or by another build whose methods give
// other answers. Every cache entry therefore carries an HMAC-SHA-256 under a per-user random key kept in the
// user cache directory (<user cache>/ipd-studio/key, mode 0600), mixed with this build's identity (version
// and compiler): an entry that does not verify is ignored and recomputed.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>

namespace ipd {

class CacheSigner {
 public:
  static constexpr size_t kMacBytes = 32;

  // The signer of this process, made from the key file on first use (created when missing). When the key
  // can't be read or created, a random key for this process is used: caches then only serve this run, and
  // the reason is said once on stderr.
  static const CacheSigner& instance();
  // A signer with the key file `key_path` (tests; instance() uses user_key_path()).
  explicit CacheSigner(const std::string& key_path);

  // HMAC-SHA-256 of `kind` (which cache the bytes belong to) and `data`: 32 raw bytes.
  std::string mac(std::string_view kind, std::string_view data) const;
  std::string mac_hex(std::string_view kind, std::string_view data) const;
  // Compares in constant time.
  bool verify(std::string_view kind, std::string_view data, std::string_view mac) const;

  // False when the key file was unusable and this process signs with a key of its own.
  bool persistent() const { return persistent_; }
  const std::string& problem() const { return problem_; }

 private:
  std::string key_;  // the key of this build: HMAC(file key, build identity)
  bool persistent_ = false;
  std::string problem_;
};

// $XDG_CACHE_HOME (or ~/.cache)/ipd-studio: the user cache directory of every study that can't hold its own,
// ipd-studio's demo study and recent list. A relative $XDG_CACHE_HOME is ignored, as the XDG Base Directory
// specification says: it would put the cache in whatever folder the program was started from. With neither
// variable set (a service, `env -i`), the home folder the password database gives this user
// (getpwuid(getuid())); "" when there is none either: never a folder other users can create first (/tmp).
std::string user_cache_root();
std::string user_key_path();
// user_cache_root() made ready to use: created with mode 0700 when missing, and refused ("" and why in *why)
// when there is none, or it is a symbolic link, not a folder, or owned by another user (who could then read
// the key and plant links in it). Callers then keep no user cache and say so.
std::string usable_user_cache_root(std::string* why = nullptr);

// What identifies this build in the key: version and compiler (a different compiler or version may give
// different registration results for the same cache key).
std::string build_identity();

}  // namespace ipd
