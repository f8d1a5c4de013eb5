// The fingerprint of a study's label set that every table, figure and export prints (provenance.h).
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "core/study/study.h"

namespace ipd {

// The first 12 hex digits of SHA-256 over every GT label file of the study, in sorted order of its path
// below the study ("<domain>/labels/<stem>.txt"): each file contributes its path, a 0 byte, its size in
// decimal, a 0 byte and its bytes, so renaming, moving or editing any label file changes it. Predictions,
// pictures, study.yaml and pairs files are not covered (the hand-pair counts speak for the pairs). Each domain's
// labels/ is opened once beneath the study and its files read through it, never through a link. Throws IoError
// naming the file for a symbolic link or an unreadable file.
std::string label_set_fingerprint(const Study& study);

// In that path order each domain's files come as one block (a domain's name has no '/'). The hash's running
// state after a domain's block lets a study that gained a domain, or changed one, read only the blocks from the
// first changed one on.
struct FingerprintCheckpoint {
  std::string domain;
  std::uint64_t files = 0;  // the domain's GT files when it was hashed
  std::string state;        // Sha256::state() after its block
};
struct ResumedFingerprint {
  std::string fingerprint;                         // label_set_fingerprint(study)
  std::vector<FingerprintCheckpoint> checkpoints;  // one a domain, in path order
  int domains_read = 0;                            // domains whose files were read; the others were resumed
};
// label_set_fingerprint(study), resumed after the longest run of leading domains (in path order) that `previous`
// holds in the same order, each with as many files as now and vouched for by `unchanged(domain)`: every one of its
// GT files is, byte for byte, the one hashed when `previous` was taken (the parsed-study cache knows it by the
// files' stamps). Throws as label_set_fingerprint.
ResumedFingerprint label_set_fingerprint(const Study& study, const std::vector<FingerprintCheckpoint>& previous,
                                         const std::function<bool(const std::string& domain)>& unchanged);

}  // namespace ipd
