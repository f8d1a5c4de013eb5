#include "app/studio/studio_replay.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <map>
#include <sstream>
#include <stdexcept>

#include "core/registration/registration.h"
#include "core/session/rock_pair_points.h"
#include "core/util/number_text.h"

namespace ipd::studio {

namespace {
// `gallery [page N] [sort KEY]`: each option once, in either order.
template <class Fail>
void check_gallery_options(const std::vector<std::string>& args, Fail fail) {
  bool page = false, sort = false;
  for (size_t k = 0; k + 1 < args.size(); k += 2) {
    const std::string& value = args[k + 1];
    long long n = 0;
    if (args[k] == "page" && !page) {
      page = true;
      if (!parse_integer(value, 1, std::numeric_limits<int>::max(), &n))
        fail("'gallery': expected a page number >= 1, got '" + quoted_for_message(value) + "'");
    } else if (args[k] == "sort" && !sort) {
      sort = true;
      GallerySort key = GallerySort::kDiff;
      if (!parse_gallery_sort(value, &key))
        fail("'gallery': expected a sort key (" + std::string(kGallerySortWords) + "), got '" +
             quoted_for_message(value) + "'");
    } else {
      fail("'gallery': expected 'page N' or 'sort KEY' (each once), got '" + quoted_for_message(args[k]) + "'");
    }
  }
}

// How many arguments a verb takes, and what they are (for the message when the count is wrong).
struct VerbArguments {
  int count;
  const char* what;
};

const std::map<std::string, VerbArguments>& replay_verbs() {
  static const std::map<std::string, VerbArguments> verbs = {
      {"wait", {1, "a frame count"}},
      {"conf", {1, "a threshold in [0, 1]"}},
      {"class", {1, "a class name, number or all"}},
      {"model", {1, "a model name"}},
      {"domains", {2, "two domain names"}},
      {"scene", {1, "next, prev or a scene name"}},
      {"pair", {2, "two rock numbers (left, right)"}},
      {"unpair", {1, "a left rock number"}},
      {"exclude", {1, "a left rock number"}},
      {"automatic", {0, "nothing"}},
      {"undo", {0, "nothing"}},
      {"redo", {0, "nothing"}},
      {"rerun", {1, "a registration method"}},
      {"export", {1, "[a figure kind] and an output file"}},
      {"screenshot", {1, "a PNG file"}},
      {"problems", {0, "nothing"}},
      {"problem", {1, "a row number of the Problems window"}},
      {"focus", {1, "on or off"}},
      {"rocks", {2, "two axis names (x, y)"}},
      {"select", {4, "a box's corners x0 y0 x1 y1 on the rock view's axes"}},
      {"list", {1, "a text file"}},
      {"gallery", {0, "[page N] [sort diff|perf-a|perf-b|size]"}},
      {"review", {0, "nothing"}},
      {"suspect", {0, "nothing"}},
      {"check", {2, "two rock numbers of a pair (left, right), or nothing for the selected pair"}},
      {"click", {1, "a left rock number"}},
      {"dialog", {1, "open, export, goto, help, search or saveas"}},
      {"type", {1, "the text to type"}},
      {"key", {1, "enter, escape or tab"}},
      {"blink", {1, "on, off, flip, overlay X (the right picture's opacity) or rate N (flips a second)"}},
      {"rank", {0, "nothing (opens the Rank window) or the setting to show on the right"}},
      {"state", {1, "a JSON file"}},
  };
  return verbs;
}

// `export KIND FILE`: the figure kinds the Export figure dialog makes.
bool is_figure_kind(const std::string& word) {
  static const std::vector<std::string> kinds = {"pairs",          "registration",     "table",
                                                 "compare",        "distribution",     "breakdown",
                                                 "breakdown-size", "breakdown-region", "breakdown-confidence",
                                                 "gallery"};
  return std::find(kinds.begin(), kinds.end(), word) != kinds.end();
}

// The action's verb is known and it has as many arguments as the verb takes (or one of the optional forms).
template <class Fail>
void check_verb_and_count(const ReplayAction& a, Fail fail) {
  const auto it = replay_verbs().find(a.verb);
  if (it == replay_verbs().end())
    fail("unknown action '" + a.verb +
         "' (expected wait, conf, model, domains, scene, pair, unpair, exclude, automatic, undo, "
         "redo, rerun, export, screenshot, problems, problem, focus, rocks, select, list, gallery, review, suspect, "
         "check, click, dialog, type, key, blink, rank or state)");
  const bool export_with_kind = a.verb == "export" && a.args.size() == 2;
  const bool gallery_options = a.verb == "gallery" && (a.args.size() == 2 || a.args.size() == 4);
  const bool check_selected = a.verb == "check" && a.args.empty();
  const bool typed_words = a.verb == "type" && !a.args.empty();  // typed with one space between them
  const bool blink_value = a.verb == "blink" && a.args.size() == 2;
  const bool rank_setting = a.verb == "rank" && a.args.size() == 1;
  if (static_cast<int>(a.args.size()) != it->second.count && !export_with_kind && !gallery_options && !check_selected &&
      !typed_words && !blink_value && !rank_setting)
    fail("'" + a.verb + "' takes " + it->second.what + ", got " + std::to_string(a.args.size()) + " argument(s)");
}

// The arguments' values: numbers, thresholds, names from a fixed set; the first wrong one fails.
template <class Fail>
void check_argument_values(const ReplayAction& a, Fail fail) {
  // The whole word is the number ("5\0" is not 5) and it fits the int the studio keeps it in.
  auto positive = [&](const std::string& w) {
    long long v = 0;
    if (!parse_integer(w, 1, std::numeric_limits<int>::max(), &v))
      fail("'" + a.verb + "': expected a number >= 1, got '" + quoted_for_message(w) + "'");
  };
  if (a.verb == "wait" || a.verb == "problem" || a.verb == "pair" || a.verb == "unpair" || a.verb == "exclude" ||
      a.verb == "check" || a.verb == "click")
    for (const auto& w : a.args) positive(w);
  static const std::vector<std::string> kDialogs = {"open", "export", "goto", "help", "search", "saveas"};
  if (a.verb == "dialog" && std::find(kDialogs.begin(), kDialogs.end(), a.args[0]) == kDialogs.end())
    fail("'dialog': expected open, export, goto, help, search or saveas, got '" + quoted_for_message(a.args[0]) + "'");
  if (a.verb == "key" && a.args[0] != "enter" && a.args[0] != "escape" && a.args[0] != "tab")
    fail("'key': expected enter, escape or tab, got '" + quoted_for_message(a.args[0]) + "'");
  // One domain against itself has no gap to measure: the studio would keep the domains it shows.
  if (a.verb == "domains" && a.args[0] == a.args[1])
    fail("'domains': expected two different domains, got '" + quoted_for_message(a.args[0]) + "' twice");
  if (a.verb == "focus" && a.args[0] != "on" && a.args[0] != "off")
    fail("'focus': expected on or off, got '" + quoted_for_message(a.args[0]) + "'");
  if (a.verb == "blink") {
    const std::string& w = a.args[0];
    const bool word = a.args.size() == 1 && (w == "on" || w == "off" || w == "flip");
    double v = NAN;
    const bool number = a.args.size() == 2 && parse_decimal(a.args[1], &v);
    if (!word && !(number && w == "overlay" && v >= 0 && v <= 1) && !(number && w == "rate" && v >= 0 && v <= 8))
      fail("'blink': expected on, off, flip, overlay X (X in [0, 1]) or rate N (N in [0, 8] flips a second), got '" +
           quoted_for_message(w) + (a.args.size() == 2 ? " " + quoted_for_message(a.args[1]) : std::string()) + "'");
  }
  if (a.verb == "conf") {
    double v = NAN;
    if (!parse_decimal(a.args[0], &v) || !(v >= 0 && v <= 1))
      fail("'conf': expected a threshold in [0, 1], got '" + quoted_for_message(a.args[0]) + "'");
  }
  PairAxis axis;
  if (a.verb == "rocks")
    for (const auto& w : a.args)
      if (!parse_pair_axis(w, &axis))
        fail("'rocks': expected an axis (" + std::string(kPairAxisWords) + "), got '" + quoted_for_message(w) + "'");
  if (a.verb == "select")
    for (const auto& w : a.args) {
      double v = NAN;
      if (!parse_decimal(w, &v)) fail("'select': expected a number, got '" + quoted_for_message(w) + "'");
    }
  if (a.verb == "gallery") check_gallery_options(a.args, fail);
  RegistrationMethod method;
  if (a.verb == "rerun" && !parse_method(a.args[0], &method))
    fail("'rerun': expected " + method_choices() + ", got '" + a.args[0] + "'");
  const bool export_with_kind = a.verb == "export" && a.args.size() == 2;
  if (export_with_kind && !is_figure_kind(a.args[0]))
    fail(
        "'export': expected a figure kind (pairs, registration, table, compare, distribution, breakdown, "
        "breakdown-size, breakdown-region, breakdown-confidence or gallery), got '" +
        a.args[0] + "'");
}

}  // namespace

std::vector<ReplayAction> parse_replay(const std::string& text, const std::string& file) {
  std::vector<ReplayAction> out;
  std::istringstream in(text);
  int n = 0;
  for (std::string line; std::getline(in, line);) {
    ++n;
    if (const size_t hash = line.find('#'); hash != std::string::npos) line.resize(hash);
    std::istringstream words(line);
    ReplayAction a;
    a.line = n;
    if (!(words >> a.verb)) continue;
    for (std::string w; words >> w;) a.args.push_back(w);
    auto fail = [&](const std::string& why) { throw std::runtime_error(file + ":" + std::to_string(n) + ": " + why); };
    check_verb_and_count(a, fail);
    check_argument_values(a, fail);
    out.push_back(std::move(a));
  }
  return out;
}

}  // namespace ipd::studio
