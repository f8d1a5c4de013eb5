#include "core/util/study_inputs.h"

#include <fmt/format.h>

#include <filesystem>
#include <optional>
#include <vector>

#include "core/util/contained_file.h"

namespace fs = std::filesystem;

namespace ipd {

namespace {

// What the study file at `relative` (below the study, lexical) is, or nullopt when it is not an input.
std::optional<std::string> input_kind(const std::string& relative) {
  std::vector<std::string> parts;
  for (const auto& p : fs::path(relative)) parts.push_back(p.string());
  if (parts.empty()) return std::nullopt;
  const std::string& top = parts[0];
  if (parts.size() == 1 && top == "study.yaml") return std::string("the study's settings");
  if (top == "pairs") return std::string("the hand pairs, pairs/");
  if (top == "review") return std::string("the review marks, review/");
  if (top == ".ipd-cache") return std::string("the study's caches, .ipd-cache/");
  if (parts.size() < 2) return std::nullopt;
  const std::string& sub = parts[1];
  if (sub == "labels") return fmt::format("the ground-truth labels of domain '{}', {}/labels/", top, top);
  if (sub == "images") return fmt::format("the pictures of domain '{}', {}/images/", top, top);
  if (sub == "predictions") return fmt::format("the predictions of domain '{}', {}/predictions/", top, top);
  return std::nullopt;
}

}  // namespace

std::string study_input_problem(const std::string& root, const std::string& path) {
  std::optional<std::string> kind;
  if (const auto rel = path_below(root, path)) kind = input_kind(*rel);
  if (!kind) {
    // The user's own link outside the study (`~/out -> STUDY/real/labels`) would be followed by the write.
    std::error_code ec;
    const fs::path resolved = fs::weakly_canonical(path, ec);
    if (!ec)
      if (const auto rel = path_below(root, resolved.string())) kind = input_kind(*rel);
  }
  if (!kind) return {};
  return fmt::format(
      "{}: is one of the study's inputs ({}); an output written there would replace it, so nothing is written. "
      "Outputs go outside study.yaml, pairs/, review/, .ipd-cache/ and each domain's labels/, images/ and "
      "predictions/ (e.g. into STUDY/figures/)",
      path, *kind);
}

}  // namespace ipd
