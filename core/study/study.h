// A study on disk: domains with labels, images and model predictions; optional study.yaml and fixed pairs.
//
//   STUDY/study.yaml                                  optional settings (StudyConfig)
//   STUDY/<domain>/labels/<stem>.txt                  GT boxes, YOLO txt
//   STUDY/<domain>/images/<stem>.<png|jpg|...>        optional pictures
//   STUDY/<domain>/predictions/<model>/<stem>.txt     detector output, YOLO txt + confidence
//   STUDY/pairs/<A>__<B>/<stem>.json                  fixed rock pairs, replacing registration (fixed_pairs.h)
#pragma once

#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/io/label_io.h"
#include "core/registration/registration.h"
#include "core/study/fixed_pairs.h"
#include "core/study/study_classes.h"
#include "core/util/errors.h"

namespace ipd {

struct ModelInfo {
  std::string name;
  std::string trained_on;  // a domain name, or empty when unknown
};

struct StudyConfig {
  // The class every number is about: a class number, kNoClassChosen (refused when the labels hold more than one
  // class) or kAllClasses (study_classes.h); `rock_class` in study.yaml, `--class` on the command line.
  int rock_class = -1;
  std::vector<std::string> class_names;  // study.yaml's `classes`, by class number; empty when not given
  std::string rock_class_word;           // `rock_class: rock` (a name), resolved once the classes are read
  int rock_class_line = 0;
  double conf_threshold = 0;  // predictions below this are dropped
  // What a performance value is: a box's IoU (detect, the paper) or an outline's mask IoU (segment);
  // `task` in study.yaml, `--task` on the command line.
  Task task = Task::kDetect;
  int image_width = 0, image_height = 0;  // for labels-only studies; 0 when unknown
  std::vector<std::string> domain_order;  // optional preferred order
  // study.yaml's `domains:` as a mapping: each domain's numbers (`params: {w: 0.30}`), by name in the file's
  // order, e.g. the renderer setting a variant was rendered with (ipd rank, ipd figure sweep). A domain given no
  // params, or the list form, has none.
  std::map<std::string, std::vector<std::pair<std::string, double>>> domain_params;
  std::map<std::string, std::string> trained_on;  // model -> domain
  RegistrationOptions registration;
};

// Parses study.yaml text; throws StudyError naming the file (and line when known).
StudyConfig parse_study_config(const std::string& yaml_text, const std::string& file_name);

struct Domain {
  std::string name;
  std::string dir;
  std::vector<std::string> stems;             // sorted; scenes with labels or images
  std::map<std::string, std::string> images;  // stem -> picture path
  std::vector<std::string> models;            // prediction sets present
};

struct Study {
  std::string root;
  StudyConfig config;
  std::vector<Domain> domains;
  std::vector<ModelInfo> models;  // union over domains and config, sorted by training-domain order
  StudyClasses classes;           // the class names and each label set's numbering (study_classes.h)

  const Domain* domain(const std::string& name) const;
  // The domain `name`, or a StudyError that lists the study's domains: "ROOT: no domain 'reel' in this study
  // (ROLE; the study's domains: real, principled)", ROLE (the option that named it) left out when null.
  const Domain& require_domain(const std::string& name, const char* role = nullptr) const;
  std::string domain_names() const;  // "real, principled, hapke" (each quoted when it needs to be)
  std::string label_path(const std::string& domain, const std::string& stem) const;
  std::string prediction_path(const std::string& domain, const std::string& model, const std::string& stem) const;
  // The folders those files are in, and the file of a stem in one: label_path(d, s) is
  // label_file(label_folder(d), s). A study's 120,000 paths are built from 12 folders.
  std::string label_folder(const std::string& domain) const;
  std::string prediction_folder(const std::string& domain, const std::string& model) const;
  static std::string label_file(const std::string& folder, const std::string& stem);
  std::string pairs_dir(const std::string& a, const std::string& b) const;  // in the A__B order given
  double aspect() const;                                                    // image width / height for registration
};

// Scans a study directory; throws StudyError when it is missing, unreadable or has no domains.
Study open_study(const std::string& root);

// JSON output holds only UTF-8 text: throws StudyError naming the first domain directory, prediction set,
// label or picture file (or study.yaml model) whose name is not UTF-8, before any JSON is written.
void require_utf8_names(const Study& study);

// Scene stems present in both domains, and those only in one (for reporting).
struct SceneMatch {
  std::vector<std::string> common, only_a, only_b;
};
SceneMatch match_scenes(const Domain& a, const Domain& b);

// Read caps: what a real file of each kind needs, with room to spare; a larger file is refused with its size
// and the limit (never read into memory). A pairs file of a 20,000-rock scene is under 2 MB and its JSON
// document takes about 25 times its size while parsed, so 8 MB bounds that at ~200 MB; study.yaml is a few KB.
constexpr size_t kMaxPairsFileBytes = size_t{8} << 20;
// And at most this many JSON values (parse_json_input): a scene's hand pairs take 15 values a pair (66,000 pairs),
// a review check 13. It bounds the parsed document at about 85 MB whatever the file holds (8 MB of `{}` would
// be 2.7 million empty objects, 216 MB).
constexpr size_t kMaxHandWorkJsonValues = 1'000'000;
// A study holds at most this many domains: every pair of them is compared (4,950 pairs at the limit); more is
// refused when the study is opened, naming the count and the limit.
constexpr size_t kMaxDomains = 100;
constexpr size_t kMaxStudyYamlBytes = size_t{1} << 20;

}  // namespace ipd
