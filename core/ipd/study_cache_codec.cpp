#include "core/ipd/study_cache_codec.h"

#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <new>

#include <algorithm>
#include <array>
#include <cmath>

namespace ipd::cache_codec {

void FileBytes::release() {
  if (mapped_)
    ::munmap(data_, capacity_);
  else
    delete[] data_;
  data_ = nullptr, capacity_ = 0, size = 0, mapped_ = false;
}

bool FileBytes::allocate(size_t n) {
  constexpr size_t kHuge = size_t{2} << 20;
  if (n >= 4 * kHuge) {
    const size_t rounded = (n + kHuge - 1) / kHuge * kHuge;
    void* p = ::mmap(nullptr, rounded, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
    if (p != MAP_FAILED) {
      ::madvise(p, rounded, MADV_HUGEPAGE);  // a hint: without it the pages are small, nothing else changes
      data_ = static_cast<char*>(p), capacity_ = rounded, mapped_ = true;
      return true;
    }
  }
  data_ = new (std::nothrow) char[n];
  capacity_ = n;
  return data_ != nullptr;
}

bool read_whole_file(int fd, const std::function<void(const char*)>& hook, FileBytes* file) {
  struct stat st {};
  if (::fstat(fd, &st) != 0) {
    ::close(fd);
    return false;
  }
  if (hook) hook("opened");
  const size_t want = static_cast<size_t>(st.st_size);
  if (!file->allocate(want > 0 ? want : 1)) {
    ::close(fd);
    return false;
  }
  size_t done = 0;
  bool read_error = false;
  while (done < want) {
    const ssize_t n = ::read(fd, file->data() + done, want - done);
    if (n < 0 && errno == EINTR) continue;
    read_error = n < 0;
    if (n <= 0) break;
    done += static_cast<size_t>(n);
  }
  ::close(fd);
  file->size = done;
  return !read_error;
}

void write_label_file(Writer& w, const LabelFile& f) {
  w.pod<std::uint8_t>(f.exists);
  // Field by field: Box has padding, whose bytes would make the file differ from run to run.
  w.pod<std::uint64_t>(f.boxes.size());
  for (const Box& b : f.boxes) {
    const double v[5] = {b.cx, b.cy, b.w, b.h, b.conf};
    w.pod<std::int32_t>(b.cls);
    w.pod(v);
    const Outline* o = b.outline.get();
    w.pod<std::uint32_t>(o ? static_cast<std::uint32_t>(o->points.size()) : 0);
    if (!o) continue;
    for (const Eigen::Vector2d& p : o->points) w.pod<std::array<double, 2>>({p.x(), p.y()});
    w.pod<std::array<double, 7>>({o->area, o->centroid.x(), o->centroid.y(), o->x0, o->y0, o->x1, o->y1});
  }
  w.vec(f.line_of_box);
  w.pod<std::uint32_t>(static_cast<std::uint32_t>(f.errors.size()));
  for (const auto& e : f.errors) {
    w.str(e.file);
    w.pod<std::int32_t>(e.line);
    w.str(e.message);
    w.pod<std::int32_t>(e.more);
  }
}

LabelFile read_label_file(Reader& r, const std::string& path) {
  LabelFile f;
  f.path = path;
  f.exists = r.pod<std::uint8_t>() != 0;
  const auto boxes = r.pod<std::uint64_t>();
  if (boxes > kMaxBoxesPerFile) throw std::runtime_error("too many boxes");
  f.boxes.resize(boxes);
  for (Box& b : f.boxes) {
    b.cls = r.pod<std::int32_t>();
    const auto v = r.pod<std::array<double, 5>>();
    b.cx = v[0], b.cy = v[1], b.w = v[2], b.h = v[3], b.conf = v[4];
    const auto points = r.pod<std::uint32_t>();
    if (points == 0) continue;
    if (points < 3 || points > kMaxOutlinePoints) throw std::runtime_error("bad outline");
    OutlineRef ref = OutlineRef::make();
    Outline* o = ref.fill();
    o->points.resize(points);
    for (Eigen::Vector2d& p : o->points) {
      const auto xy = r.pod<std::array<double, 2>>();
      p = {xy[0], xy[1]};
    }
    const auto m = r.pod<std::array<double, 7>>();
    o->area = m[0], o->centroid = {m[1], m[2]}, o->x0 = m[3], o->y0 = m[4], o->x1 = m[5], o->y1 = m[6];
    if (!(o->area > 0)) throw std::runtime_error("bad outline area");
    b.outline = std::move(ref);
  }
  f.line_of_box = r.vec<int>();
  if (f.line_of_box.size() != f.boxes.size()) throw std::runtime_error("box and line counts differ");
  const auto errors = r.pod<std::uint32_t>();
  for (std::uint32_t k = 0; k < errors; ++k) {
    LabelError e;
    e.file = r.str();
    e.line = r.pod<std::int32_t>();
    e.message = r.str();
    e.more = r.pod<std::int32_t>();
    f.errors.push_back(std::move(e));
  }
  return f;
}

void write_report(Writer& w, const RegistrationReport& r) {
  w.pod<std::int32_t>(static_cast<int>(r.method));
  for (int k = 0; k < 6; ++k) w.pod<double>(r.affine(k / 3, k % 3));
  w.pod<std::uint64_t>(r.pairs.size());
  for (const auto& [i, j] : r.pairs) w.pod<std::int32_t>(i), w.pod<std::int32_t>(j);
  w.pod<std::int32_t>(r.samples);
  w.pod<std::int32_t>(r.em_iterations);
  w.pod<std::int32_t>(r.hypotheses);
  w.pod<std::int32_t>(r.inliers);
  w.pod<std::uint8_t>(static_cast<std::uint8_t>(r.fit.measure));
  w.pod<double>(std::isfinite(r.fit.value) ? r.fit.value : 0.0);
  w.pod<std::int32_t>(static_cast<int>(r.stop));
  w.str(r.note);
  w.pod<double>(r.elapsed_ms);
  w.pod<double>(std::isfinite(r.confidence) ? r.confidence : 0.0);
  w.pod<std::uint8_t>(static_cast<std::uint8_t>(r.ambiguity));
}

RegistrationReport read_report(Reader& rd) {
  RegistrationReport r;
  const int method = rd.pod<std::int32_t>();
  if (method < 0 || method > static_cast<int>(RegistrationMethod::kCpd)) throw std::runtime_error("bad method");
  r.method = static_cast<RegistrationMethod>(method);
  for (int k = 0; k < 6; ++k) {
    r.affine(k / 3, k % 3) = rd.pod<double>();
    if (!std::isfinite(r.affine(k / 3, k % 3))) throw std::runtime_error("bad affine");
  }
  const auto pairs = rd.pod<std::uint64_t>();
  r.pairs.reserve(static_cast<size_t>(std::min<std::uint64_t>(pairs, kMaxBoxesPerFile)));
  for (std::uint64_t k = 0; k < pairs; ++k) {
    const int i = rd.pod<std::int32_t>();
    r.pairs.emplace_back(i, rd.pod<std::int32_t>());
  }
  r.samples = rd.pod<std::int32_t>();
  r.em_iterations = rd.pod<std::int32_t>();
  r.hypotheses = rd.pod<std::int32_t>();
  r.inliers = rd.pod<std::int32_t>();
  const int measure = rd.pod<std::uint8_t>();
  if (measure > static_cast<int>(FitMeasure::kMixtureWidth)) throw std::runtime_error("bad fit measure");
  r.fit = {static_cast<FitMeasure>(measure), rd.pod<double>()};
  const int stop = rd.pod<std::int32_t>();
  if (stop < 0 || stop > static_cast<int>(kLastStopReason)) throw std::runtime_error("bad stop reason");
  r.stop = static_cast<StopReason>(stop);
  r.note = rd.str();
  r.elapsed_ms = rd.pod<double>();
  r.confidence = rd.pod<double>();
  const int ambiguity = rd.pod<std::uint8_t>();
  if (ambiguity >= kAmbiguityCount) throw std::runtime_error("bad ambiguity");
  r.ambiguity = static_cast<Ambiguity>(ambiguity);
  r.ambiguous = r.ambiguity != Ambiguity::kNone;
  return r;
}

void write_stamp(Writer& w, const FileStamp& s) {
  w.pod(s.size);
  w.pod(s.mtime_ns);
  w.pod(s.ctime_ns);
  w.pod(s.inode);
  w.pod<std::uint8_t>(s.exists);
}

FileStamp read_stamp(Reader& r) {
  FileStamp s;
  s.size = r.pod<std::int64_t>();
  s.mtime_ns = r.pod<std::int64_t>();
  s.ctime_ns = r.pod<std::int64_t>();
  s.inode = r.pod<std::uint64_t>();
  s.exists = r.pod<std::uint8_t>() != 0;
  return s;
}

}  // namespace ipd::cache_codec
