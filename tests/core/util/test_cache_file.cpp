// Cache files inside an untrusted study (cache_file.h): a symbolic link anywhere from .ipd-cache on is
// never written, created or deleted through, even when swapped in between the check and the write; and the
// signer (cache_signer.h) trusts only its own key, kept private to the user.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <fmt/format.h>
#include <cstdlib>
#include <filesystem>
#include <optional>

#include "core/ipd/study_cache.h"
#include "core/registration/registration_cache.h"
#include "core/util/atomic_file.h"
#include "core/util/cache_file.h"
#include "core/util/cache_signer.h"
#include "tests/support/test_support.h"

namespace fs = std::filesystem;

namespace ipd {
namespace {

// A process id that no process has now: a child that has exited and been reaped.
pid_t dead_pid() {
  const pid_t pid = ::fork();
  if (pid == 0) ::_exit(0);
  ::waitpid(pid, nullptr, 0);
  return pid;
}

std::vector<Box> rocks_cache_file(double dx) { return test::seven_rocks(dx); }

TEST(CacheDir, AnchorIsTheStudyRootBeforeTheLastIpdCache) {
  EXPECT_EQ(cache_anchor("/s/.ipd-cache/registration"), "/s");
  EXPECT_EQ(cache_anchor("/s/.ipd-cache"), "/s");
  EXPECT_EQ(cache_anchor(".ipd-cache/registration"), ".");
  EXPECT_EQ(cache_anchor("/a/.ipd-cache/b/.ipd-cache/c"), "/a/.ipd-cache/b");
  EXPECT_EQ(cache_anchor("/home/u/.cache/ipd-studio/registration"), "/home/u/.cache/ipd-studio/registration");
}

TEST(CacheDir, ALinkedIpdCacheIsNeitherWrittenNorReadAndSaidOnce) {
  test::TempDir d;
  fs::create_directories(d / "study");
  fs::create_directories(d / "outside");
  fs::create_symlink(d / "outside", d / "study/.ipd-cache");
  testing::internal::CaptureStderr();
  EXPECT_EQ(CacheDir::open(d / "study/.ipd-cache/registration", true), nullptr);
  EXPECT_EQ(CacheDir::open(d / "study/.ipd-cache", false), nullptr);
  const RegistrationCache cache(d / "study/.ipd-cache/registration");
  bool hit = true;
  const RegistrationReport r =
      register_rocks_cached(&cache, rocks_cache_file(0), rocks_cache_file(0.02), RegistrationOptions{}, &hit);
  EXPECT_FALSE(hit);
  EXPECT_EQ(r.pairs.size(), 7u);
  EXPECT_EQ(testing::internal::GetCapturedStderr(), d / "study/.ipd-cache" + ": is a symbolic link; not used\n");
  EXPECT_TRUE(fs::is_empty(d / "outside"));  // no registration/ folder created through the link
}

TEST(CacheDir, LinkedEntriesAndFoldersAtAnyDepthAreLeftAlone) {
  test::TempDir d;
  fs::create_directories(d / "study/.ipd-cache/registration");
  fs::create_directories(d / "outside");
  test::write_text(d / "outside/victim", "precious\n");
  const RegistrationOptions o;
  const auto a = rocks_cache_file(0), b = rocks_cache_file(0.02);
  const std::string key = registration_cache_key(a, b, o);
  const RegistrationCache cache(d / "study/.ipd-cache/registration");
  // The entry's two-digit folder is a link: nothing is stored through it.
  fs::create_symlink(d / "outside", d / "study/.ipd-cache/registration/" + key.substr(0, 2));
  testing::internal::CaptureStderr();
  EXPECT_FALSE(cache.store(key, register_rocks(a, b, o)));
  EXPECT_FALSE(cache.load(key, 7, 7).has_value());
  EXPECT_EQ(testing::internal::GetCapturedStderr(),
            d / "study/.ipd-cache/registration/" + key.substr(0, 2) + ": is a symbolic link; not used\n");
  EXPECT_EQ(fs::directory_iterator(d / "outside")->path().filename(), "victim");  // nothing added
  EXPECT_TRUE(fs::is_symlink(d / "study/.ipd-cache/registration/" + key.substr(0, 2)));

  // The entry itself is a link to a file outside: not replaced, not read, the target unchanged.
  fs::remove(d / "study/.ipd-cache/registration/" + key.substr(0, 2));
  fs::create_directories(d / "study/.ipd-cache/registration/" + key.substr(0, 2));
  fs::create_symlink(d / "outside/victim", cache.entry_path(key));
  testing::internal::CaptureStderr();
  EXPECT_FALSE(cache.store(key, register_rocks(a, b, o)));
  EXPECT_FALSE(cache.load(key, 7, 7).has_value());
  EXPECT_EQ(testing::internal::GetCapturedStderr(), cache.entry_path(key) + ": is a symbolic link; not used\n");
  EXPECT_EQ(read_file(d / "outside/victim"), "precious\n");
  EXPECT_TRUE(fs::is_symlink(cache.entry_path(key)));

  // registration/ is a dangling link: its target's folders are never created.
  fs::remove_all(d / "study/.ipd-cache/registration");
  fs::create_symlink(d / "outside/new/deeper", d / "study/.ipd-cache/registration");
  const RegistrationCache dangling(d / "study/.ipd-cache/registration");
  testing::internal::CaptureStderr();
  EXPECT_FALSE(dangling.store(key, register_rocks(a, b, o)));
  EXPECT_EQ(testing::internal::GetCapturedStderr(),
            d / "study/.ipd-cache/registration: is a symbolic link; not used\n");
  EXPECT_FALSE(fs::exists(d / "outside/new"));
}

TEST(CacheDir, ALinkSwappedInBeforeTheRenameIsReplacedNotWrittenThrough) {
  test::TempDir d;
  fs::create_directories(d / "study");
  test::write_text(d / "victim", "precious\n");
  const auto dir = CacheDir::open(d / "study/.ipd-cache", true);
  ASSERT_NE(dir, nullptr);
  int calls = 0;
  EXPECT_TRUE(dir->write("parsed-study.bin", "cache bytes", [&](const char* step) {
    EXPECT_STREQ(step, "checked");
    ++calls;
    fs::create_symlink(d / "victim", d / "study/.ipd-cache/parsed-study.bin");  // the attacker's move
  }));
  EXPECT_EQ(calls, 1);
  EXPECT_EQ(read_file(d / "victim"), "precious\n");
  EXPECT_FALSE(fs::is_symlink(d / "study/.ipd-cache/parsed-study.bin"));
  EXPECT_EQ(read_file(d / "study/.ipd-cache/parsed-study.bin"), "cache bytes");

  // .ipd-cache itself swapped for a link after it was opened: the write stays in the folder that was opened.
  fs::create_directories(d / "outside");
  fs::rename(d / "study/.ipd-cache", d / "study/moved");
  fs::create_symlink(d / "outside", d / "study/.ipd-cache");
  EXPECT_TRUE(dir->write("sub/entry", "x"));
  EXPECT_TRUE(fs::is_empty(d / "outside"));
  EXPECT_EQ(read_file(d / "study/moved/sub/entry"), "x");
}

TEST(CacheDir, StudyCacheNeverWritesThroughALinkedParsedStudyFile) {
  test::TempDir d;
  test::write_text(d / "study/real/labels/s0.txt", "0 0.5 0.5 0.1 0.1\n");
  test::write_text(d / "victim", "precious\n");
  fs::create_directories(d / "study/.ipd-cache");
  fs::create_symlink(d / "victim", d / "study/.ipd-cache/parsed-study.bin");
  const Study study = open_study(d / "study");
  testing::internal::CaptureStderr();
  StudyCache cache(parsed_study_cache_path(study.root), study.root);
  const StudyLabels labels = cache.load_labels(study);
  cache.save(labels, RegistrationCache(""));
  EXPECT_EQ(testing::internal::GetCapturedStderr(),
            d / "study/.ipd-cache/parsed-study.bin: is a symbolic link; not used\n");
  EXPECT_FALSE(cache.stats().written);
  EXPECT_EQ(read_file(d / "victim"), "precious\n");

  // The swap between check and rename, through the StudyCache's own write.
  fs::remove(d / "study/.ipd-cache/parsed-study.bin");
  StudyCache again(parsed_study_cache_path(study.root), study.root);
  again.set_write_hook([&](const char*) { fs::create_symlink(d / "victim", d / "study/.ipd-cache/parsed-study.bin"); });
  again.save(again.load_labels(study), RegistrationCache(""));
  EXPECT_TRUE(again.stats().written);
  EXPECT_EQ(read_file(d / "victim"), "precious\n");
  EXPECT_EQ(read_file(d / "study/.ipd-cache/parsed-study.bin").substr(0, 8), "IPDSTUDY");
}

TEST(CacheDir, TempFilesOfKilledWritersAreRemoved) {
  test::TempDir d;
  test::write_text(d / "study/real/labels/s0.txt", "0 0.5 0.5 0.1 0.1\n");
  const std::string dead = fmt::format("parsed-study.bin.tmp-{}-7", dead_pid());
  const std::string alive = fmt::format("parsed-study.bin.tmp-{}-7", ::getpid());
  test::write_text(d / "study/.ipd-cache/" + dead, "half a cache");
  test::write_text(d / "study/.ipd-cache/" + alive, "being written");
  test::write_text(d / "outside", "precious\n");
  const std::string dead_link = fmt::format("x.tmp-{}-8", dead_pid());
  fs::create_symlink(d / "outside", d / "study/.ipd-cache/" + dead_link);
  const Study study = open_study(d / "study");
  StudyCache cache(parsed_study_cache_path(study.root), study.root);
  EXPECT_FALSE(fs::exists(d / "study/.ipd-cache/" + dead));
  EXPECT_TRUE(fs::exists(d / "study/.ipd-cache/" + alive));           // its writer still runs
  EXPECT_FALSE(fs::is_symlink(d / "study/.ipd-cache/" + dead_link));  // the link itself goes ...
  EXPECT_EQ(read_file(d / "outside"), "precious\n");                  // ... never its target
}

// Sets an environment variable for one test and restores what was there.
class ScopedEnv {
 public:
  ScopedEnv(const char* name, const char* value) : name_(name) {
    const char* old = std::getenv(name);
    if (old) old_ = old;
    ::setenv(name, value, 1);
  }
  ~ScopedEnv() {
    if (old_)
      ::setenv(name_, old_->c_str(), 1);
    else
      ::unsetenv(name_);
  }

 private:
  const char* name_;
  std::optional<std::string> old_;
};

// A relative XDG_CACHE_HOME made ./relcache/ipd-studio/ in whatever folder the program started in; the XDG
// Base Directory specification calls such a path invalid, to be ignored.
TEST(CacheSigner, ARelativeXdgCacheHomeIsIgnored) {
  const ScopedEnv home("HOME", "/home/someone");
  {
    const ScopedEnv xdg("XDG_CACHE_HOME", "relcache");
    EXPECT_EQ(user_cache_root(), "/home/someone/.cache/ipd-studio");
    EXPECT_EQ(user_key_path(), "/home/someone/.cache/ipd-studio/key");
  }
  const ScopedEnv xdg("XDG_CACHE_HOME", "/var/cache/someone");
  EXPECT_EQ(user_cache_root(), "/var/cache/someone/ipd-studio");
}

// A cache folder that can't be made (no permission) was reported as "No such file or directory", the open of
// the key's temp file in it; the folder's own error is named. Run as an unprivileged user in a child when the
// tests run as root, whom permissions don't stop.
TEST(CacheSigner, AFolderThatCannotBeMadeIsReportedWithItsOwnError) {
  test::TempDir d;
  fs::create_directories(d / "ro");
  const fs::perms read_and_enter = fs::perms::owner_read | fs::perms::owner_exec | fs::perms::group_read |
                                   fs::perms::group_exec | fs::perms::others_read | fs::perms::others_exec;
  fs::permissions(d.path(), read_and_enter | fs::perms::owner_write);  // the child may enter, not write
  fs::permissions(d / "ro", read_and_enter);
  int pipe_fds[2];
  ASSERT_EQ(::pipe(pipe_fds), 0);
  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    ::close(pipe_fds[0]);
    if (::geteuid() == 0 && ::setuid(65534) != 0) ::_exit(2);
    const CacheSigner signer(d / "ro/ipd-studio/key");
    const std::string problem = signer.problem();
    const bool written = ::write(pipe_fds[1], problem.data(), problem.size()) == static_cast<ssize_t>(problem.size());
    ::_exit(written ? 0 : 3);
  }
  ::close(pipe_fds[1]);
  std::string problem;
  char buf[512];
  for (ssize_t n; (n = ::read(pipe_fds[0], buf, sizeof buf)) > 0;) problem.append(buf, static_cast<size_t>(n));
  ::close(pipe_fds[0]);
  int status = 0;
  ASSERT_EQ(::waitpid(child, &status, 0), child);
  ASSERT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << status;
  EXPECT_EQ(problem,
            d / "ro/ipd-studio/key" + ": cannot create the folder " + d / "ro/ipd-studio" + ": Permission denied");
  fs::permissions(d / "ro", fs::perms::owner_all);
}

TEST(CacheSigner, KeyIsCreatedPrivateAndSignsOnlyForItsOwner) {
  test::TempDir d;
  const CacheSigner signer(d / "cache/ipd-studio/key");
  ASSERT_TRUE(signer.persistent()) << signer.problem();
  struct stat st {};
  ASSERT_EQ(::stat((d / "cache/ipd-studio/key").c_str(), &st), 0);
  EXPECT_EQ(st.st_mode & 0777, 0600u);
  EXPECT_EQ(st.st_size, 32);
  const std::string mac = signer.mac("registration entry", "payload");
  EXPECT_EQ(mac.size(), 32u);
  EXPECT_EQ(signer.mac_hex("registration entry", "payload").size(), 64u);
  EXPECT_TRUE(signer.verify("registration entry", "payload", mac));
  EXPECT_FALSE(signer.verify("registration entry", "payloaD", mac));
  EXPECT_FALSE(signer.verify("parsed study 3", "payload", mac));      // another cache's kind
  EXPECT_FALSE(signer.verify("registration entr", "ypayload", mac));  // the kind/data boundary counts
  EXPECT_EQ(CacheSigner(d / "cache/ipd-studio/key").mac("registration entry", "payload"), mac);  // same key
  EXPECT_NE(CacheSigner(d / "other/key").mac("registration entry", "payload"), mac);             // another installation
  EXPECT_EQ(std::distance(fs::directory_iterator(d / "cache/ipd-studio"), fs::directory_iterator()),
            1);  // no temp left
}

TEST(CacheSigner, AKeyOthersCanReadIsNotTrusted) {
  test::TempDir d;
  { const CacheSigner make(d / "key"); }
  fs::permissions(d / "key",
                  fs::perms::owner_read | fs::perms::owner_write | fs::perms::group_read | fs::perms::others_read);
  const CacheSigner shared(d / "key");
  EXPECT_FALSE(shared.persistent());
  EXPECT_EQ(shared.problem(), d / "key" +
                                  ": cannot be used as the cache key: readable or writable by others (mode 644, "
                                  "expected 600); remove it to make a new one");
  test::write_text(d / "short", "0123");
  fs::permissions(d / "short", fs::perms::owner_read | fs::perms::owner_write);
  EXPECT_EQ(CacheSigner(d / "short").problem(),
            d / "short" + ": cannot be used as the cache key: 4 bytes, expected 32; remove it to make a new one");
  fs::create_symlink(d / "key", d / "link");
  EXPECT_EQ(CacheSigner(d / "link").problem(), d / "link" + ": cannot read: Too many levels of symbolic links");
  // Two signers of one process with unusable keys still disagree with each other: nothing they write
  // outlives the run.
  EXPECT_NE(CacheSigner(d / "link").mac("k", "x"), CacheSigner(d / "link").mac("k", "x"));
}

}  // namespace
}  // namespace ipd
