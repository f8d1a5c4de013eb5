// map[domain][model][stem] lookups that fall back instead of inserting: the study's predictions and the
// session's derived tables share this shape.
#pragma once

#include <map>
#include <string>

namespace ipd {

template <typename T>
using ByDomainModelStem = std::map<std::string, std::map<std::string, std::map<std::string, T>>>;

template <typename T>
const T& lookup(const ByDomainModelStem<T>& map, const std::string& domain, const std::string& model,
                const std::string& stem, const T& fallback) {
  const auto di = map.find(domain);
  if (di == map.end()) return fallback;
  const auto mi = di->second.find(model);
  if (mi == di->second.end()) return fallback;
  const auto si = mi->second.find(stem);
  return si == mi->second.end() ? fallback : si->second;
}

}  // namespace ipd
