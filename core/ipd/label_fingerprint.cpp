#include "core/ipd/label_fingerprint.h"

#include <algorithm>
#include <map>
#include <memory>
#include <optional>
#include <utility>
#include <vector>

#include "core/util/contained_file.h"
#include "core/util/sha256.h"

namespace ipd {

std::string label_set_fingerprint(const Study& study) {
  // Paths sort by domain first, then stem: the study's domains and stems are read in any order, so sort here.
  std::vector<std::pair<std::string, std::string>> files;  // (path below the study, domain)
  for (const Domain& d : study.domains)
    for (const std::string& stem : d.stems) files.emplace_back(d.name + "/labels/" + stem + ".txt", d.name);
  std::sort(files.begin(), files.end());
  std::map<std::string, std::unique_ptr<OpenFolder>> folders;  // domain -> its labels/, opened once
  Sha256 sha;
  for (const auto& [rel, domain] : files) {
    auto& folder = folders[domain];
    if (!folder) folder = std::make_unique<OpenFolder>(study.root, domain + "/labels");
    const std::optional<std::string> text = folder->read(rel.substr(domain.size() + 8));  // after "<domain>/labels/"
    if (!text) continue;  // a scene with a picture and no label file
    sha.add(rel + std::string(1, '\0') + std::to_string(text->size()) + std::string(1, '\0'));
    sha.add(*text);
  }
  return sha.hex().substr(0, 12);
}

}  // namespace ipd
