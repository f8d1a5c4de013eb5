#include "core/report/provenance.h"

#include <fmt/format.h>
#include <openssl/evp.h>

#include <algorithm>
#include <memory>
#include <optional>
#include <stdexcept>

#include "core/util/contained_file.h"

namespace ipd {

namespace {

class Sha256 {
 public:
  Sha256() : ctx_(EVP_MD_CTX_new(), EVP_MD_CTX_free) {
    if (!ctx_ || !EVP_DigestInit_ex(ctx_.get(), EVP_sha256(), nullptr))
      throw std::runtime_error("SHA-256 is not available from OpenSSL");
  }
  void add(const std::string& bytes) {
    if (!EVP_DigestUpdate(ctx_.get(), bytes.data(), bytes.size())) throw std::runtime_error("SHA-256 failed");
  }
  std::string hex() {
    unsigned char out[EVP_MAX_MD_SIZE];
    unsigned int len = 0;
    if (!EVP_DigestFinal_ex(ctx_.get(), out, &len)) throw std::runtime_error("SHA-256 failed");
    std::string s;
    for (unsigned int i = 0; i < len; ++i) s += fmt::format("{:02x}", out[i]);
    return s;
  }

 private:
  std::unique_ptr<EVP_MD_CTX, void (*)(EVP_MD_CTX*)> ctx_;
};

std::string plural(int n, const char* one, const char* many) { return fmt::format("{} {}", n, n == 1 ? one : many); }

}  // namespace

std::string label_set_fingerprint(const Study& study) {
  // Paths sort by domain first, then stem: the study's domains and stems are read in any order, so sort here.
  std::vector<std::string> files;
  for (const Domain& d : study.domains)
    for (const std::string& stem : d.stems) files.push_back(d.name + "/labels/" + stem + ".txt");
  std::sort(files.begin(), files.end());
  Sha256 sha;
  for (const std::string& rel : files) {
    const std::optional<std::string> text = read_file_beneath(study.root, rel);
    if (!text) continue;  // a scene with a picture and no label file
    sha.add(rel + std::string(1, '\0') + std::to_string(text->size()) + std::string(1, '\0'));
    sha.add(*text);
  }
  return sha.hex().substr(0, 12);
}

Provenance table_provenance(const CrossTable& table, const Study& study) {
  Provenance p;
  for (size_t c = 0; c < table.pairings.size() && c < table.columns.size(); ++c)
    for (const ScenePairing& s : table.pairings[c]) {
      if (!s.fixed) continue;
      ++p.scenes_with_hand_pairs;
      p.pairs_set_by_hand += static_cast<int>(s.pairs.size());
      p.rocks_excluded += static_cast<int>(s.excluded_a.size() + s.excluded_b.size());
      p.edited_scenes.push_back({table.columns[c].first, table.columns[c].second, s.stem});
    }
  p.label_fingerprint = label_set_fingerprint(study);
  return p;
}

std::string provenance_note(const Provenance& p) {
  if (p.scenes_with_hand_pairs == 0)
    return fmt::format("Label files {}; no hand pairs (every pair from registration).", p.label_fingerprint);
  return fmt::format("Label files {}; hand pairs in {} ({} set by hand, {} excluded).", p.label_fingerprint,
                     plural(p.scenes_with_hand_pairs, "scene", "scenes"), plural(p.pairs_set_by_hand, "pair", "pairs"),
                     plural(p.rocks_excluded, "rock", "rocks"));
}

}  // namespace ipd
