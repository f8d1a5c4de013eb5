// Names a study declares that become parts of file names: domains (STUDY/pairs/<A>__<B>/, figure file names),
// models (predictions/<model>/, export file names) and scene stems (pairs/<A>__<B>/<stem>.json). A study is
// untrusted input, so each is checked when the study is opened: a name with a path separator or `..` would
// lead a write out of its folder, a control character would corrupt keys and messages, and one too long for
// the file system would fail later with a bare ENAMETOOLONG.
#pragma once

#include <cstddef>
#include <string>

namespace ipd {

// Longest names that still fit one file-name component (255 bytes on Linux file systems) where they are
// joined: "<A>__<B>" for two domains, "<stem>.json" for a scene.
constexpr size_t kMaxDomainNameBytes = 120;
constexpr size_t kMaxModelNameBytes = 120;
constexpr size_t kMaxStemBytes = 250;

// Why `name` can't be part of a file name ("contains a path separator '/'", ...), or "" when it can.
std::string file_name_problem(const std::string& name, size_t max_bytes);

// `name` with control characters shown as \xNN, for messages.
std::string printable_name(const std::string& name, size_t max_bytes = std::string::npos);

}  // namespace ipd
