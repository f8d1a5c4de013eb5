#include "core/ipd/label_fingerprint.h"

#include <algorithm>
#include <memory>
#include <optional>
#include <utility>

#include "core/util/contained_file.h"
#include "core/util/sha256.h"

namespace ipd {

std::string label_set_fingerprint(const Study& study) { return label_set_fingerprint(study, {}, {}).fingerprint; }

ResumedFingerprint label_set_fingerprint(const Study& study, const std::vector<FingerprintCheckpoint>& previous,
                                         const std::function<bool(const std::string& domain)>& unchanged) {
  // Paths sort by domain first, then file name: "<domain>/" orders the blocks and "<stem>.txt" the files in one
  // ('-' sorts before '/' and '.', so "a-b/" comes before "a/" and "a-b.txt" before "a.txt").
  std::vector<const Domain*> domains;
  for (const Domain& d : study.domains) domains.push_back(&d);
  std::sort(domains.begin(), domains.end(),
            [](const Domain* a, const Domain* b) { return a->name + '/' < b->name + '/'; });
  ResumedFingerprint out;
  // The leading domains that read as when `previous` was taken.
  size_t kept = 0;
  while (kept < domains.size() && kept < previous.size() && previous[kept].domain == domains[kept]->name &&
         previous[kept].files == domains[kept]->stems.size() && unchanged && unchanged(domains[kept]->name))
    ++kept;
  std::optional<Sha256> sha;
  while (kept > 0 && !(sha = Sha256::resume(previous[kept - 1].state))) --kept;
  if (!sha) sha.emplace();
  out.checkpoints.assign(previous.begin(), previous.begin() + static_cast<std::ptrdiff_t>(kept));
  for (size_t k = kept; k < domains.size(); ++k) {
    const Domain& d = *domains[k];
    std::vector<std::string> names;
    for (const std::string& stem : d.stems) names.push_back(stem + ".txt");
    std::sort(names.begin(), names.end());
    std::unique_ptr<OpenFolder> folder;
    for (const std::string& name : names) {
      if (!folder) folder = std::make_unique<OpenFolder>(study.root, d.name + "/labels");
      const std::optional<std::string> text = folder->read(name);
      if (!text) continue;  // a scene with a picture and no label file
      const std::string rel = d.name + "/labels/" + name;
      sha->add(rel + std::string(1, '\0') + std::to_string(text->size()) + std::string(1, '\0'));
      sha->add(*text);
    }
    out.checkpoints.push_back({d.name, d.stems.size(), sha->state()});
    ++out.domains_read;
  }
  out.fingerprint = sha->hex().substr(0, 12);
  return out;
}

}  // namespace ipd
