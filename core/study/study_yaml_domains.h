// study.yaml's `domains:` setting, in either form: a list giving the order (`domains: [real, principled]`), or a
// mapping in that order whose values may attach numbers to a domain, e.g. a renderer setting's parameters
// (`domains: {real: {}, hapke-w030: {params: {w: 0.30, b: 0.2}}}`). Internal to core/study (yaml-cpp types).
#pragma once

#include <yaml-cpp/yaml.h>

#include <string>

#include "core/study/study.h"

namespace ipd {

// Fills c->domain_order and c->domain_params from the `domains` node; throws StudyError naming FILE:LINE for a
// domain listed twice, a parameter value that is not a number, or any other setting than `params`.
void parse_study_domains(const YAML::Node& v, const std::string& file, int line, StudyConfig* c);

}  // namespace ipd
