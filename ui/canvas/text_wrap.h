// Breaking text into lines for the studio's panels and the paper figures alike: one rule, so a number and what
// belongs to it read the same on screen and on paper. GL- and ImGui-free: the caller measures.
#pragma once

#include <functional>
#include <string>
#include <vector>

namespace ipd::ui {

// `text` broken into lines no wider than `width` (as `measure` says), at spaces only: a word, number
// included, is never split, nor a label from its number ("p = 0.031"), a count from the word it counts
// ("8 scenes"), a number from its unit ("0.3 px") or "scene IPD" from its value ("scene IPD 0.0404"), nor "delta IPD"
// (ΔIPD in ASCII); a word (or such a group) wider than `width` gets a line of its own. Newlines are kept.
std::vector<std::string> wrap_at_spaces(const std::string& text, float width,
                                        const std::function<float(const std::string&)>& measure);

}  // namespace ipd::ui
