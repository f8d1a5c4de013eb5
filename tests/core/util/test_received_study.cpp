// A study received from someone else, and a second process at work on it: every file the study holds is
// reached through a descriptor opened beneath the study (contained_file.h), so a folder or file swapped for a
// link, a FIFO or a hard link between a check and its use can't make the tool read, write, delete or wait
// outside the study. The swaps happen in each operation's step hook, between its check and its use: no timing.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <pwd.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <filesystem>
#include <map>
#include <mutex>
#include <optional>
#include <set>
#include <string>
#include <thread>

#include "app/studio/recent_studies.h"
#include "core/io/label_io.h"
#include "core/picture/picture_codec.h"
#include "core/session/session.h"
#include "core/session/study_lock.h"
#include "core/util/atomic_file.h"
#include "core/util/cache_signer.h"
#include "core/util/contained_file.h"
#include "tests/support/test_support.h"

namespace fs = std::filesystem;

namespace ipd {
namespace {

std::string png_of(int w, int h) {
  std::vector<uchar> png;
  EXPECT_TRUE(encode_picture(".png", cv::Mat(h, w, CV_8UC1, cv::Scalar(9)), &png));
  return std::string(png.begin(), png.end());
}

// Opens the write end of `fifo` (releasing a reader blocked in open) unless `done` is set within 5 s;
// `released` says whether it had to. A reader that never blocks is done long before.
class FifoWatch {
 public:
  explicit FifoWatch(std::string fifo) : fifo_(std::move(fifo)), thread_([this] { watch(); }) {}
  ~FifoWatch() {
    finish();
    thread_.join();
  }
  void finish() {
    std::lock_guard<std::mutex> l(mu_);
    done_ = true;
    cv_.notify_all();
  }
  bool released() const { return released_; }

 private:
  void watch() {
    std::unique_lock<std::mutex> l(mu_);
    if (cv_.wait_for(l, std::chrono::seconds(5), [&] { return done_; })) return;
    released_ = true;
    const int fd = ::open(fifo_.c_str(), O_WRONLY | O_NONBLOCK);
    if (fd >= 0) ::close(fd);
  }
  std::string fifo_;
  std::mutex mu_;
  std::condition_variable cv_;
  bool done_ = false;
  std::atomic<bool> released_{false};
  std::thread thread_;
};

// A picture swapped for a FIFO after its folder was opened (where a check by name used to come before an open
// by name): opened with O_NONBLOCK and refused by fstat, at once.
TEST(ReceivedStudy, APictureSwappedForAFifoBeforeItIsOpenedIsRefusedWithoutWaiting) {
  test::TempDir d;
  const std::string picture = d / "real/images/s1.png";
  test::write_text(picture, png_of(6, 4));
  FifoWatch watch(picture);
  const PictureRead r = read_study_picture(d.path(), picture, cv::IMREAD_GRAYSCALE, [&](const char* step) {
    if (std::string(step) != "folder opened") return;
    fs::remove(picture);
    ASSERT_EQ(::mkfifo(picture.c_str(), 0600), 0);
  });
  watch.finish();
  EXPECT_FALSE(watch.released());
  EXPECT_TRUE(r.image.empty());
  EXPECT_EQ(r.problem, picture + ": is a FIFO, expected a regular file");
}

// A picture swapped for a link to a picture outside the study is refused, not read through.
TEST(ReceivedStudy, APictureSwappedForALinkBeforeItIsOpenedIsNotFollowed) {
  test::TempDir d, elsewhere;
  const std::string picture = d / "real/images/s1.png";
  test::write_text(picture, png_of(6, 4));
  test::write_text(elsewhere / "secret.png", png_of(8, 8));
  const PictureRead r = read_study_picture(d.path(), picture, cv::IMREAD_GRAYSCALE, [&](const char* step) {
    if (std::string(step) != "folder opened") return;
    fs::remove(picture);
    fs::create_symlink(elsewhere / "secret.png", picture);
  });
  EXPECT_TRUE(r.image.empty());
  EXPECT_EQ(r.problem,
            picture + ": is a symbolic link; reading through it is refused (links inside a study are never followed)");
}

// The pictures folder swapped for a link after the study was scanned: the walk beneath the study refuses it.
TEST(ReceivedStudy, APicturesFolderSwappedForALinkIsNotFollowed) {
  test::TempDir d, elsewhere;
  test::write_text(elsewhere / "images/s1.png", png_of(8, 8));
  fs::create_directories(d / "real");
  fs::create_directory_symlink(elsewhere / "images", d / "real/images");
  const PictureRead r = read_study_picture(d.path(), d / "real/images/s1.png", cv::IMREAD_GRAYSCALE);
  EXPECT_TRUE(r.image.empty());
  EXPECT_EQ(r.problem,
            d / "real/images" +
                ": is a symbolic link; reading through it is refused (links inside a study are never followed)");
}

// A picture read whole once, its size checked and its pixels decoded from those same bytes.
TEST(ReceivedStudy, APictureIsDecodedFromTheBytesReadBeneathTheStudy) {
  test::TempDir d;
  test::write_text(d / "real/images/s1.png", png_of(6, 4));
  const PictureRead r = read_study_picture(d.path(), d / "real/images/s1.png", cv::IMREAD_GRAYSCALE);
  EXPECT_EQ(r.problem, "");
  ASSERT_EQ(r.image.cols, 6);
  EXPECT_EQ(r.image.rows, 4);
  EXPECT_EQ(r.image.at<uchar>(3, 5), 9);
  EXPECT_EQ(read_study_picture(d.path(), d / "real/images/none.png", cv::IMREAD_GRAYSCALE).problem,
            d / "real/images/none.png" + ": no such file");
}

// review/ swapped for a link after it was checked: the stale temp files of the link's target stay; those of
// the folder that was opened go.
TEST(ReceivedStudy, StaleTempFileCleanUpNeverDeletesThroughAFolderSwappedForALink) {
  test::TempDir d, elsewhere;
  test::write_text(d / "review/a.json.tmp-4194305-1", "{");
  test::write_text(elsewhere / "b.json.tmp-4194305-2", "precious");
  const int removed = remove_stale_temp_files_beneath(d.path(), "review", [&](const char* step) {
    if (std::string(step) != "folder opened") return;
    fs::rename(d / "review", d / "review-moved");
    fs::create_directory_symlink(elsewhere.path(), d / "review");
  });
  EXPECT_EQ(removed, 1);
  EXPECT_FALSE(fs::exists(d / "review-moved/a.json.tmp-4194305-1"));
  EXPECT_EQ(read_file(elsewhere / "b.json.tmp-4194305-2"), "precious");
  // And a folder that is already a link is not tidied at all.
  EXPECT_EQ(remove_stale_temp_files_beneath(d.path(), "review"), 0);
  EXPECT_EQ(read_file(elsewhere / "b.json.tmp-4194305-2"), "precious");
}

// pairs/<A>__<B> a link: listed as not a folder, never tidied.
TEST(ReceivedStudy, PairsFoldersThatAreLinksAreNotListed) {
  test::TempDir d, elsewhere;
  fs::create_directories(d / "pairs/real__synth");
  fs::create_directory_symlink(elsewhere.path(), d / "pairs/real__hapke");
  test::write_text(d / "pairs/notes.txt", "x");
  EXPECT_EQ(folders_beneath(d.path(), "pairs"), std::vector<std::string>{"real__synth"});
  EXPECT_TRUE(folders_beneath(d.path(), "missing").empty());
}

// The lock file a hard link to a file outside the study: the holder's note would replace that file's
// contents. Refused, the file untouched.
TEST(ReceivedStudy, ALockFileThatIsAHardLinkIsRefusedAndNeverWritten) {
  test::TempDir d, elsewhere;
  test::write_text(elsewhere / "thesis.tex", "precious\n");
  fs::create_directories(d / ".ipd-cache");
  fs::create_hard_link(elsewhere / "thesis.tex", d / ".ipd-cache/lock");
  std::string held_by;
  EXPECT_EQ(StudyLock::try_acquire(d.path(), &held_by), nullptr);
  EXPECT_EQ(held_by, d / ".ipd-cache/lock" +
                         ": has 2 names (a hard link to another file); no lock is taken through it (delete it: the "
                         "study's .ipd-cache may be deleted)");
  EXPECT_EQ(read_file(elsewhere / "thesis.tex"), "precious\n");
  // Deleted, the lock is taken (a fresh file of one name).
  fs::remove(d / ".ipd-cache/lock");
  EXPECT_NE(StudyLock::try_acquire(d.path(), &held_by), nullptr);
}

// .ipd-cache may be deleted at any time: a window that holds the study keeps holding it (the study folder's
// own lock), so a second window can't take a new lock file and save over the first one's edits.
TEST(ReceivedStudy, DeletingTheCacheFolderLetsNoSecondWindowTakeTheStudy) {
  test::TempDir d;
  std::string held_by;
  const auto first = StudyLock::try_acquire(d.path(), &held_by);
  ASSERT_NE(first, nullptr) << held_by;
  fs::remove_all(d / ".ipd-cache");
  EXPECT_EQ(StudyLock::try_acquire(d.path(), &held_by), nullptr);
  EXPECT_EQ(held_by, "another window");
}

// A lock file another user created (0644), whose holder is gone, is stale: taken (read-only) by the next
// window, not a study read-only for everyone. Run as an unprivileged user in a child when the tests run as root.
TEST(ReceivedStudy, AStaleLockFileOfAnotherUserIsTaken) {
  if (::geteuid() != 0) GTEST_SKIP() << "needs root to make a file of another user";
  test::TempDir d;
  test::write_text(d / ".ipd-cache/lock", "pid 4194305 on elsewhere\n");
  ASSERT_EQ(::chmod((d / ".ipd-cache/lock").c_str(), 0644), 0);
  for (const std::string& p : {d.path(), d / ".ipd-cache"}) ASSERT_EQ(::chmod(p.c_str(), 0777), 0);
  const pid_t child = ::fork();
  if (child == 0) {
    if (::setgid(65534) != 0 || ::setuid(65534) != 0) ::_exit(3);
    std::string why;
    ::_exit(StudyLock::try_acquire(d.path(), &why) ? 0 : 1);
  }
  int status = 0;
  ASSERT_EQ(::waitpid(child, &status, 0), child);
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 0);
  EXPECT_EQ(read_file(d / ".ipd-cache/lock"), "pid 4194305 on elsewhere\n");  // another user's note, not written
}

// Every pair of domains is compared: a study of more than kMaxDomains is refused with the count and the limit
// (1,000 one-scene domains took 24 s and 1 GB, 10,000 ran past 300 s and 12 GB).
TEST(ReceivedStudy, AStudyOfTooManyDomainsIsRefused) {
  test::TempDir d;
  for (int k = 0; k <= 100; ++k) fs::create_directories(d / ("d" + std::to_string(k) + "/labels"));
  EXPECT_EQ(test::open_study_error(d.path()), d.path() +
                                                  ": 101 domains, more than the 100 a study may hold (every "
                                                  "pair of domains is compared; 1,000 one-scene domains take 24 "
                                                  "s and 1 GB)");
  fs::remove_all(d / "d100");
  EXPECT_EQ(test::open_study_error(d.path()), "no error");
}

// Sets an environment variable (or unsets it: nullptr) for a scope.
class ScopedEnvReceivedStudy {
 public:
  ScopedEnvReceivedStudy(const char* name, const char* value) : name_(name) {
    if (const char* old = std::getenv(name)) old_ = old;
    if (value)
      ::setenv(name, value, 1);
    else
      ::unsetenv(name);
  }
  ~ScopedEnvReceivedStudy() {
    if (old_)
      ::setenv(name_, old_->c_str(), 1);
    else
      ::unsetenv(name_);
  }

 private:
  const char* name_;
  std::optional<std::string> old_;
};

// With HOME and XDG_CACHE_HOME unset (a service, `env -i`) the user cache is below the home folder the
// password database gives this user, never a folder of /tmp another user could have made first.
TEST(ReceivedStudy, WithoutHomeTheUserCacheIsInThePasswordDatabasesHomeFolder) {
  const ScopedEnvReceivedStudy xdg("XDG_CACHE_HOME", nullptr), home("HOME", nullptr);
  const passwd* pw = ::getpwuid(::getuid());
  ASSERT_NE(pw, nullptr);
  EXPECT_EQ(user_cache_root(), std::string(pw->pw_dir) + "/.cache/ipd-studio");
}

// The user cache root is made private (0700), and one that is a link or belongs to another user is not used.
TEST(ReceivedStudy, TheUserCacheRootIsPrivateAndOurOwn) {
  test::TempDir d, elsewhere;
  const ScopedEnvReceivedStudy xdg("XDG_CACHE_HOME", d.path().c_str());
  std::string why;
  EXPECT_EQ(usable_user_cache_root(&why), d / "ipd-studio");
  EXPECT_EQ(why, "");
  EXPECT_EQ(fs::status(d / "ipd-studio").permissions() & fs::perms::all, fs::perms::owner_all);
  fs::remove(d / "ipd-studio");
  fs::create_directory_symlink(elsewhere.path(), d / "ipd-studio");
  EXPECT_EQ(usable_user_cache_root(&why), "");
  EXPECT_EQ(why, d / "ipd-studio" + ": is a symbolic link; the user cache is not used");
  if (::geteuid() == 0) {  // only root can give a folder away
    fs::remove(d / "ipd-studio");
    fs::create_directory(d / "ipd-studio");
    ASSERT_EQ(::chown((d / "ipd-studio").c_str(), 65534, 65534), 0);
    EXPECT_EQ(usable_user_cache_root(&why), "");
    EXPECT_EQ(why, d / "ipd-studio" + ": belongs to another user (uid 65534); the user cache is not used");
  }
}

// The recent-studies list that can't be written is said as what it is (not a lost edit); written, it is
// read back newest first, each study once.
TEST(ReceivedStudy, AnUnwritableRecentStudiesListIsSaidAsSuch) {
  test::TempDir d;
  fs::create_directories(d / "recent.txt");  // a folder where the list goes: it can't be replaced
  EXPECT_EQ(studio::save_recent_studies(d.path(), {"/a"}),
            "the recent-studies list was not saved: " + d / "recent.txt" + ": is not a regular file; not replaced");
  EXPECT_EQ(studio::save_recent_studies("", {"/a"}, "no user cache: X"),
            "the recent-studies list was not saved: no user cache: X");
  fs::remove(d / "recent.txt");
  const std::vector<std::string> list = studio::with_recent_study({"/a", "/b"}, "/b");
  EXPECT_EQ(list, (std::vector<std::string>{"/b", "/a"}));
  EXPECT_EQ(studio::save_recent_studies(d.path(), list), "");
  EXPECT_EQ(studio::read_recent_studies(d.path()), list);
}

// A prediction file that is a FIFO: ipd table and ipd-studio keep one rule (LabelError::unusable_file), and
// both refuse the study naming the file, instead of the studio opening it with the file's rocks missing.
TEST(ReceivedStudy, APredictionFileThatIsAFifoStopsTheStudioAsItStopsIpdTable) {
  test::TempDir d;
  test::write_two_rock_study(d);
  const std::string fifo = d / "synth/predictions/det/s1.txt";
  fs::remove(fifo);
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  const std::string why = fifo + ": is a FIFO, expected a regular file";
  try {
    Session::open(d.path());
    ADD_FAILURE() << "opened";
  } catch (const StudyError& e) {
    EXPECT_EQ(std::string(e.what()), why + " (every rock of the file would count as missing)");
  }
  const test::CommandResult r = test::run_ipd_with_timeout("table " + d.path() + " --bootstrap 0", 60);
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_NE(r.err.find(why), std::string::npos) << r.err;
}

// A label file over the documented cap is refused unread, its size and the limit named: a sparse 1 GiB file
// costs no disk, and parsing it took 4 GB of memory.
TEST(ReceivedStudy, ALabelFileOverTheCapIsRefusedUnread) {
  test::TempDir d;
  test::write_two_rock_study(d);
  ASSERT_EQ(::truncate((d / "real/labels/s1.txt").c_str(), static_cast<off_t>(kMaxLabelFileBytes + 1)), 0);
  const LabelFile f = read_labels_beneath(d.path(), "real/labels/s1.txt", {LabelKind::kGroundTruth});
  ASSERT_EQ(f.errors.size(), 1u);
  EXPECT_TRUE(f.errors[0].unusable_file());
  EXPECT_EQ(f.errors[0].to_string(),
            d / "real/labels/s1.txt" + ": is 16.1 MB, larger than the 16 MB limit for this kind of file");
  EXPECT_TRUE(f.boxes.empty());
}

// A review file is parsed into a document that costs memory per value, far more than its bytes: 2 MB of zeros
// is a million numbers. Past the cap the file is refused by its count before the document grows further.
TEST(ReceivedStudy, AReviewFileOfOverAMillionValuesIsRefusedByItsCount) {
  test::TempDir d;
  test::write_two_rock_study(d);
  std::string zeros = "{\"reviewed\": [0";
  for (size_t k = 1; k <= kMaxHandWorkJsonValues; ++k) zeros += ",0";
  test::write_text(d / "review/real__synth.json", zeros + "]}\n");
  try {
    Session::open(d.path());
    ADD_FAILURE() << "opened";
  } catch (const StudyError& e) {
    const std::string why = std::string(e.what());
    EXPECT_EQ(why.rfind(d / "review/real__synth.json" +
                            ": holds more than 1000000 JSON values, the limit for this kind of file: expected ",
                        0),
              0u)
        << why;
  }
}

// The rule of docs/architecture.md: code under core/, ui/ and app/ reaches a study's files only through
// contained_file.h (descriptors opened beneath the study), never by name. Each call that opens, removes or
// renames by name is listed here with why its path is not a study's.
TEST(ReceivedStudy, NoCodeOpensOrRemovesAFileByNameOutsideTheListedPlaces) {
  const fs::path source = fs::path(IPD_TESTS_DIR).parent_path();
  const std::vector<std::string> by_name = {"std::ifstream",
                                            "std::ofstream",
                                            "cv::imread",
                                            "cv::imdecode",
                                            "cv::imencode",
                                            "cv::imwrite",
                                            "fs::remove(",
                                            "fs::remove_all(",
                                            "fs::rename(",
                                            "fs::copy_file(",
                                            "fs::create_hard_link(",
                                            "std::filesystem::remove",
                                            "std::filesystem::rename",
                                            "fopen("};
  const std::set<std::pair<std::string, std::string>> allowed = {
      // The codecs module decodes bytes already read through a descriptor and encodes into memory: the one
      // place OpenCV's codecs are called (picture_codec.h), so every program reads pictures as a study's files.
      {"core/picture/picture_codecs_module.cpp", "cv::imdecode"},
      {"core/picture/picture_codecs_module.cpp", "cv::imencode"},
      // run_unchecked_save_job: a save job without a study root is a path the user gave ('save as').
      {"core/session/session_edits.cpp", "fs::remove("},
      // The benchmarks' own scratch folders, made by mkdtemp.
      {"app/bench/bench_study.cpp", "fs::remove_all("},
      {"app/bench/registration_runs.cpp", "fs::remove_all("},
      // The variants study bench rank writes into its scratch folder, a variant moved out and back in.
      {"app/bench/bench_rank.cpp", "fs::remove_all("},
      {"app/bench/bench_rank.cpp", "fs::rename("},
  };
  std::vector<std::string> found;
  for (const char* top : {"core", "ui", "app"})
    for (const auto& e : fs::recursive_directory_iterator(source / top)) {
      const std::string ext = e.path().extension().string();
      if (ext != ".cpp" && ext != ".h") continue;
      const std::string rel = e.path().lexically_relative(source).string();
      const std::string text = read_file(e.path().string());
      size_t line_no = 0, pos = 0;
      while (pos < text.size()) {
        const size_t eol = std::min(text.find('\n', pos), text.size());
        const std::string line = text.substr(pos, eol - pos);
        ++line_no;
        pos = eol + 1;
        const size_t code = line.find_first_not_of(" \t");
        if (code == std::string::npos || line.compare(code, 2, "//") == 0) continue;
        for (const std::string& call : by_name) {
          if (line.find(call) == std::string::npos) continue;
          if (!allowed.count({rel, call})) found.push_back(rel + ":" + std::to_string(line_no) + ": " + call);
        }
      }
    }
  EXPECT_TRUE(found.empty()) << ::testing::PrintToString(found);
}

}  // namespace
}  // namespace ipd
