// ipd-studio --replay FILE: scripted sessions, one action per line, one action per frame (the next one waits
// until the worker has applied the previous). Rock numbers are 1-based, left side first.
//   wait N | conf X | model NAME | domains A B | scene next|prev|STEM | pair I J | unpair I | exclude I
//   undo | redo | rerun paper|consensus|cpd | export [KIND] FILE | screenshot FILE   (# starts a comment)
//   problems | problem N | rocks X Y | select X0 Y0 X1 Y1 | list FILE | gallery [page N] [sort KEY]
//   suspect | check [I J] | review | click I | dialog open|export|goto|help|search|saveas | type TEXT
//   key enter|escape|tab
// rocks: the rock view open on axes X, Y (perf-a, perf-b, diff, size, x, y, conf-a, conf-b); select: a drag box
// in the axes' units, as the mouse draws it; list: the scene list (its selection chip's label, then one scene
// per line) written to FILE; gallery: the Rock pairs window on its gallery tab, at page N (1-based), sorted by
// KEY (diff, perf-left, perf-right, size; largest first). suspect: `N`, the next suspect pair (selected); check:
// the pair I J (or the selected one) checked as correct, again: unchecked (`C`); review: the scene in view
// reviewed, again: not (`R`). click: the left rock I selected, as a click on it. dialog: open, export, goto and
// help open that dialog as its menu item does; search and saveas give the keyboard to the scene list's filter or
// the 'save as' field. type: each character a key pressed and released on its own frame, as a keyboard sends it
// (the key, then its character), to whatever holds the keyboard; key: Enter, Esc or Tab, the same way.
// KIND: pairs (the default), registration, table, compare, distribution, breakdown[-size|-region|-confidence]
// (the Export figure dialog's defaults for that kind and the current view).
#pragma once

#include <string>
#include <vector>

namespace ipd::studio {

struct ReplayAction {
  std::string verb;
  std::vector<std::string> args;
  int line = 0;
};

// Throws std::runtime_error "FILE:LINE: ..." for an unknown action or wrong arguments.
std::vector<ReplayAction> parse_replay(const std::string& text, const std::string& file_name);

}  // namespace ipd::studio
