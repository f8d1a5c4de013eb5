// The parsed-study file's bytes (study_cache.h): the file read whole (FileBytes), a writer and a bounds-checked reader,
// and how a label file, a registration report and a file's stamp are written and read back. A read past the end or a
// value out of range throws std::runtime_error: the file is then ignored and rebuilt, never trusted in part.
#pragma once

#include <cstdint>
#include <cstring>
#include <functional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

#include "core/io/label_io.h"
#include "core/ipd/study_cache.h"
#include "core/registration/registration.h"

namespace ipd::cache_codec {

class Writer {
 public:
  std::string out;
  template <typename T>
  void pod(const T& v) {
    static_assert(std::is_trivially_copyable_v<T>);
    out.append(reinterpret_cast<const char*>(&v), sizeof v);
  }
  // Room for a u32 written later (patch_u32): the size of what follows, once it is written.
  size_t reserve_u32() {
    out.append(4, '\0');
    return out.size() - 4;
  }
  void patch_u32(size_t at, std::uint32_t v) { std::memcpy(&out[at], &v, sizeof v); }
  void str(const std::string& s) {
    pod<std::uint32_t>(static_cast<std::uint32_t>(s.size()));
    out.append(s);
  }
  template <typename T>
  void vec(const std::vector<T>& v) {
    static_assert(std::is_trivially_copyable_v<T>);
    pod<std::uint64_t>(v.size());
    if (!v.empty()) out.append(reinterpret_cast<const char*>(v.data()), v.size() * sizeof(T));
  }
};

// Reads what Writer wrote; any read past the end throws (a truncated or corrupt file).
class Reader {
 public:
  Reader(const char* p, size_t n) : p_(p), end_(p + n) {}
  explicit Reader(std::string_view bytes) : Reader(bytes.data(), bytes.size()) {}
  template <typename T>
  T pod() {
    T v;
    need(sizeof v);
    std::memcpy(&v, p_, sizeof v);
    p_ += sizeof v;
    return v;
  }
  std::string str() {
    const auto n = pod<std::uint32_t>();
    need(n);
    std::string s(p_, n);
    p_ += n;
    return s;
  }
  // The next string where it lies in the bytes (valid while they are).
  std::string_view view() {
    const auto n = pod<std::uint32_t>();
    need(n);
    const std::string_view s(p_, n);
    p_ += n;
    return s;
  }
  // The next n bytes where they lie.
  std::string_view bytes(size_t n) {
    need(n);
    const std::string_view s(p_, n);
    p_ += n;
    return s;
  }
  template <typename T>
  std::vector<T> vec() {
    const auto n = pod<std::uint64_t>();
    if (n > static_cast<std::uint64_t>(end_ - p_) / sizeof(T)) throw std::runtime_error("truncated");
    std::vector<T> v(n);
    if (n) std::memcpy(v.data(), p_, n * sizeof(T));  // an empty vector's data() may be null: UB for memcpy
    p_ += n * sizeof(T);
    return v;
  }
  bool at_end() const { return p_ == end_; }
  std::string_view rest() const { return {p_, static_cast<size_t>(end_ - p_)}; }

 private:
  void need(size_t n) const {
    if (n > static_cast<size_t>(end_ - p_)) throw std::runtime_error("truncated");
  }
  const char* p_;
  const char* end_;
};

// A file's bytes, not zero-filled first: the parsed-study cache of a 10,000-scene study is tens of megabytes read
// on every warm run. Large buffers are mapped memory asking for huge pages: read() into fresh 4 KiB pages
// costs a page fault each (45,000 for 180 MB), a visible part of a warm run.
class FileBytes {
 public:
  FileBytes() = default;
  FileBytes(const FileBytes&) = delete;
  FileBytes& operator=(const FileBytes&) = delete;
  ~FileBytes() { release(); }
  void release();
  // Room for n bytes (n > 0); false when no memory could be had.
  bool allocate(size_t n);
  char* data() { return data_; }
  size_t size = 0;

 private:
  char* data_ = nullptr;
  size_t capacity_ = 0;
  bool mapped_ = false;
};

// Reads the open file `fd` whole and closes it; false when it can't be read. Read, not mapped: a file shortened
// meanwhile reads short (and is then "truncated"), never a crash. `hook` step: "opened" (before it is read).
bool read_whole_file(int fd, const std::function<void(const char*)>& hook, FileBytes* file);

void write_label_file(Writer& w, const LabelFile& f);
LabelFile read_label_file(Reader& r, const std::string& path);
// The fields the registration entry files keep (registration_cache.cpp), nothing more.
void write_report(Writer& w, const RegistrationReport& r);
RegistrationReport read_report(Reader& rd);
void write_stamp(Writer& w, const FileStamp& s);
FileStamp read_stamp(Reader& r);

}  // namespace ipd::cache_codec
