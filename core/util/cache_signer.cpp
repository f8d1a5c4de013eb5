#include "core/util/cache_signer.h"

#include <fcntl.h>
#include <openssl/crypto.h>
#include <openssl/evp.h>
#include <openssl/params.h>
#include <pwd.h>
#include <sys/random.h>
#include <sys/stat.h>
#include <unistd.h>

#include <fmt/format.h>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <stdexcept>

#ifndef IPD_VERSION
#define IPD_VERSION "unknown"
#endif

namespace fs = std::filesystem;

namespace ipd {

namespace {

constexpr size_t kKeyBytes = 32;

// HMAC-SHA-256 over a 0-separated pair, so ("ab", "c") and ("a", "bc") sign differently. Incremental: a
// 150 MB parsed-study file is signed in place, not copied.
std::string hmac_sha256(std::string_view key, std::string_view a, std::string_view b) {
  static EVP_MAC* const hmac = EVP_MAC_fetch(nullptr, "HMAC", nullptr);
  EVP_MAC_CTX* ctx = hmac ? EVP_MAC_CTX_new(hmac) : nullptr;
  if (!ctx) throw std::runtime_error("HMAC-SHA-256 is not available");
  char digest[] = "SHA256";
  const OSSL_PARAM params[] = {OSSL_PARAM_construct_utf8_string("digest", digest, 0), OSSL_PARAM_construct_end()};
  const auto* k = reinterpret_cast<const unsigned char*>(key.data());
  unsigned char out[EVP_MAX_MD_SIZE];
  size_t len = 0;
  const unsigned char zero = 0;
  const bool ok = EVP_MAC_init(ctx, k, key.size(), params) &&
                  EVP_MAC_update(ctx, reinterpret_cast<const unsigned char*>(a.data()), a.size()) &&
                  EVP_MAC_update(ctx, &zero, 1) &&
                  EVP_MAC_update(ctx, reinterpret_cast<const unsigned char*>(b.data()), b.size()) &&
                  EVP_MAC_final(ctx, out, &len, sizeof out);
  EVP_MAC_CTX_free(ctx);
  if (!ok) throw std::runtime_error("HMAC-SHA-256 failed");
  return std::string(reinterpret_cast<const char*>(out), len);
}

std::string random_bytes(size_t n) {
  std::string out(n, '\0');
  size_t done = 0;
  while (done < n) {
    const ssize_t got = ::getrandom(out.data() + done, n - done, 0);
    if (got < 0) {
      if (errno == EINTR) continue;
      throw std::runtime_error(std::string("no random bytes: ") + std::strerror(errno));
    }
    done += static_cast<size_t>(got);
  }
  return out;
}

// Reads the key at `path`: true with the key, false when there is none; throws (with the reason) when the
// file is there but can't be trusted as private to this user.
bool read_key(const std::string& path, std::string* key) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_NOFOLLOW | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) {
    if (errno == ENOENT) return false;
    throw std::runtime_error(fmt::format("{}: cannot read: {}", path, std::strerror(errno)));
  }
  struct stat st {};
  std::string why;
  if (::fstat(fd, &st) != 0)
    why = std::strerror(errno);
  else if (!S_ISREG(st.st_mode))
    why = "not a regular file";
  else if (st.st_uid != ::geteuid())
    why = "owned by another user";
  else if ((st.st_mode & 077) != 0)
    why = fmt::format("readable or writable by others (mode {:o}, expected 600)", st.st_mode & 0777);
  else if (st.st_size != static_cast<off_t>(kKeyBytes))
    why = fmt::format("{} bytes, expected {}", st.st_size, kKeyBytes);
  key->assign(kKeyBytes, '\0');
  if (why.empty() && ::read(fd, key->data(), kKeyBytes) != static_cast<ssize_t>(kKeyBytes)) why = "short read";
  ::close(fd);
  if (!why.empty())
    throw std::runtime_error(
        fmt::format("{}: cannot be used as the cache key: {}; remove it to make a new one", path, why));
  return true;
}

// Creates the key so that no reader ever sees a partial one: written and synced under a temporary name,
// then hard-linked to its name (which fails, leaving the other process's key, when two create it at once).
void create_key(const std::string& path) {
  // The folder's own error (no permission, say): the open below would only say "No such file or directory".
  const fs::path folder = fs::path(path).parent_path();
  if (std::error_code ec; !folder.empty() && !fs::create_directories(folder, ec) && ec)
    throw std::runtime_error(fmt::format("{}: cannot create the folder {}: {}", path, folder.string(), ec.message()));
  const std::string tmp =
      fmt::format("{}.tmp-{}-{}", path, ::getpid(), static_cast<unsigned>(random_bytes(2)[0]) & 0xff);
  const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0600);
  if (fd < 0) throw std::runtime_error(fmt::format("{}: cannot create: {}", path, std::strerror(errno)));
  const std::string key = random_bytes(kKeyBytes);
  const bool ok = ::write(fd, key.data(), key.size()) == static_cast<ssize_t>(key.size()) && ::fsync(fd) == 0;
  const int err = errno;
  ::close(fd);
  if (!ok) {
    ::unlink(tmp.c_str());
    throw std::runtime_error(fmt::format("{}: cannot create: {}", path, std::strerror(err)));
  }
  const int linked = ::link(tmp.c_str(), path.c_str());
  const int link_err = errno;
  ::unlink(tmp.c_str());
  if (linked != 0 && link_err != EEXIST)
    throw std::runtime_error(fmt::format("{}: cannot create: {}", path, std::strerror(link_err)));
}

}  // namespace

std::string user_cache_root() {
  const auto absolute = [](const char* p) { return p && *p && fs::path(p).is_absolute(); };
  const char* xdg = std::getenv("XDG_CACHE_HOME");
  if (absolute(xdg)) return (fs::path(xdg) / "ipd-studio").string();
  const char* home = std::getenv("HOME");
  if (!absolute(home)) {
    const passwd* pw = ::getpwuid(::getuid());
    home = pw ? pw->pw_dir : nullptr;
  }
  if (!absolute(home)) return "";
  return (fs::path(home) / ".cache" / "ipd-studio").string();
}

std::string usable_user_cache_root(std::string* why) {
  std::string problem;
  const std::string root = user_cache_root();
  struct stat st {};
  std::error_code ec;
  if (root.empty()) {
    problem = "no user cache: XDG_CACHE_HOME and HOME are unset and this user has no home folder";
  } else if (fs::create_directories(fs::path(root).parent_path(), ec); ec) {
    problem = fmt::format("{}: cannot create the folder: {}", fs::path(root).parent_path().string(), ec.message());
  } else if (::mkdir(root.c_str(), 0700) != 0 && errno != EEXIST) {
    problem = fmt::format("{}: cannot create the folder: {}", root, std::strerror(errno));
  } else if (::lstat(root.c_str(), &st) != 0) {
    problem = fmt::format("{}: cannot examine: {}", root, std::strerror(errno));
  } else if (S_ISLNK(st.st_mode)) {
    problem = fmt::format("{}: is a symbolic link; the user cache is not used", root);
  } else if (!S_ISDIR(st.st_mode)) {
    problem = fmt::format("{}: is not a folder; the user cache is not used", root);
  } else if (st.st_uid != ::geteuid()) {
    problem = fmt::format("{}: belongs to another user (uid {}); the user cache is not used", root, st.st_uid);
  }
  if (why) *why = problem;
  return problem.empty() ? root : "";
}

std::string user_key_path() { return (fs::path(user_cache_root()) / "key").string(); }

std::string build_identity() { return std::string("ipd-studio " IPD_VERSION " ") + __VERSION__; }

CacheSigner::CacheSigner(const std::string& key_path) {
  std::string file_key;
  try {
    if (key_path.empty()) throw std::runtime_error("no user cache for the key");
    if (!read_key(key_path, &file_key)) {
      create_key(key_path);
      if (!read_key(key_path, &file_key)) throw std::runtime_error(key_path + ": vanished after it was created");
    }
    persistent_ = true;
  } catch (const std::exception& e) {
    problem_ = e.what();
    file_key = random_bytes(kKeyBytes);
  }
  key_ = hmac_sha256(file_key, "build", build_identity());
}

const CacheSigner& CacheSigner::instance() {
  static const CacheSigner signer = [] {
    std::string why;
    const std::string root = usable_user_cache_root(&why);
    CacheSigner s(root.empty() ? std::string() : (fs::path(root) / "key").string());
    if (!s.persistent())
      std::fprintf(stderr, "%s; caches written now serve this run only\n", (root.empty() ? why : s.problem()).c_str());
    return s;
  }();
  return signer;
}

std::string CacheSigner::mac(std::string_view kind, std::string_view data) const {
  return hmac_sha256(key_, kind, data);
}

std::string CacheSigner::mac_hex(std::string_view kind, std::string_view data) const {
  std::string out;
  for (const unsigned char c : mac(kind, data)) out += fmt::format("{:02x}", c);
  return out;
}

bool CacheSigner::verify(std::string_view kind, std::string_view data, std::string_view given) const {
  const std::string want = mac(kind, data);
  return given.size() == want.size() && CRYPTO_memcmp(want.data(), given.data(), want.size()) == 0;
}

}  // namespace ipd
