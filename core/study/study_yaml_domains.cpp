#include "core/study/study_yaml_domains.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "core/util/number_text.h"

namespace ipd {

namespace {

std::string node_kind(const YAML::Node& n) {
  if (n.IsNull()) return "nothing";
  if (n.IsSequence()) return "a list";
  if (n.IsMap()) return "a mapping";
  return "'" + quoted_for_message(n.Scalar()) + "'";
}

// Twice is a typo (the second was meant to be another domain), not an order: said, never dropped.
void add_domain(const std::string& name, const std::string& file, int line, StudyConfig* c) {
  if (std::find(c->domain_order.begin(), c->domain_order.end(), name) != c->domain_order.end())
    throw StudyError(fmt::format("{}:{}: domains lists '{}' twice; each domain once, in the order to show", file, line,
                                 quoted_for_message(name)));
  c->domain_order.push_back(name);
}

// `params: {w: 0.30, b: 0.2}`: names to finite numbers, in the file's order. A sweep plots IPD against them, so
// a value that is not a number (a word, a list, "nan", ".inf") is refused where it is written.
std::vector<std::pair<std::string, double>> parse_params(const YAML::Node& params, const std::string& file,
                                                         const std::string& domain) {
  if (!params.IsMap())
    throw StudyError(
        fmt::format("{}:{}: domains.{}.params must be a mapping of parameter names to numbers (e.g. "
                    "{{w: 0.30, b: 0.2}}), got {}",
                    file, params.Mark().line + 1, quoted_for_message(domain), node_kind(params)));
  std::vector<std::pair<std::string, double>> out;
  for (const auto& kv : params) {
    const int line = kv.first.Mark().line + 1;
    if (!kv.first.IsScalar())
      throw StudyError(fmt::format("{}:{}: domains.{}.params: expected a parameter name, found {}", file, line,
                                   quoted_for_message(domain), node_kind(kv.first)));
    const std::string name = kv.first.Scalar();
    double value = 0;
    const bool number = kv.second.IsScalar() && parse_decimal(kv.second.Scalar(), &value) && std::isfinite(value);
    if (!number)
      throw StudyError(fmt::format("{}:{}: domains.{}.params.{} must be a number, got {}", file,
                                   kv.second.Mark().line + 1, quoted_for_message(domain), quoted_for_message(name),
                                   node_kind(kv.second)));
    if (std::any_of(out.begin(), out.end(), [&](const auto& p) { return p.first == name; }))
      throw StudyError(fmt::format("{}:{}: domains.{}.params gives '{}' twice", file, line, quoted_for_message(domain),
                                   quoted_for_message(name)));
    out.emplace_back(name, value);
  }
  return out;
}

}  // namespace

void parse_study_domains(const YAML::Node& v, const std::string& file, int line, StudyConfig* c) {
  if (v.IsSequence()) {
    for (const auto& d : v) {
      if (!d.IsScalar()) throw StudyError(fmt::format("{}:{}: domains has the wrong type", file, d.Mark().line + 1));
      add_domain(d.Scalar(), file, line, c);
    }
    return;
  }
  if (!v.IsMap())
    throw StudyError(
        fmt::format("{}:{}: domains must be a list of domain names or a mapping of domain names to "
                    "settings ({{params: {{...}}}}), got {}",
                    file, line, node_kind(v)));
  for (const auto& kv : v) {
    const int at = kv.first.Mark().line + 1;
    if (!kv.first.IsScalar())
      throw StudyError(fmt::format("{}:{}: domains: expected a domain name, found {}", file, at, node_kind(kv.first)));
    const std::string name = kv.first.Scalar();
    add_domain(name, file, at, c);
    const YAML::Node& settings = kv.second;
    if (settings.IsNull()) continue;  // `real:` or `real: {}`: a domain without parameters
    if (!settings.IsMap())
      throw StudyError(fmt::format("{}:{}: domains.{} must be a mapping of settings (params), got {}", file, at,
                                   quoted_for_message(name), node_kind(settings)));
    for (const auto& s : settings) {
      const std::string key = s.first.IsScalar() ? s.first.Scalar() : std::string("(a list or mapping)");
      if (key != "params")
        throw StudyError(fmt::format("{}:{}: unknown setting 'domains.{}.{}' (expected params)", file,
                                     s.first.Mark().line + 1, quoted_for_message(name), quoted_for_message(key)));
      c->domain_params[name] = parse_params(s.second, file, name);
    }
  }
}

}  // namespace ipd
